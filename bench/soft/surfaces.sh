#!/usr/bin/env bash
# bench/soft/surfaces.sh BIN_DIR - what one particle's contact query with
# the rigid world costs (BulletSurfaces::contacts): a 20,000-grain bed on
# the ground plane, on a static box and on an 8,192-triangle static mesh.
# The figures come from sim_tests' SurfacesCost test (built beside the
# tools); skipped when the tests were not built.
set -euo pipefail
BIN=$(cd "$1" && pwd)
if [[ ! -x $BIN/sim_tests ]]; then
  echo "surfaces: $BIN/sim_tests not built, skipped"
  exit 0
fi
echo "== particle contact queries (BulletSurfaces) =="
"$BIN/sim_tests" --gtest_filter='SurfacesCost.*' --gtest_brief=1 | grep 'ns per query'
