#!/usr/bin/env bash
# bench/soft/surfaces.sh BIN_DIR - what one particle's contact query with
# the rigid world costs (BulletSurfaces::contacts): a 20,000-grain bed on
# the ground plane, on a static box, on a convex hull and on an
# 8,192-triangle static mesh.  The figures come from rscene-surfaces-bench
# (bench/sim/surfaces.cpp, built where lib/sim is); skipped without it.
set -euo pipefail
BIN=$(cd "$1" && pwd)
if [[ ! -x $BIN/rscene-surfaces-bench ]]; then
  echo "surfaces: $BIN/rscene-surfaces-bench not built, skipped"
  exit 0
fi
echo "== particle contact queries (BulletSurfaces) =="
"$BIN/rscene-surfaces-bench"
