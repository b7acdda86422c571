#!/usr/bin/env bash
# bench/robot/run.sh BIN_DIR - robots (issues 11 and 26, "Speed"): rscene-sim
# against MuJoCo 2.2.2 on the same robot, pose, PD gains and time step, side
# by side in one run, the time to load the robot, and what the feet did.
#
# Worlds, written by rscene-robot-bench-mujoco (bench/robot/mujoco.cpp) for
# both programs from one description, never copied into the repository:
#   anymal     ANYmal C (../shared/corpus/robots/anymal_c) in its standing
#              pose on a ground plane, held by PD toward that pose
#   anymal16   16 of them, 1.5 m apart, on a 12 x 12 m height field
#   anymal64   64 of them on the same height field (how cost grows with
#              robots; one run of each, no feet: MuJoCo takes about 15 CPU s
#              for it; ROBOT_BENCH_64=0 leaves it out)
# Each is simulated for ROBOT_BENCH_DURATION seconds (default 10) at dt
# 0.0025 s, best of ROBOT_BENCH_REPEAT runs (default 3) by CPU time.
# MuJoCo's figures are its stepping alone (compile excluded); rscene-sim's
# are its --report stepCpuTime and stepTime (stepping alone) and, beside
# them, its load time and the whole process's CPU time.  Both hold every
# joint toward its initial position with the gains ROBOT_BENCH_GAINS
# (default 400,10: ANYmal C sags under 6 cm in MuJoCo with them; 100,2
# lets it sink onto its knees in 10 s): MuJoCo with explicit torques
# kp (q* - q) - kd qdot, rscene-sim with its --pd-gains (its own
# integration of the same law).
#
# Targets, marked PASS or MISS (issue 26): rscene-sim's steps per CPU
# second of stepping at least MuJoCo's (the CPU ratio, MuJoCo's stepping
# CPU s over rscene-sim's) for one ANYmal and for 16; CPU time, because a
# loaded machine moves it far less than wall time.  Printed beside it:
# the ratio against rscene-sim's whole process (load and write included)
# and the wall-time ratio of stepping alone; for 64 ANYmals the ratio and
# the cost per robot step of both against 16 (no target).  Loading the
# robot under 0.3 s (rscene-sim's loadTime: scene, URDF, world build;
# rscene-render's scene build, which reads the visual meshes, is printed
# when rscene-render is built).  Until rscene-sim simulates robots (its
# --pd-gains flag), its rows say "robots not simulated yet" and the
# benchmark does not fail.  The final base heights and tilts of both are
# printed: a robot that fell makes the figures moot.
#
# The feet (ROBOT_BENCH_FEET=0 leaves them out): one more, untimed run of
# each program for 1 and 16 ANYmals, rscene-sim's writing its trajectory every 4
# steps, both measured by rscene-robot-bench-mujoco (MuJoCo's kinematics
# and collision on the same geometry): the deepest any foot went into the
# ground from the first second on (the start pose has them 2.7 mm in) and
# at the end, and the farthest a foot's centre ended from where it started
# (slip), in millimetres.
#
# Skipped (exit 0) when ../shared/corpus/robots is absent or the MuJoCo
# program is not built.  Environment: ROBOT_BENCH_DIR (default: a temporary
# directory, removed), ROBOT_BENCH_REPEAT, ROBOT_BENCH_DURATION,
# ROBOT_BENCH_GAINS, ROBOT_BENCH_FEET, ROBOT_BENCH_64, ROBOT_BENCH_CORPUS
# (default ../shared/corpus beside the repository).  Exit status: 0, or 1
# when a program failed.
set -euo pipefail

