#!/bin/bash
#SBATCH --job-name=rscene-sim
#SBATCH --cpus-per-task=1
#SBATCH --mem-per-cpu=1G
#SBATCH --time=04:00:00
# One task of the rscene-sim job array (README: "Large batches on a
# cluster").  Submit it with submit.sh, which works out --array, --output
# and the environment below; by hand:
#
#   sbatch --array=0-999 --output=OUT/logs/%A_%a.out \
#     --export=ALL,CHUNK=100 sim-array.sh LIST OUT
#
# LIST: the scenes, one path a line (absolute, or relative to the folder
# sbatch ran in).  Task T (SLURM_ARRAY_TASK_ID, from 0) simulates lines
# T*CHUNK+1 .. (T+1)*CHUNK of LIST, so 100,000 scenes are 1,000 tasks of
# 100, within Slurm's default MaxArraySize (1001).  Each scene
# DIR/STEM.rscene gives:
#   OUT/scenes/STEM.rscene   the simulated scene (rscene-sim -o: atomic);
#   OUT/reports/STEM.json    one JSON line: scene, output, task, job,
#                            exit (rscene-sim's status), error (null, or
#                            the first diagnostic of a failed run), report
#                            (its --report JSON, null when it failed);
# and the task writes OUT/status/T: "ok N" or "failed K of N" (K scenes
# failed).  Report and status files are written to a temporary file in
# their folder and renamed, so a reader sees a whole file or none.
#
# Every scene of the chunk is simulated even when one fails; the task
# then exits 1, so Slurm marks it FAILED and the other tasks' results
# stand.  A scene whose report says exit 0 and whose output is newer than
# the scene is not simulated again: a rerun of a task (rerun-failed.sh)
# redoes only what is missing or failed.
#
# Environment: CHUNK (scenes per task, default 100), DURATION (simulated
# seconds, default 2), RSCENE_SIM (the rscene-sim to run, default the one
# on PATH).
set -uo pipefail

if [ $# -ne 2 ] || [ -z "${SLURM_ARRAY_TASK_ID:-}" ]; then
  echo "usage: sbatch --array=... sim-array.sh LIST OUT" >&2
  exit 2
fi
list=$1 out=$2
chunk=${CHUNK:-100}
duration=${DURATION:-2}
sim=${RSCENE_SIM:-rscene-sim}
task=$SLURM_ARRAY_TASK_ID
job="${SLURM_ARRAY_JOB_ID:-${SLURM_JOB_ID:-0}}_$task"
[ -r "$list" ] || { echo "sim-array: cannot read $list" >&2; exit 2; }
mkdir -p "$out/scenes" "$out/reports" "$out/status" || exit 2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/rscene-task.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT

# put FILE: standard input to FILE, atomically (a temporary file beside
# it, named for this host and process, then a rename).
put() {
  local t
  t="$(dirname "$1")/.$(basename "$1").${HOSTNAME:-host}.$$"
  if ! { cat > "$t" && mv -f "$t" "$1"; }; then
    rm -f "$t"
    return 1
  fi
}

first=$((task * chunk + 1))
last=$((first + chunk - 1))
mapfile -t scenes < <(sed -n "${first},${last}p;${last}q" "$list")
[ "${#scenes[@]}" -gt 0 ] || { echo "sim-array: task $task: no lines $first-$last in $list" >&2; exit 2; }

failed=0
for scene in "${scenes[@]}"; do
  stem=${scene##*/}
  stem=${stem%.rscene}
  output="$out/scenes/$stem.rscene"
  report="$out/reports/$stem.json"
  if [ "$output" -nt "$scene" ] && [ -s "$report" ] && [ "$(jq -r .exit "$report" 2>/dev/null)" = 0 ]; then
    continue  # done by an earlier run of this task
  fi
  # The simulation of one scene.  With a multi-scene rscene-sim this loop
  # becomes one call over "${scenes[@]}" with -o "$out/scenes/{stem}.rscene".
  "$sim" --duration "$duration" --report -o "$output" "$scene" 2> "$tmp/stderr"
  rc=$?
  [ "$rc" -eq 0 ] || failed=$((failed + 1))
  [ "$rc" -eq 0 ] || cat "$tmp/stderr" >&2  # the task's log keeps the whole message
  # One record.  --report's JSON is the last line of standard error;
  # diagnostics (warnings, or the error of a failed run) come before it.
  # error: a failed run's first diagnostic, else its last line (a crash,
  # a missing tool).
  jq -cn --arg scene "$scene" --arg output "$output" --argjson task "$task" \
    --arg job "$job" --argjson exit "$rc" --rawfile stderr "$tmp/stderr" '
    ($stderr | split("\n") | map(select(length > 0))) as $lines
    | {scene: $scene, output: (if $exit == 0 then $output else null end), task: $task, job: $job,
       exit: $exit,
       error: (if $exit == 0 then null
               else (first($lines[] | select(contains(": error: "))) // $lines[-1] // "exit status \($exit)") end),
       report: ($lines[-1] // "" | (try fromjson catch null) | if type == "object" then . else null end)}' |
    put "$report" || exit 2
done

if [ "$failed" -eq 0 ]; then
  echo "ok ${#scenes[@]}" | put "$out/status/$task"
else
  echo "failed $failed of ${#scenes[@]}" | put "$out/status/$task"
  echo "sim-array: task $task: $failed of ${#scenes[@]} scenes failed" >&2
  exit 1
fi
