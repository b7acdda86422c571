#!/bin/bash
# Submits the rscene-sim job array over a list of scenes.
#
#   submit.sh LIST OUT [SBATCH_OPTION...]
#
# LIST holds one scene path a line; OUT is the results folder (see
# sim-array.sh).  The options go to sbatch as they are (--wait,
# --partition=..., --test-only).  With --wait it exits 1 when a task
# failed or did not run (rerun-failed.sh --check), 0 when all are ok.  It records LIST and CHUNK in OUT/batch,
# which rerun-failed.sh and summarize.sh read, so that a task number keeps
# naming the same scenes.
#
# CHUNK (scenes per task) defaults to as few as keep the array within
# 1,000 tasks: 1 for up to 1,000 scenes, 100 for 100,000.  THROTTLE=N
# lets at most N tasks run at once (--array=...%N).  Refused (exit 2):
# an empty list, two scenes of one file name (their results would share
# OUT/scenes/STEM.rscene), or more tasks than the cluster's MaxArraySize.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
die() { echo "submit: $*" >&2; exit 2; }
[ $# -ge 2 ] || die "usage: submit.sh LIST OUT [SBATCH_OPTION...]"
list=$1 out=$2
shift 2
[ -r "$list" ] || die "cannot read $list"
list=$(cd "$(dirname "$list")" && pwd)/$(basename "$list")

n=$(grep -c . "$list" || true)
[ "$n" -gt 0 ] || die "$list lists no scene"
[ "$(grep -c . "$list")" -eq "$(wc -l < "$list")" ] || die "$list has an empty line"
dup=$(sed -e 's|.*/||' -e 's|\.rscene$||' "$list" | sort | uniq -d | head -n 3)
[ -z "$dup" ] || die "$list names more than one scene called: $(tr '\n' ' ' <<<"$dup")"

chunk=${CHUNK:-$(((n + 999) / 1000))}
tasks=$(((n + chunk - 1) / chunk))
max=$(scontrol show config 2>/dev/null | awk '$1 == "MaxArraySize" { print $3 }')
max=${max:-1001}
[ "$tasks" -le "$((max - 1))" ] ||
  die "$n scenes in chunks of $chunk are $tasks tasks, over the cluster's MaxArraySize ($max): raise CHUNK"

mkdir -p "$out/logs"
out=$(cd "$out" && pwd)
# A fresh batch: no task's status from an earlier one (with another list
# or chunk) may pass for this one's.  sbatch --test-only submits nothing,
# so it changes nothing here either.
case " $* " in
  *" --test-only "*) ;;
  *)
    rm -rf "$out/status"
    printf 'LIST=%q\nCHUNK=%d\nTASKS=%d\n' "$list" "$chunk" "$tasks" > "$out/batch"
    ;;
esac
echo "submit: $n scenes, $tasks tasks of $chunk" >&2
rc=0
sbatch --array="0-$((tasks - 1))${THROTTLE:+%$THROTTLE}" \
  --output="$out/logs/%A_%a.out" --export="ALL,CHUNK=$chunk" \
  "$@" "$here/sim-array.sh" "$list" "$out" || rc=$?
case " $* " in
  # sbatch --wait's own status can miss a failed task of an array (one
  # whose record slurmctld dropped, MinJobAge, before the last task
  # ended): the status files tell.
  *" --wait "*) exec "$here/rerun-failed.sh" --check "$out" ;;
esac
exit "$rc"