if [[ $# -ne 1 || ! -d $1 ]]; then
  echo "usage: bench/robot/run.sh BIN_DIR" >&2
  exit 2
fi
BIN=$(cd "$1" && pwd)
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPEAT=${ROBOT_BENCH_REPEAT:-3}
DURATION=${ROBOT_BENCH_DURATION:-10}
GAINS=${ROBOT_BENCH_GAINS:-400,10}
CORPUS=${ROBOT_BENCH_CORPUS:-$HERE/../../../shared/corpus}
DT=0.0025
KP=${GAINS%%,*}
KD=${GAINS#*,}
MJ=$BIN/rscene-robot-bench-mujoco
ROBOT=$CORPUS/robots/anymal_c
URDF=$ROBOT/urdf/anymal.urdf
TIME=/usr/bin/time

FEET=${ROBOT_BENCH_FEET:-1}
WITH64=${ROBOT_BENCH_64:-1}
echo "robot benchmark (issues 11, 26): $(uname -m), $(nproc) cores, ${DURATION} s at dt $DT, PD gains $GAINS, best of $REPEAT"
if [[ ! -r $URDF ]]; then
  echo "robot benchmark: skipped ($URDF is absent)"
  exit 0
fi
if [[ ! -x $MJ ]]; then
  echo "robot benchmark: skipped ($MJ is not built: MuJoCo is missing)"
  exit 0
fi
command -v jq > /dev/null || { echo "bench/robot/run.sh: error: jq is missing" >&2; exit 2; }
[[ -x $TIME ]] || { echo "bench/robot/run.sh: error: $TIME is missing (GNU time)" >&2; exit 2; }

if [[ -n ${ROBOT_BENCH_DIR:-} ]]; then
  DIR=$ROBOT_BENCH_DIR
  mkdir -p "$DIR"
else
  DIR=$(mktemp -d "${TMPDIR:-/tmp}/rscene-robotbench.XXXXXX")
  trap 'rm -rf "$DIR"' EXIT
fi

SIM_READY=0
if [[ -x $BIN/rscene-sim ]] && "$BIN/rscene-sim" --help 2>/dev/null | grep -q -- '--pd-gains'; then SIM_READY=1; fi

# verdict LABEL VALUE OP LIMIT: prints the line with PASS or MISS.
verdict() {
  local ok
  ok=$(awk -v v="$2" -v l="$4" -v op="$3" 'BEGIN { print (op == ">=" ? v >= l : v < l) ? "PASS" : "MISS" }')
  printf '  %-52s %10s  (target %s %s)  %s\n' "$1" "$2" "$3" "$4" "$ok"
}

# mujoco NAME ARGS...: best of REPEAT (anymal64: 1) by stepping CPU time;
# sets MJ_JSON.
mujoco() {
  local name=$1 i line best= n=$REPEAT
  shift
  [[ $name == anymal64 ]] && n=1
  MJ_JSON=
  for ((i = 0; i < n; i++)); do
    if ! line=$("$MJ" run "$URDF" "$@" --dt "$DT" --duration "$DURATION" --kp "$KP" --kd "$KD" 2> "$DIR/$name.mj.err"); then
      echo "bench/robot/run.sh: error: MuJoCo failed on $name:" >&2
      sed -n '1,5p' "$DIR/$name.mj.err" >&2
      return 1
    fi
    if [[ -z $best ]] || awk -v a="$(jq -r .stepCpu <<< "$line")" -v b="$best" 'BEGIN { exit !(a < b) }'; then
      best=$(jq -r .stepCpu <<< "$line")
      MJ_JSON=$line
    fi
  done
}

# rscene NAME SCENE: best of REPEAT by stepping CPU time (--report
# stepCpuTime); sets SIM_JSON (that run's --report line), SIM_STEP_CPU,
# SIM_CPU (the least whole-process CPU time of the runs) and SIM_OUT (the
# scene written back).
rscene() {
  local name=$1 scene=$2 i cpu json step n=$REPEAT
  SIM_JSON='' SIM_CPU='' SIM_STEP_CPU=''
  SIM_OUT=$DIR/$name.out.rscene
  [[ $name == anymal64 ]] && n=1
  for ((i = 0; i < n; i++)); do
    if ! "$TIME" -f '%U %S' -o "$DIR/$name.time" "$BIN/rscene-sim" --duration "$DURATION" --pd-gains "$GAINS" \
      --report -o "$SIM_OUT" "$scene" > /dev/null 2> "$DIR/$name.sim.err"; then
      echo "bench/robot/run.sh: error: rscene-sim failed on $name:" >&2
      sed -n '1,5p' "$DIR/$name.sim.err" >&2
      return 1
    fi
    cpu=$(tail -n 1 "$DIR/$name.time" | awk '{ print $1 + $2 }')
    if [[ -z $SIM_CPU ]] || awk -v a="$cpu" -v b="$SIM_CPU" 'BEGIN { exit !(a < b) }'; then SIM_CPU=$cpu; fi
    json=$(grep '^{' "$DIR/$name.sim.err" | tail -n 1)
    step=$(jq -r '.stepCpuTime // .stepTime' <<< "$json")
    if [[ -z $SIM_STEP_CPU ]] || awk -v a="$step" -v b="$SIM_STEP_CPU" 'BEGIN { exit !(a < b) }'; then
      SIM_STEP_CPU=$step
      SIM_JSON=$json
    fi
  done
}

# feet NAME SCENE ARGS...: footPenetration and footSlip (mm) of both
# programs' runs; sets FEET_LINE.
feet() {
  local name=$1 scene=$2 mj sim
  shift 2
  FEET_LINE=''
  mj=$("$MJ" run "$URDF" "$@" --dt "$DT" --duration "$DURATION" --kp "$KP" --kd "$KD" --feet 2> "$DIR/$name.feet.err") || return 1
  "$BIN/rscene-sim" --duration "$DURATION" --pd-gains "$GAINS" --trajectory "$DIR/$name.csv" --every 4 \
    --trajectory-format csv -o /dev/null "$scene" > /dev/null 2>> "$DIR/$name.feet.err" || return 1
  sim=$("$MJ" feet "$URDF" "$@" --dt "$DT" --trajectory "$DIR/$name.csv" 2>> "$DIR/$name.feet.err") || return 1
  rm -f "$DIR/$name.csv"
  FEET_LINE=$(jq -rn --argjson m "$mj" --argjson s "$sim" \
    'def mm: . * 1000 | . * 1000 | round / 1000;
     def of(x): "penetration \(x.footPenetration | mm) (end \(x.footPenetrationEnd | mm)), slip \(x.footSlip | mm)";
     "MuJoCo \(of($m)); rscene-sim \(of($s)) (mm, \($s.feet) feet)"')
}

# Lowest base height and largest tilt (degrees) of the robots in a scene
# written back by rscene-sim, above the highest ground under their start
# footprint (as rscene-robot-bench-mujoco reports MuJoCo's).
sim_bases() {
  paste <(grep '^articulated ' "$1" | sed 's/.*generalizedCoordinate=\([^ ]*\).*/\1/') \
    <(grep '^articulated ' "$2" | sed 's/.*generalizedCoordinate=\([^ ]*\).*/\1/') | awk '
    { split($1, q, ","); split($2, q0, ",")
      z = q[3] - (q0[3] - 0.54); n = q[4]^2 + q[5]^2 + q[6]^2 + q[7]^2
      c = 1 - 2 * (q[5]^2 + q[6]^2) / n; if (c > 1) c = 1; if (c < -1) c = -1
      t = atan2(sqrt(1 - c * c), c) * 180 / 3.141592653589793
      if (NR == 1 || z < zmin) zmin = z; if (t > tmax) tmax = t }
    END { printf "%.4f/%.3f", zmin, tmax }'
}

status=0
declare -a TARGETS
declare -A MJ_PROFILE FEET_OF PER_ROBOT
WORLDS=("anymal|" "anymal16|--robots 16 --terrain")
((WITH64)) && WORLDS+=("anymal64|--robots 64 --terrain")
printf '%-9s %6s  %12s %12s %14s  %12s %12s %9s %9s %9s  %7s  %s\n' world steps "MuJoCo st/s" "MuJoCo CPU s" "MJ z m/tilt" \
  "rscene st/s" "rscene CPU s" "CPU ratio" "proc rat." "st/s ratio" "load s" "rscene z m/tilt"
for entry in "${WORLDS[@]}"; do
  name=${entry%%|*}
  read -r -a args <<< "${entry#*|}"
  "$MJ" scene "$URDF" "$ROBOT" "${args[@]}" --dt "$DT" > "$DIR/$name.rscene"
  if ! mujoco "$name" "${args[@]}"; then
    status=1
    continue
  fi
  mj_rate=$(jq -r '.steps / .stepWall' <<< "$MJ_JSON")
  MJ_PROFILE[$name]=$(jq -r '"\(.contactsAtEnd) contacts at the end; of its step time, collision \(.collisionShare * 100 | floor)%, constraint solver \(.constraintShare * 100 | floor)%"' <<< "$MJ_JSON")
  [[ -z ${MJ_COMPILE:-} ]] && MJ_COMPILE=$(jq -r .compileTime <<< "$MJ_JSON")
  mj_line=$(printf '%-9s %6s  %12.0f %12.3f %14s' "$name" "$(jq -r .steps <<< "$MJ_JSON")" "$mj_rate" \
    "$(jq -r .stepCpu <<< "$MJ_JSON")" "$(jq -r '"\(.baseHeightMin)/\(.tiltMaxDeg)"' <<< "$MJ_JSON")")
  if ((SIM_READY == 0)); then
    printf '%s  %s\n' "$mj_line" "rscene-sim: robots not simulated yet"
    continue
  fi
  if ! rscene "$name" "$DIR/$name.rscene"; then
    printf '%s  %s\n' "$mj_line" "rscene-sim: failed"
    status=1
    continue
  fi
  sim_rate=$(jq -r '.steps / .stepTime' <<< "$SIM_JSON")
  ratio=$(awk -v a="$sim_rate" -v b="$mj_rate" 'BEGIN { printf "%.3f", a / b }')
  mj_cpu=$(jq -r .stepCpu <<< "$MJ_JSON")
  cpu_ratio=$(awk -v a="$mj_cpu" -v b="$SIM_STEP_CPU" 'BEGIN { printf "%.3f", (b > 0 ? a / b : 0) }')
  proc_ratio=$(awk -v a="$mj_cpu" -v b="$SIM_CPU" 'BEGIN { printf "%.3f", (b > 0 ? a / b : 0) }')
  load=$(jq -r .loadTime <<< "$SIM_JSON" | awk '{ printf "%.3f", $1 }')
  printf '%s  %12.0f %12.3f %9s %9s %9s  %7.3f  %s\n' "$mj_line" "$sim_rate" "$SIM_STEP_CPU" "$cpu_ratio" "$proc_ratio" \
    "$ratio" "$load" "$(sim_bases "$SIM_OUT" "$DIR/$name.rscene")"
  robots=$(grep -c '^articulated ' "$DIR/$name.rscene")
  PER_ROBOT[$name]=$(jq -rn --argjson steps "$(jq -r .steps <<< "$MJ_JSON")" --argjson n "$robots" \
    --argjson m "$mj_cpu" --argjson s "$SIM_STEP_CPU" \
    '"\($s / $steps / $n * 1e6 | . * 10 | round / 10) us (MuJoCo \($m / $steps / $n * 1e6 | . * 10 | round / 10) us)"')
  TARGETS+=("$name|$cpu_ratio|$load|$(jq -c '{parseTime, buildTime, stepTime, stepCpuTime, writeTime}' <<< "$SIM_JSON")")
  if ((FEET)) && [[ $name != anymal64 ]]; then
    if feet "$name" "$DIR/$name.rscene" "${args[@]}"; then
      FEET_OF[$name]=$FEET_LINE
    else
      FEET_OF[$name]="not measured: $(head -n 1 "$DIR/$name.feet.err")"
    fi
  fi
done
for entry in "${WORLDS[@]}"; do
  name=${entry%%|*}
  [[ -n ${MJ_PROFILE[$name]:-} ]] && echo "  MuJoCo $name: ${MJ_PROFILE[$name]}"
done
for entry in "${WORLDS[@]}"; do
  name=${entry%%|*}
  [[ -n ${FEET_OF[$name]:-} ]] && echo "  feet, $name over $DURATION s: ${FEET_OF[$name]}"
done
for entry in "${WORLDS[@]}"; do
  name=${entry%%|*}
  [[ -n ${PER_ROBOT[$name]:-} ]] && echo "  stepping CPU per robot and step, $name: ${PER_ROBOT[$name]}"
done
echo "  (st/s: steps per second of stepping wall time; rscene CPU s: its stepping CPU time (--report stepCpuTime);" \
  "CPU ratio: MuJoCo's stepping CPU s / rscene-sim's; proc rat.: MuJoCo's stepping CPU s / rscene-sim's whole process;" \
  "z: lowest final base height, m; tilt: largest, degrees;" \
  "MuJoCo compiled the URDF in ${MJ_COMPILE:-?} s)"

# Loading the robot with its meshes: rscene-render builds the scene's
# drawables, visual meshes and textures included.
if [[ -x $BIN/rscene-render && -s $DIR/anymal.rscene ]]; then
  if "$BIN/rscene-render" "$DIR/anymal.rscene" --backend cpu --width 320 --height 240 -v -o "$DIR/anymal.png" \
    > /dev/null 2> "$DIR/render.err"; then
    build=$(sed -n 's/.*scene build \([0-9.]*\) s.*/\1/p' "$DIR/render.err" | tail -n 1)
    echo "  rscene-render, one ANYmal C (meshes once it draws robots): scene build ${build:-?} s"
  else
    echo "  rscene-render failed on the ANYmal scene: $(head -n 1 "$DIR/render.err")"
  fi
fi

echo
echo "targets (issue 26): rscene-sim steps per CPU second of stepping >= MuJoCo's (1 and 16 ANYmals), robot load < 0.3 s"
if ((SIM_READY == 0)); then
  echo "  rscene-sim: robots not simulated yet (no --pd-gains); nothing to compare"
fi
for t in "${TARGETS[@]}"; do
  IFS='|' read -r name ratio load parts <<< "$t"
  if [[ $name == anymal64 ]]; then
    printf '  %-52s %10s  (no target)\n' "$name: rscene-sim / MuJoCo steps per CPU second" "$ratio"
  else
    verdict "$name: rscene-sim / MuJoCo steps per CPU second" "$ratio" ">=" 1.0
  fi
  verdict "$name: rscene-sim load time (s)" "$load" "<" 0.3
  echo "    rscene-sim breakdown (s): $parts"
done
exit $status
