#!/bin/bash
# Submits the rscene-sim job array over a list of scenes.
#
#   submit.sh LIST OUT [SBATCH_OPTION...]
#
# LIST holds one scene path a line; OUT is the results folder (see
# sim-array.sh).  The options go to sbatch as they are (--wait,
# --partition=..., --test-only).  With --wait it exits 1 when a task
# failed or did not run (rerun-failed.sh --check), 0 when all are ok.  It
# records LIST, CHUNK, DURATION and RSCENE_SIM in OUT/batch, which
# rerun-failed.sh and summarize.sh read, so that a task number keeps
# naming the same scenes and a rerun simulates them as the first run did.
#
# CHUNK (scenes per task) defaults to as few as keep the array within
# 1,000 tasks: 1 for up to 1,000 scenes, 100 for 100,000.  THROTTLE=N
# lets at most N tasks run at once (--array=...%N).  Refused (exit 2):
# an empty list, a line that names no readable file, carriage returns
# (a list written on Windows), two scenes of one file name (their results
# would share OUT/scenes/STEM.rscene), or more tasks than the cluster's
# MaxArraySize.
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
! grep -q $'\r' "$list" || die "$list has carriage returns (Windows line ends): convert it first, e.g. sed -i 's/\\r\$//' $list"
missing=$(while IFS= read -r f; do [ -r "$f" ] || printf '%s\n' "$f"; done < "$list")
[ -z "$missing" ] || die "$list names $(grep -c . <<<"$missing") scene(s) that cannot be read, such as: $(head -n 3 <<<"$missing" | tr '\n' ' ')"
dup=$(sed -e 's|.*/||' -e 's|\.rscene$||' "$list" | sort | uniq -d | head -n 3)
[ -z "$dup" ] || die "$list names more than one scene called: $(tr '\n' ' ' <<<"$dup")"

chunk=${CHUNK:-$(((n + 999) / 1000))}
# The run's settings, recorded in OUT/batch: a rerun of a failed task
# simulates as the first run did.
duration=${DURATION:-2}
sim=${RSCENE_SIM:-}
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
    printf 'LIST=%q\nCHUNK=%d\nTASKS=%d\nDURATION=%q\nRSCENE_SIM=%q\n' "$list" "$chunk" "$tasks" "$duration" "$sim" > "$out/batch"
    ;;
esac
echo "submit: $n scenes, $tasks tasks of $chunk" >&2
rc=0
sbatch --array="0-$((tasks - 1))${THROTTLE:+%$THROTTLE}" \
  --output="$out/logs/%A_%a.out" --export="ALL,CHUNK=$chunk,DURATION=$duration${sim:+,RSCENE_SIM=$sim}" \
  "$@" "$here/sim-array.sh" "$list" "$out" || rc=$?
case " $* " in
  # sbatch --wait's own status can miss a failed task of an array (one
  # whose record slurmctld dropped, MinJobAge, before the last task
  # ended): the status files tell.
  *" --wait "*) exec "$here/rerun-failed.sh" --check "$out" ;;
esac
exit "$rc"
