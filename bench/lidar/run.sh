#!/usr/bin/env bash
# bench/lidar/run.sh BIN_DIR - one 64 x 1024 LiDAR scan of the warehouse's
# collision geometry (../shared/corpus/rayrai_warehouse.rscene: its ground
# and 508 static boxes; its mesh objects are visual only), issue 12's
# target: under 20 ms.  rscene-lidar-bench times lib/sim's exact ray casts
# (1 and 2 threads) and, in the same run, Bullet's btCollisionWorld::rayTest
# per ray on the same world, and says how far the two disagree (Bullet's
# convex casts hit within the shapes' 4 cm collision margin at grazing
# angles: a few rays of a scan differ there, the exact casts are the ones on
# the box).  Skipped when the corpus is absent.
#
# Environment:
#   BENCH_LIDAR_REPEAT  scans timed, best kept (default 10; Bullet: 3)
#   SIM_BENCH_CORPUS    the corpus folder (default: ../shared/corpus beside
#                       the repository)
# Exit status: 0 when it ran or was skipped, 1 when it failed, 2 on usage.
set -euo pipefail

if [[ $# -ne 1 || ! -d $1 ]]; then
  echo "usage: bench/lidar/run.sh BIN_DIR" >&2
  exit 2
fi
BIN=$(cd "$1" && pwd)
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
CORPUS=${SIM_BENCH_CORPUS:-$ROOT/../shared/corpus}
SCENE=$CORPUS/rayrai_warehouse.rscene

if [[ ! -x $BIN/rscene-lidar-bench ]]; then
  echo "bench/lidar/run.sh: $BIN/rscene-lidar-bench is not built (lib/sim is needed); skipped"
  exit 0
fi
if [[ ! -f $SCENE ]]; then
  echo "bench/lidar/run.sh: $SCENE is absent; skipped"
  exit 0
fi
echo "LiDAR (issue 12): one 64x1024 scan, best of ${BENCH_LIDAR_REPEAT:-10}"
"$BIN/rscene-lidar-bench" "$SCENE"
