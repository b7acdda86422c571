#!/usr/bin/env bash
# bench/sim/run.sh BIN_DIR - rscene-sim against a hand-written Bullet
# program (bench/sim/baseline.cpp) on the same worlds (issue 5, "Speed").
#
# Scenes, generated here, never copied into the repository:
#   pile       1000 boxes falling into a pile on a ground plane
#              (rscene-sim-bench-gen pile; bench/sim/scenes.hpp)
#   warehouse  the ground and static collision boxes of
#              ../shared/corpus/rayrai_warehouse.rscene (its mesh objects,
#              whose assets are not in the corpus, are left out) plus 100
#              dynamic 0.4 m crates dropped onto racks 1 and 2; skipped
#              when the corpus is absent
# Each is simulated for SIM_BENCH_DURATION seconds (default 10) by
# `rscene-sim --duration S --report -o FILE` and by rscene-sim-baseline
# with the same number of steps (which writes its final poses to a file),
# best of SIM_BENCH_REPEAT runs (default 3) for CPU (user+sys) and wall time.
#
# Targets, marked PASS or MISS: rscene-sim's total time <= 1.10 x the
# baseline's (CPU time; wall time printed beside it), and scene loading
# (rscene-sim --report's loadTime: read, parse, scene view, checks, world
# build) under 5% of rscene-sim's wall time.  The final poses of the two
# programs are compared as well: the same world stepped the same way gives
# the same poses, so a large difference means the baseline no longer
# builds what lib/sim builds (the benchmark then exits 1).
#
# Environment:
#   SIM_BENCH_DIR       where scenes and outputs go (default: a temporary
#                       directory, removed)
#   SIM_BENCH_REPEAT    runs per measurement (default 3)
#   SIM_BENCH_DURATION  simulated seconds (default 10)
#   SIM_BENCH_CORPUS    the corpus folder (default: ../shared/corpus beside
#                       the repository)
# Exit status: 0 when every program ran and the poses agree, 1 when one
# failed or the poses disagree, 2 on usage or a missing program.
set -euo pipefail

