#!/bin/bash
# Gathers every scene's record of a job array (OUT/reports/*.json, see
# sim-array.sh) into one file, in the order of the scene list:
#
#   summarize.sh OUT               # JSON Lines on standard output
#   summarize.sh OUT FILE.jsonl    # JSON Lines
#   summarize.sh OUT FILE.csv      # CSV
#
# One line (row) per scene of the list.  A scene with no record yet (its
# task has not run, or lost its node) is listed with exit null and error
# "not run".  JSON Lines keep each record whole: scene, output, task, job,
# exit, error, and report (rscene-sim's --report object, null for a
# failed run).  CSV has the columns scene,output,task,job,exit,error and
# then report.KEY for every value of the report (nested ones as
# report.granular.contacts), empty where the run has no report.  FILE is
# written atomically.  Exit status: 0 when every scene's run succeeded,
# 1 when some failed or did not run, 2 on a usage or I/O error.
set -euo pipefail

die() { echo "summarize: $*" >&2; exit 2; }
[ $# -eq 1 ] || [ $# -eq 2 ] || die "usage: summarize.sh OUT [FILE.jsonl|FILE.csv]"
out=$1 file=${2:-}
[ -r "$out/batch" ] || die "no $out/batch: submit the batch with submit.sh"
LIST="" CHUNK=""
# shellcheck source=/dev/null
. "$out/batch"
[ -r "$LIST" ] || die "cannot read $LIST"

tmp=$(mktemp -d "${TMPDIR:-/tmp}/rscene-summary.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# The records in list order; awk reads each report itself (no process per
# scene, for 100,000 of them).
awk -v dir="$out/reports" -v chunk="$CHUNK" '
  function esc(s) { gsub(/\\/, "\\\\", s); gsub(/"/, "\\\"", s); gsub(/\t/, "\\t", s); return s }
  {
    stem = $0; sub(/.*\//, "", stem); sub(/\.rscene$/, "", stem)
    f = dir "/" stem ".json"; line = ""
    if ((getline line < f) > 0) print line
    else printf "{\"scene\":\"%s\",\"output\":null,\"task\":%d,\"job\":null,\"exit\":null,\"error\":\"not run\",\"report\":null}\n", esc($0), int((NR - 1) / chunk)
    close(f)
  }' "$LIST" | jq -c . > "$tmp/all.jsonl" || die "a report in $out/reports is not JSON"

case $file in
  *.csv)
    # The report's columns: every scalar path of the first report found.
    cols=$(jq -cn 'first(inputs | select(.report != null) | [.report | paths(type != "object" and type != "array")])' "$tmp/all.jsonl")
    jq -rn --argjson cols "${cols:-[]}" '
      (["scene", "output", "task", "job", "exit", "error"]
        + [$cols[] | "report." + (map(tostring) | join("."))] | @csv),
      (inputs | .report as $r
        | [.scene, .output, .task, .job, .exit, .error]
          + [$cols[] as $p | if $r == null then null else ($r | getpath($p)) end]
        | @csv)' "$tmp/all.jsonl" > "$tmp/summary"
    ;;
  *) cp "$tmp/all.jsonl" "$tmp/summary" ;;
esac

if [ -z "$file" ]; then
  cat "$tmp/summary"
else
  t="$(dirname "$file")/.$(basename "$file").$$"
  if ! { cp "$tmp/summary" "$t" && mv -f "$t" "$file"; }; then
    rm -f "$t"
    die "cannot write $file"
  fi
fi
bad=$(jq -n 'reduce inputs as $r (0; . + (if $r.exit == 0 then 0 else 1 end))' "$tmp/all.jsonl")
total=$(wc -l < "$tmp/all.jsonl")
echo "summarize: $total scenes, $((total - bad)) ok, $bad failed or not run" >&2
[ "$bad" -eq 0 ]
