#!/usr/bin/env bats
# The examples stand on their own: `make demo` runs on a fresh machine
# without ../shared, so every file a scene of examples/ names must be in
# the repository, and the demo must copy it next to the scenes it runs.

ROOT="$BATS_TEST_DIRNAME/.."

bats_require_minimum_version 1.5.0

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