if [[ $# -ne 1 || ! -d $1 ]]; then
  echo "usage: bench/sim/run.sh BIN_DIR" >&2
  exit 2
fi
BIN=$(cd "$1" && pwd)
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPEAT=${SIM_BENCH_REPEAT:-3}
DURATION=${SIM_BENCH_DURATION:-10}
CORPUS=${SIM_BENCH_CORPUS:-$HERE/../../../shared/corpus}
TIME=/usr/bin/time

for need in "$BIN/rscene-sim" "$BIN/rscene-sim-bench-gen" "$BIN/rscene-sim-baseline" "$TIME"; do
  if [[ ! -x $need ]]; then
    echo "bench/sim/run.sh: error: $need is missing (build it, or install GNU time)" >&2
    exit 2
  fi
done
command -v jq > /dev/null || { echo "bench/sim/run.sh: error: jq is missing" >&2; exit 2; }

if [[ -n ${SIM_BENCH_DIR:-} ]]; then
  DIR=$SIM_BENCH_DIR
  mkdir -p "$DIR"
else
  DIR=$(mktemp -d "${TMPDIR:-/tmp}/rscene-simbench.XXXXXX")
  trap 'rm -rf "$DIR"' EXIT
fi

# measure NAME CMD...: runs CMD REPEAT times; sets BEST_CPU (user+sys s),
# BEST_WALL (s) and, for rscene-sim, REPORT (the --report line of the run
# with the best wall time).
measure() {
  local name=$1 i rc wall cpu
  shift
  BEST_CPU= BEST_WALL= REPORT=
  for ((i = 0; i < REPEAT; i++)); do
    rc=0
    "$TIME" -f '%e %U %S' -o "$DIR/$name.time" "$@" > /dev/null 2> "$DIR/$name.stderr" || rc=$?
    if ((rc != 0)); then
      echo "bench/sim/run.sh: error: '$*' failed with status $rc:" >&2
      sed -n '1,5p' "$DIR/$name.stderr" >&2
      return 1
    fi
    read -r wall cpu < <(tail -n 1 "$DIR/$name.time" | awk '{ print $1, $2 + $3 }')
    if [[ -z $BEST_CPU ]] || awk -v a="$cpu" -v b="$BEST_CPU" 'BEGIN { exit !(a < b) }'; then BEST_CPU=$cpu; fi
    if [[ -z $BEST_WALL ]] || awk -v a="$wall" -v b="$BEST_WALL" 'BEGIN { exit !(a < b) }'; then
      BEST_WALL=$wall
      REPORT=$(grep '^{' "$DIR/$name.stderr" | tail -n 1 || true)
    fi
  done
}

# verdict LABEL VALUE OP LIMIT: prints the line with PASS or MISS.
verdict() {
  local ok
  ok=$(awk -v v="$2" -v l="$4" -v op="$3" 'BEGIN { print (op == "<" ? v < l : v <= l) ? "PASS" : "MISS" }')
  printf '  %-46s %9s  (target %s %s)  %s\n' "$1" "$2" "$3" "$4" "$ok"
}

# poses SCENE: `path x y z qw qx qy qz` of the dynamic boxes in a scene.
poses() { awk '$1 == "object" && $23 == "dynamic" { print $2, $4, $5, $6, $7, $8, $9, $10 }' "$1"; }

# Scene (b)'s table for the baseline: solver settings and bodies in record
# order.  Refuses (exit 1) what the baseline does not map.
table() {
  awk '
    function fail(why) { print "bench/sim/run.sh: error: " FILENAME ":" FNR ": " why > "/dev/stderr"; bad = 1; exit 1 }
    $1 == "time_step" { print "time_step", $2 }
    $1 == "gravity" { print "gravity", $2, $3, $4 }
    $1 == "solver" {
      erp2 = 0; thr = 0.001
      if ($5 ~ /=/) fail("solver without its mode")  # the mode has no Bullet equivalent
      for (i = 6; i <= NF; i++) {
        if ($i ~ /^erp2=/) erp2 = substr($i, 6)
        else if ($i ~ /^defaultRestitutionThreshold=/) thr = substr($i, 29)
        else if ($i !~ /^(defaultStaticFrictionVelocityThreshold|fixedContactSolverIterationOrder)=/)
          fail("solver key " $i " is not mapped by the baseline")
      }
      print "solver", $2, $3, $4, erp2, thr
    }
    $1 == "object" {
      if (NF != 26) fail("object with keys or an old layout")
      if ($24 != "true" || $19 != "false") fail("object that is not collidable")
      if ($3 == "ground") print "ground", $2, $6
      else if ($3 == "box" && ($23 == "static" || $23 == "dynamic"))
        print "box", $2, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $16, $23, $25, $26
      else fail("object the baseline does not map")
    }
    END { exit bad }' "$1"
}

status=0
echo "rscene-sim benchmark: $(uname -m), $(nproc) cores, ${DURATION} s simulated, best of $REPEAT runs"
echo "scenes in $DIR"
echo
echo "sim = rscene-sim, base = rscene-sim-baseline; ratios sim/base; load = loadTime / wallTime of rscene-sim"
printf '%-10s %6s %6s  %9s %9s  %10s %9s  %9s %10s %9s %9s\n' scene bodies steps "sim CPU s" "sim wall" \
  "base CPU s" "base wall" "CPU ratio" "wall ratio" "load" "pose diff"

declare -a RESULTS

# bench NAME SCENE BASELINE_ARGS...: one row.
bench() {
  local name=$1 scene=$2
  shift 2
  local sim_cpu sim_wall base_cpu base_wall steps load wall share diff bodies report
  if ! measure "$name.sim" "$BIN/rscene-sim" --duration "$DURATION" --report -o "$DIR/$name.out.rscene" "$scene"; then
    status=1
    return
  fi
  sim_cpu=$BEST_CPU sim_wall=$BEST_WALL report=$REPORT
  steps=$(jq -r .steps <<< "$report")
  load=$(jq -r .loadTime <<< "$report")
  wall=$(jq -r .wallTime <<< "$report")
  bodies=$(jq -r .bodies <<< "$report")
  if ! measure "$name.base" "$BIN/rscene-sim-baseline" "$@" --steps "$steps" -o "$DIR/$name.base.txt"; then
    status=1
    return
  fi
  base_cpu=$BEST_CPU base_wall=$BEST_WALL
  share=$(awk -v l="$load" -v w="$wall" 'BEGIN { printf "%.2f", 100 * l / w }')
  # Largest difference of any pose component between the two programs.
  diff=$(poses "$DIR/$name.out.rscene" | awk 'NR == FNR { p[$1] = $0; next }
    { if (!($1 in p)) { missing++; next } split(p[$1], a, " "); n++
      for (i = 2; i <= 8; i++) { d = a[i] - $i; if (d < 0) d = -d; if (d > m) m = d } }
    END { if (missing || n == 0) print "missing"; else printf "%.1e", m }' - "$DIR/$name.base.txt")
  printf '%-10s %6s %6s  %9.2f %9.2f  %10.2f %9.2f  %9.3f %10.3f %8s%% %9s\n' "$name" "$bodies" "$steps" \
    "$sim_cpu" "$sim_wall" "$base_cpu" "$base_wall" \
    "$(awk -v a="$sim_cpu" -v b="$base_cpu" 'BEGIN { print a / b }')" \
    "$(awk -v a="$sim_wall" -v b="$base_wall" 'BEGIN { print a / b }')" "$share" "$diff"
  RESULTS+=("$name|$sim_cpu|$base_cpu|$share|$diff|$(jq -c '{parseTime, buildTime, stepTime, writeTime}' <<< "$report")")
}

"$BIN/rscene-sim-bench-gen" pile > "$DIR/pile.rscene"
bench pile "$DIR/pile.rscene" pile

WAREHOUSE=$CORPUS/rayrai_warehouse.rscene
if [[ -r $WAREHOUSE ]]; then
  # Racks 1 and 2 stand back to back at y = -11.3 and -9.9, x from -27 to 7,
  # beams up to z = 7.2: the crates start above the top beams.
  awk '$1 == "raisim_engine_scene" || $1 == "time_step" || $1 == "gravity" || $1 == "solver" ||
       ($1 == "object" && ($3 == "ground" || $3 == "box"))' "$WAREHOUSE" > "$DIR/warehouse.rscene"
  "$BIN/rscene-sim-bench-gen" crates --count 100 --at -20 -10.6 8.5 >> "$DIR/warehouse.rscene"
  if table "$DIR/warehouse.rscene" > "$DIR/warehouse.table"; then
    bench warehouse "$DIR/warehouse.rscene" table "$DIR/warehouse.table"
  else
    status=1
  fi
else
  echo "warehouse: skipped ($WAREHOUSE is absent)"
fi

echo
echo "targets (issue 5, rscene-sim against the hand-written program, load/step/write included):"
for r in "${RESULTS[@]}"; do
  IFS='|' read -r name sim_cpu base_cpu share diff parts <<< "$r"
  verdict "$name: CPU time rscene-sim / baseline" "$(awk -v a="$sim_cpu" -v b="$base_cpu" 'BEGIN { printf "%.3f", a / b }')" "<=" 1.10
  verdict "$name: scene loading share of the total (%)" "$share" "<" 5
  echo "    rscene-sim breakdown (s): $parts"
  if [[ $diff == missing ]] || awk -v d="$diff" 'BEGIN { exit !(d > 1e-6) }'; then
    echo "    final poses differ from the baseline's by $diff: the two programs do not build the same world" >&2
    status=1
  else
    echo "    final poses agree with the baseline's within $diff m (same world, same steps)"
  fi
done
exit $status
