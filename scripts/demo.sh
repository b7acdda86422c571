#!/bin/sh
# The demo behind `make demo`: runs the tools on copies of examples/ in
# out/demo/ and says where the results are.  Each step is one `step` line;
# a step whose tool has not been built is skipped, so later tools only add
# a line here.
set -eu

ROOT=$(CDPATH= cd -- "$(dirname -- "$0")/.." && pwd)
BIN=${RSCENE_BIN:-$ROOT/build/bin}
OUT=${RSCENE_DEMO_OUT:-$ROOT/out/demo}

rm -rf "$OUT"
mkdir -p "$OUT"
cp "$ROOT"/examples/*.rscene "$OUT"/
cp -R "$ROOT"/examples/robots "$OUT"/  # robot files the scenes name
cp -R "$ROOT"/examples/gallery "$OUT"/  # the gallery's mesh and texture
cp -R "$ROOT"/examples/soft_bodies "$OUT"/  # the cloth OBJ of soft_bodies.rscene
cp -R "$ROOT"/examples/xml "$OUT"/  # the hand-written RaiSim world and the file it includes
cd "$OUT"

# step TOOL TITLE 'COMMAND' : runs the shell COMMAND (with $BIN first on
# PATH) unless $BIN/TOOL is missing.  Findings (exit 1) are part of a demo;
# trouble (exit 2 and up) stops it.
step() {
  tool=$1 title=$2 cmd=$3
  if [ ! -x "$BIN/$tool" ]; then
    printf '\n== %s: skipped (%s not built)\n' "$title" "$tool"
    return 0
  fi
  printf '\n== %s\n$ %s\n' "$title" "$cmd"
  rc=0
  PATH="$BIN:$PATH" sh -c "$cmd" || rc=$?
  if [ "$rc" -gt 1 ]; then
    printf 'demo: error: step failed with exit status %s\n' "$rc" >&2
    exit "$rc"
  fi
}

step rscene-fmt "what rscene-fmt would change" 'rscene-fmt --diff *.rscene'
step rscene-fmt "files that are not canonical" 'rscene-fmt --check *.rscene'
step rscene-fmt "format in place" 'rscene-fmt -i *.rscene'
step rscene-fmt "all canonical now (exit 0)" 'rscene-fmt --check *.rscene && echo "all canonical"'
step rscene-validate "lint the scenes" 'rscene-validate *.rscene'
step rscene-to-json "JSON for scripts (records per tag)" \
  'rscene-to-json warehouse_crates.rscene > warehouse_crates.json && jq -r ".records | group_by(.tag)[] | \"\\(length) \\(.[0].tag)\"" warehouse_crates.json'
step rscene-sim "drop the crates: simulate 2 s" \
  'rscene-sim --duration 2 --report -o warehouse_crates.settled.rscene warehouse_crates.rscene'
step rscene-diff "what the simulation moved" 'rscene-diff --stat warehouse_crates.rscene warehouse_crates.settled.rscene'
step rscene-sim "a robot held standing by PD for 2 s (robot_cell: our quadruped, a cart on a wire)" \
  'rscene-sim --duration 2 --pd-gains 100,2 --report --trajectory robot_cell.csv --trajectory-format csv --every 100 -o robot_cell.settled.rscene robot_cell.rscene && head -c 300 robot_cell.csv | head -1 | cut -c1-160'
step rscene-diff "what the robot's joints did, by joint name" 'rscene-diff robot_cell.rscene robot_cell.settled.rscene | head -20'
step rscene-sim "the robot's LiDAR (PCD point clouds) and IMU (CSV) while it stands" \
  'rscene-sim --duration 1 --pd-gains 100,2 --sensors sensors -o /dev/null robot_cell.rscene && ls sensors sensors/World+Robot+Lidar | head -8 && head -3 sensors/World+Robot+Imu.csv'
step rscene-sim "soft bodies and granular media for 2 s: a pinned curtain, a cloth over a sphere, a ball dropped in 2916 grains (points per trajectory line)" \
  'rscene-sim --duration 2 --every 100 --report --trajectory soft_bodies.jsonl -o soft_bodies.settled.rscene soft_bodies.rscene && jq -c "select(has(\"points\")) | [.time, .path, (.points | length)]" soft_bodies.jsonl | tail -3'
step rscene-diff "what the simulation wrote back: the ball moved, the sand got explicit positions and radii (the cloths keep their record)" \
  'rscene-diff --stat soft_bodies.rscene soft_bodies.settled.rscene'
step rscene-render "the soft bodies along their trajectory, a frame every 0.5 s: the cloths deformed, the grains and the ball moving" \
  'rscene-render --width 640 --height 360 --trajectory soft_bodies.jsonl --every 5 -o "frames/soft.{kind}.{frame}.png" soft_bodies.rscene && ls frames | grep "^soft\." && echo "a video: ffmpeg -framerate 2 -i frames/soft.rgb.%06d.png -pix_fmt yuv420p soft.mp4"'
step rscene-render "every camera of robot_cell: the overview, the head camera's rgb, depth (16-bit PNG + .npy) and segmentation (+ legend)" \
  'rscene-render --all-cameras -o "views/{name}.{kind}.png" robot_cell.rscene && ls views'
step rscene-render "the head camera along the simulated trajectory (one image per saved frame)" \
  'rscene-render --camera /World/Robot/HeadCam --trajectory robot_cell.csv -o "frames/head.{kind}.{frame}.png" robot_cell.rscene && ls frames | wc -l'
step rscene-render "the gallery: every visual record kind, lights of every type with shadows, reflections, decal, fog, foliage, post-processing (1280x720, CPU)" \
  'rscene-render -v -o gallery.png gallery.rscene'
step rscene-render "thumbnails (CPU, headless EGL)" \
  'for f in *.rscene; do rscene-render --width 480 --height 300 --allow-missing-assets -o "${f%.rscene}.png" "$f" || exit $?; done; ls *.png'

# Editor to training and back (README "Training with RaiSim").
step rscene-to-xml "the editor's scene for training: robot_cell as a RaiSim world XML (raisim::World world(path))" \
  'rscene-to-xml robot_cell.rscene -o robot_cell.xml && grep -E "<(timeStep|articulatedSystem|compound|wire) " robot_cell.xml'
step rscene-from-xml "a hand-written templated RaiSim world as a scene: 12 balls on a spiral, a cart, walls from an include" \
  'rscene-from-xml xml/arena.xml --param ball_count=12 -o arena.rscene && grep -c "^object /World/ball_" arena.rscene'
[ ! -x "$BIN/rscene-from-xml" ] ||
  step rscene-sim "the imported world simulated 2 s" \
    'rscene-sim --duration 2 --report -o arena.settled.rscene arena.rscene'

printf '\nresults: %s\n' "$OUT"
