#!/usr/bin/env bash
# bench/soft/granular.sh BIN_DIR - issue 14's granular benchmark: a bed of
# 20,000 grains (40 x 25 x 20, a box fill) settling on the ground for 2 s
# of simulated time in rscene-sim, with RaiSim's GranularMedia.rst example
# material (radius 0.02, density 1600, normalStiffness 5e4, normalDamping
# 25, tangentialStiffness 2.5e4, tangentialDamping 6, friction 0.8,
# rollingFriction 0.02, linear law, 2 substeps of a 1 ms step).
#
# Prints rscene-sim --report's figures: steps/s, particle-substeps/s and
# where the granular solver's time went (neighbour search, grain contacts,
# surface contacts, integration), and particle-substeps per CPU second of
# the whole run (parsing, Bullet and writing included) against the target: 5e6
# particle-substeps per second on one core, the low end of what
# LAMMPS/LIGGGHTS-class DEM codes reach per core (1e6-1e7 for a
# monodisperse linear spring-dashpot bed with neighbour lists).
#
# Environment:
#   BENCH_GRANULAR_SECONDS  simulated seconds (default 2)
# Exit status: 0 when it ran, 1 when rscene-sim failed, 2 on usage.
set -euo pipefail

if [[ $# -ne 1 || ! -d $1 ]]; then
  echo "usage: bench/soft/granular.sh BIN_DIR" >&2
  exit 2
fi
BIN=$(cd "$1" && pwd)
SECONDS_SIMULATED=${BENCH_GRANULAR_SECONDS:-2}
if [[ ! -x $BIN/rscene-sim ]]; then
  echo "bench/soft/granular.sh: $BIN/rscene-sim is not built; skipped"
  exit 0
fi
DIR=$(mktemp -d "${TMPDIR:-/tmp}/rscene-granular.XXXXXX")
trap 'rm -rf "$DIR"' EXIT

# A box fill counts floor((span - 2 radius) / spacing) + 1 grains per axis:
# spans 1.74, 1.09 and 0.88 give 40, 25 and 20.
cat > "$DIR/bed.rscene" <<'EOF'
raisim_engine_scene 1
time_step 0.001
gravity 0 0 -9.81
object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
granular /World/Sand sand 0 0 0 1 0 0 0 1 1 1 id=granular_sand boxMin=-0.87,-0.545,0 boxMax=0.87,0.545,0.88 radius=0.02 spacing=0.043 maxParticles=20000 density=1600 normalStiffness=5e4 normalDamping=25 tangentialStiffness=2.5e4 tangentialDamping=6 friction=0.8 rollingFriction=0.02 normalContactModel=linear substeps=2
EOF

echo "granular media (issue 14): 20,000 grains settling on the ground for ${SECONDS_SIMULATED} s (1 ms steps)"
# CPU time (user + system) beside the report's wall-clock figures: on a
# shared machine the wall clock counts other jobs' time too.
TIME=/usr/bin/time
[[ -x $TIME ]] || TIME=
if ! ${TIME:+$TIME -f '%U %S' -o "$DIR/cpu"} "$BIN/rscene-sim" --duration "$SECONDS_SIMULATED" --report \
  -o "$DIR/out.rscene" "$DIR/bed.rscene" 2> "$DIR/report"; then
  echo "bench/soft/granular.sh: error: rscene-sim failed:" >&2
  sed -n '1,5p' "$DIR/report" >&2
  exit 1
fi
report=$(tail -n 1 "$DIR/report")
cpu=null
[[ -n $TIME ]] && cpu=$(awk '{ print $1 + $2 }' "$DIR/cpu")
jq -r --argjson cpu "$cpu" '
  def f(x): (x * 1000 | round) / 1000;
  .granular as $g
  | ($g.neighbourTime + $g.contactTime + $g.surfaceTime + $g.integrationTime) as $t
  | "  particles \(.particles), steps \(.steps), substeps per step \($g.substepsPerStep)",
    "  wall \(f(.wallTime)) s, steps/s \(f(.stepsPerSecond)), particle steps \(f(.particleStepTime)) s of \(f(.stepTime)) s stepping",
    "  particle-substeps/s \($g.particleSubstepsPerSecond | floor) of the granular solver'"'"'s wall time",
    (if $cpu == null then "  (no /usr/bin/time: no CPU figure)" else
      ($g.particleSubsteps / $cpu) as $c
      | "  particle-substeps per CPU second of the whole run \($c | floor) (\($cpu) s user+system; target >= 5000000 on one core: \(if $c >= 5e6 then "PASS" else "MISS" end))" end),
    "  granular time: neighbour search \(f($g.neighbourTime)) s (\($g.neighbourBuilds) rebuilds), grain contacts \(f($g.contactTime)) s, surface contacts \(f($g.surfaceTime)) s, integration \(f($g.integrationTime)) s",
    "  at the end: \($g.contacts) grain contacts, \($g.surfaceContacts) surface contacts, deepest overlap \($g.maxPenetration * 1e6 | round) um, at rest: \(.atRest)"
' <<< "$report"
if [[ $(jq '.granular.surfaceContacts' <<< "$report") == 0 ]]; then
  echo "  note: no grain touches the ground at the end: the bed fell through (lib/sim/bullet_surfaces.cpp without contacts?)"
fi
