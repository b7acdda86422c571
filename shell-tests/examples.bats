#!/usr/bin/env bats
# The examples stand on their own: `make demo` runs on a fresh machine
# without ../shared, so every file a scene of examples/ names must be in
# the repository, and the demo must copy it next to the scenes it runs.

load helpers

setup() {
  cd "$BATS_TEST_TMPDIR"
}

# The robot files (articulated_resource paths and resourceDirectory=) of
# the scenes in folder $1, one per line, relative to that folder.
robot_files() {
  grep -h '^articulated_resource ' "$1"/*.rscene | awk '{ print $4 }'
  grep -ho ' resourceDirectory=[^ ]*' "$1"/*.rscene | sed 's/^ resourceDirectory=//'
}

@test "every robot file the examples name is in examples/" {
  run -0 robot_files "$ROOT/examples"
  [ -n "$output" ]
  while read -r f; do
    [ -e "$ROOT/examples/$f" ] || { echo "examples/ names $f, which is missing"; false; }
  done <<<"$output"
}

@test "the demo copies the robot files next to the scenes it runs" {
  mkdir nobin
  # With no tools built every step is skipped: only the copying runs.
  run -0 env RSCENE_BIN="$PWD/nobin" RSCENE_DEMO_OUT="$PWD/out" sh "$ROOT/scripts/demo.sh"
  [ -f out/robot_cell.rscene ]
  run -0 robot_files out
  while read -r f; do
    [ -e "out/$f" ] || { echo "the demo's robot_cell names $f, which was not copied"; false; }
  done <<<"$output"
  [ -f out/robots/quadruped/quadruped.urdf ]
}

@test "the gallery's mesh and texture are in examples/gallery and the demo copies them" {
  run -0 "${RSCENE_BIN:-$ROOT/build/bin}/rscene-validate" --check-files "$ROOT/examples/gallery.rscene"
  mkdir nobin
  run -0 env RSCENE_BIN="$PWD/nobin" RSCENE_DEMO_OUT="$PWD/out" sh "$ROOT/scripts/demo.sh"
  [ -f out/gallery/meshes/flag.obj ]
  [ -f out/gallery/textures/warning.png ]
  run -0 "${RSCENE_BIN:-$ROOT/build/bin}/rscene-validate" --check-files out/gallery.rscene
}

@test "the demo's editor-to-training steps: robot_cell exports, examples/xml/arena.xml imports with its include and simulates" {
  bin=${RSCENE_BIN:-$ROOT/build/bin}
  mkdir nobin
  run -0 env RSCENE_BIN="$PWD/nobin" RSCENE_DEMO_OUT="$PWD/out" sh "$ROOT/scripts/demo.sh"
  # The world and the file it includes are copied beside the scenes.
  [ -f out/xml/arena.xml ] && [ -f out/xml/walls.xml ]
  grep -q '<include file="\[THIS_DIR\]/walls.xml"/>' out/xml/arena.xml
  [ -x "$bin/rscene-to-xml" ] && [ -x "$bin/rscene-from-xml" ] || skip "rscene-to-xml/rscene-from-xml not built"
  cd out
  run -0 "$bin/rscene-to-xml" -q robot_cell.rscene -o robot_cell.xml
  grep -q '<articulatedSystem name="/World/Robot" urdf_path="\[THIS_DIR\]/robots/quadruped/quadruped.urdf"' robot_cell.xml
  run -0 "$bin/rscene-from-xml" -q xml/arena.xml --param ball_count=12 -o arena.rscene
  [ "$(grep -c '^object /World/ball_[0-9]* sphere ' arena.rscene)" = 12 ]
  [ "$(grep -c '^object /World/wall_[a-z]* box ' arena.rscene)" = 4 ]
  [ "$(grep -c '^compound_child /World/cart ' arena.rscene)" = 5 ]
  [ "$(grep -c '^contact_material ' arena.rscene)" = 3 ]
  # Ball 11: (cos(8.8) 3.75, sin(8.8) 3.75, 3.8); the default is 8 balls.
  awk '$2 == "/World/ball_11" { x = cos(8.8) * 3.75; y = sin(8.8) * 3.75
    if ((d = $4 - x) > 1e-12 || d < -1e-12 || (d = $5 - y) > 1e-12 || d < -1e-12 || $6 != 3.8) { print $4, $5, $6; exit 1 } }' arena.rscene
  run -0 "$bin/rscene-from-xml" -q xml/arena.xml
  [ "$(grep -c '^object /World/ball_' <<<"$output")" = 8 ]
  # The include's parameter default, and an override.
  run -0 "$bin/rscene-from-xml" -q xml/arena.xml --param wall_height=1
  grep -q '^object /World/wall_north box 0 4.5 0.5 ' <<<"$output"
  run -0 "$bin/rscene-sim" --duration 2 -o arena.settled.rscene arena.rscene
}
