#!/usr/bin/env bash
# Batch render benchmark (issue "Batches of scenes"), CPU backend (llvmpipe):
# N small scenes (default 500: a ground, a sun, 2 to 8 primitives, a
# 160x100 camera; bench/render/gen.sh) rendered as thumbnails by one
# process (`rscene-render -o 'thumbs/{stem}.png' dir/`, one GL context and
# its programs kept across the scenes) and by N processes, one a scene.
# Prints wall and CPU seconds of both and the ratio one / N, against the
# target <= 0.25.  Exits 1 only when a run fails or the target is missed.
#   bash bench/batch/render.sh BIN_DIR        (BATCH_SCENES=N to change N)
set -euo pipefail
BIN=${1:?usage: render.sh BIN_DIR}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
RENDER="$BIN/rscene-render"
N=${BATCH_SCENES:-500}
[[ -x $RENDER ]] || { echo "batch render bench: rscene-render not built; skipped"; exit 0; }
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
mkdir -p "$DIR/scenes"
for k in 2 3 4 5 6 7 8; do bash "$HERE/../render/gen.sh" $k | sed 's/ 1280 800 rgb/ 160 100 rgb/' > "$DIR/kind$k"; done
for ((i = 0; i < N; ++i)); do cp "$DIR/kind$((2 + i % 7))" "$DIR/scenes/s$i.rscene"; done
TIME=/usr/bin/time
[[ -x $TIME ]] || { echo "batch render bench: GNU time missing; skipped"; exit 0; }

cd "$DIR"
# Wall, user and system seconds of each way (children included).
$TIME -f '%e %U %S' -o one.time "$RENDER" --backend cpu -o 'one/{stem}.png' scenes/ 2> one.log ||
  { cat one.log >&2; echo "batch render bench: the batch failed" >&2; exit 1; }
$TIME -f '%e %U %S' -o many.time bash -c '
  mkdir -p many
  for ((i = 0; i < $2; ++i)); do "$1" --backend cpu -o "many/s$i.png" "scenes/s$i.rscene" || exit 1; done' _ "$RENDER" "$N" ||
  { echo "batch render bench: a single-scene run failed" >&2; exit 1; }
[[ $(ls one | wc -l) -eq $N && $(ls many | wc -l) -eq $N ]] || { echo "batch render bench: images missing" >&2; exit 1; }
read -r wall1 wallN cpu1 cpuN ratio cpuratio < <(tail -1 many.time |
  awk -v one="$(tail -1 one.time)" '{ split(one, a, " "); u1 = a[2] + a[3]; un = $2 + $3
    printf "%.2f %.2f %.2f %.2f %.3f %.3f\n", a[1], $1, u1, un, a[1] / $1, (un > 0 ? u1 / un : 0) }')
verdict=$(awk -v r="$ratio" 'BEGIN { print (r <= 0.25) ? "PASS" : "MISS" }')
echo "batch render: $N thumbnails 160x100, one process ${wall1} s wall (${cpu1} s CPU), $N processes ${wallN} s wall (${cpuN} s CPU)"
echo "batch render: one / $N = ${ratio} wall (${cpuratio} CPU), target <= 0.25: $verdict"
[[ $verdict == PASS ]]
