#!/usr/bin/env bash
# bench/batch/sim.sh BIN_DIR - "Batches of scenes": 500 small scenes (a few
# boxes dropped on a ground each, 0.5 s at 1 ms steps) simulated by one
# `rscene-sim -o 'out/{stem}.rscene' DIR/` against 500 rscene-sim
# processes, one per scene (a shell loop).  CPU time (user + system, the
# loop's children included), best of BENCH_BATCH_REPEAT runs each; the
# target is one process taking at most 0.5 of the loop's time.  The
# outputs of the two are compared too (a batch must write what single runs
# write).
#
# Environment:
#   BENCH_BATCH_SCENES  scenes (default 500)
#   BENCH_BATCH_REPEAT  runs of each, best kept (default 3)
# Exit status: 0 when it ran (PASS or MISS is printed, never an error),
# 1 when rscene-sim failed or the outputs differ, 2 on usage.
set -euo pipefail

if [[ $# -ne 1 || ! -d $1 ]]; then
  echo "usage: bench/batch/sim.sh BIN_DIR" >&2
  exit 2
fi
BIN=$(cd "$1" && pwd)
N=${BENCH_BATCH_SCENES:-500}
REPEAT=${BENCH_BATCH_REPEAT:-3}
TIME=/usr/bin/time
if [[ ! -x $BIN/rscene-sim || ! -x $TIME ]]; then
  echo "bench/batch/sim.sh: $BIN/rscene-sim or $TIME is missing; skipped"
  exit 0
fi
DIR=$(mktemp -d "${TMPDIR:-/tmp}/rscene-batch.XXXXXX")
trap 'rm -rf "$DIR"' EXIT

# The scenes: a ground and three boxes, each scene's boxes placed apart.
mkdir -p "$DIR/scenes" "$DIR/batch" "$DIR/single"
for ((i = 0; i < N; i++)); do
  printf -v name 'scene%04d' "$i"
  {
    printf 'raisim_engine_scene 1\ntime_step 0.001\ngravity 0 0 -9.81\n'
    printf 'object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615\n'
    for b in 0 1 2; do
      printf 'object /World/Box%d box %d.%d 0 %d.%02d 1 0 0 0 0.4 0.4 0.4 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615\n' \
        "$b" "$b" "$((i % 10))" "$((b + 1))" "$((i % 100))"
    done
  } > "$DIR/scenes/$name.rscene"
done

# cpu CMD...: runs CMD REPEAT times; sets CPU to the best user+system seconds.
cpu() {
  CPU=
  local k c
  for ((k = 0; k < REPEAT; k++)); do
    if ! "$TIME" -f '%U %S' -o "$DIR/cpu" "$@" > /dev/null 2> "$DIR/stderr"; then
      echo "bench/batch/sim.sh: error: '$*' failed:" >&2
      sed -n '1,5p' "$DIR/stderr" >&2
      return 1
    fi
    c=$(tail -n 1 "$DIR/cpu" | awk '{ printf "%.3f", $1 + $2 }')
    if [[ -z $CPU ]] || awk -v a="$c" -v b="$CPU" 'BEGIN { exit !(a < b) }'; then CPU=$c; fi
  done
}

echo "batches of scenes: $N small scenes (3 boxes on a ground, 0.5 s at 1 ms steps), CPU seconds, best of $REPEAT"
cpu "$BIN/rscene-sim" --duration 0.5 -o "$DIR/batch/{stem}.rscene" "$DIR/scenes/" || exit 1
batch=$CPU
# shellcheck disable=SC2016  # expanded by the inner shell
cpu bash -c 'for f in "$2"/scenes/*.rscene; do
  n=${f##*/}; "$1" --duration 0.5 -o "$2/single/$n" "$f" || exit 1
done' loop "$BIN/rscene-sim" "$DIR" || exit 1
single=$CPU
if ! diff -rq "$DIR/batch" "$DIR/single" > /dev/null; then
  echo "bench/batch/sim.sh: error: the batch's outputs differ from single runs'" >&2
  exit 1
fi
ratio=$(awk -v a="$batch" -v b="$single" 'BEGIN { printf "%.3f", (b > 0) ? a / b : 0 }')
verdict=$(awk -v r="$ratio" 'BEGIN { print (r <= 0.5 ? "PASS" : "MISS") }')
echo "  one process ($N scenes):   $batch s"
echo "  $N processes:              $single s"
echo "  one process / $N processes: $ratio (target <= 0.5) $verdict"
