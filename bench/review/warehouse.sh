#!/usr/bin/env bash
# bench/review/warehouse.sh BIN_DIR - "rscene-diff --review" (issue 27):
# the review of the corpus warehouse with one crate moved 10 cm (two
# renders, their id passes, changes.png, review.md and index.html) against
# one `rscene-render` of the same scene; the target is at most 2x.  Wall
# time and CPU time (user + system), best of BENCH_REVIEW_REPEAT runs each.
# The corpus's meshes are not in it: both draw placeholders.
#
# Environment:
#   BENCH_REVIEW_REPEAT  runs of each, best kept (default 3)
# Exit status: 0 when it ran (PASS or MISS is printed), 1 when a tool
# failed, 2 on usage.
set -euo pipefail

if [[ $# -ne 1 || ! -d $1 ]]; then
  echo "usage: bench/review/warehouse.sh BIN_DIR" >&2
  exit 2
fi
BIN=$(cd "$1" && pwd)
REPEAT=${BENCH_REVIEW_REPEAT:-3}
TIME=/usr/bin/time
SCENE="$(dirname "$0")/../../../shared/corpus/rayrai_warehouse.rscene"
for f in "$BIN/rscene-render" "$BIN/rscene-diff" "$TIME" "$SCENE"; do
  [[ -e $f ]] || { echo "bench/review/warehouse.sh: $f is missing; skipped"; exit 0; }
done
"$BIN/rscene-diff" --help | grep -q -- --review || { echo "rscene-diff has no --review; skipped"; exit 0; }
DIR=$(mktemp -d "${TMPDIR:-/tmp}/rscene-review.XXXXXX")
trap 'rm -rf "$DIR"' EXIT
cp "$SCENE" "$DIR/old.rscene"
sed 's|^object /World/Props/Crate_0 mesh 4.6 1.55|object /World/Props/Crate_0 mesh 4.7 1.55|' "$SCENE" > "$DIR/new.rscene"
cmp -s "$DIR/old.rscene" "$DIR/new.rscene" && { echo "the crate was not found"; exit 1; }

# best CMD...: the best wall and CPU seconds of REPEAT runs, as "WALL CPU".
best() {
  local wall=999999 cpu=999999 w c i
  for ((i = 0; i < REPEAT; i++)); do
    read -r w c < <({ "$TIME" -f '%e %U %S' "$@" 2>&1 >/dev/null | tail -n 1; } | awk '{ print $1, $2 + $3 }')
    wall=$(awk -v a="$wall" -v b="$w" 'BEGIN { print (b < a ? b : a) }')
    cpu=$(awk -v a="$cpu" -v b="$c" 'BEGIN { print (b < a ? b : a) }')
  done
  echo "$wall $cpu"
}
cd "$DIR"
"$BIN/rscene-render" new.rscene -o one.png --allow-missing-assets 2>/dev/null || { echo "rscene-render failed"; exit 1; }
rc=0
"$BIN/rscene-diff" -q --review review old.rscene new.rscene 2>/dev/null || rc=$?
[[ $rc -eq 1 ]] || { echo "rscene-diff --review exited $rc, expected 1"; exit 1; }
read -r rw rc_ < <(best "$BIN/rscene-render" new.rscene -o one.png --allow-missing-assets)
read -r vw vc < <(best "$BIN/rscene-diff" -q --review review old.rscene new.rscene)
ratio=$(awk -v a="$vw" -v b="$rw" 'BEGIN { printf "%.2f", a / b }')
cratio=$(awk -v a="$vc" -v b="$rc_" 'BEGIN { printf "%.2f", a / b }')
verdict=$(awk -v r="$ratio" 'BEGIN { print (r <= 2 ? "PASS" : "MISS") }')
echo "review of the warehouse: ${vw} s wall, ${vc} s CPU; one render: ${rw} s wall, ${rc_} s CPU;" \
  "ratio ${ratio} wall, ${cratio} CPU (target <= 2): $verdict"
