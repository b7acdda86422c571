#!/bin/bash
# Resubmits only the tasks of a finished job array that did not end
# well: those whose OUT/status/T is missing (the task never ran, was
# cancelled, hit its time limit or lost its node) or says "failed".
#
#   rerun-failed.sh OUT [SBATCH_OPTION...]
#   rerun-failed.sh --check OUT    # only lists them: exit 1 when any
#
# Run it once the array has ended (`sbatch --wait`, or squeue shows none
# of its tasks): a task still queued or running has no status yet and
# would be submitted twice.  It reuses the LIST, CHUNK, DURATION and
# RSCENE_SIM that submit.sh
# recorded in OUT/batch, so each task number names the same scenes and
# is simulated as before (a different DURATION or RSCENE_SIM in the
# environment is refused); a
# rerun task simulates again only its scenes without a good result
# (sim-array.sh), after you have mended them or their inputs.  Prints
# the --array it submits; exits 0 without submitting when every task is
# ok.  With --wait among the options it waits for the rerun and exits 1
# when a task still failed.  (`sacct -j JOB --state=FAILED` lists the
# same tasks where the cluster keeps accounting; the status files work
# without it.)
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
die() { echo "rerun-failed: $*" >&2; exit 2; }
check=false
[ "${1:-}" != --check ] || { check=true; shift; }
[ $# -ge 1 ] || die "usage: rerun-failed.sh [--check] OUT [SBATCH_OPTION...]"
out=$(cd "$1" && pwd) || die "no folder $1"
shift
[ -r "$out/batch" ] || die "no $out/batch: submit the batch with submit.sh"
given_duration=${DURATION-} given_sim=${RSCENE_SIM-}
LIST="" CHUNK="" TASKS="" DURATION="" RSCENE_SIM=""
# shellcheck source=/dev/null
. "$out/batch"
# A rerun simulates as the first run did (its settings are in OUT/batch);
# a different setting in the environment would mix two runs in one batch.
[ -z "$DURATION" ] || [ -z "$given_duration" ] || [ "$given_duration" = "$DURATION" ] ||
  die "the batch ran with DURATION=$DURATION, the environment says $given_duration: unset it, or submit a new batch"
[ -z "$given_sim" ] || [ "$given_sim" = "$RSCENE_SIM" ] ||
  die "the batch ran with RSCENE_SIM=${RSCENE_SIM:-(rscene-sim on PATH)}, the environment says $given_sim: unset it, or submit a new batch"

failed=()
for ((t = 0; t < TASKS; t++)); do
  s=""
  [ ! -r "$out/status/$t" ] || read -r s < "$out/status/$t" || true
  [[ $s == "ok "* ]] || failed+=("$t")
done
if [ "${#failed[@]}" -eq 0 ]; then
  echo "batch $out: all $TASKS tasks ok" >&2
  exit 0
fi
# 3,4,5,9 -> 3-5,9
array=$(printf '%s\n' "${failed[@]}" | awk '
  NR == 1 { a = b = $1; next }
  $1 == b + 1 { b = $1; next }
  { s = s (s == "" ? "" : ",") (a == b ? a : a "-" b); a = b = $1 }
  END { s = s (s == "" ? "" : ",") (a == b ? a : a "-" b); print s }')
if $check; then
  # (also what submit.sh --wait ends with: said as the batch's state, not
  # as a rerun)
  echo "batch $out: ${#failed[@]} of $TASKS tasks failed or did not run (task numbers $array); rerun them with: $here/rerun-failed.sh $out" >&2
  exit 1
fi
echo "rerun-failed: resubmitting task numbers $array (--array=$array${THROTTLE:+%$THROTTLE})" >&2
rc=0
sbatch --array="$array${THROTTLE:+%$THROTTLE}" \
  --output="$out/logs/%A_%a.out" --export="ALL,CHUNK=$CHUNK${DURATION:+,DURATION=$DURATION}${RSCENE_SIM:+,RSCENE_SIM=$RSCENE_SIM}" \
  "$@" "$here/sim-array.sh" "$LIST" "$out" || rc=$?
case " $* " in
  # sbatch --wait's own status can miss a failed task of an array (one
  # whose record slurmctld dropped, MinJobAge, before the last task
  # ended): the status files tell.
  *" --wait "*) exec "$0" --check "$out" ;;
esac
exit "$rc"
