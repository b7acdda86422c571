#!/usr/bin/env bash
# Render benchmark of issue 14, CPU backend (llvmpipe): a 20,000-grain
# granular bed and a 64 x 64 cloth, each drawn once at rest and along a
# 5-frame trajectory rscene-sim writes (1280 x 720).  Prints the still
# render's shadow + drawing + post-processing seconds (rscene-render -v)
# beside the trajectory's seconds per frame (reading, posing and
# re-uploading the particles included), against the target: a frame costs
# at most 1.5 x the still render.  A MISS is printed, never fatal (the
# figures move with the machine's load); exits 1 only when a tool fails.
#   bash bench/soft/render.sh BIN_DIR
set -euo pipefail
BIN=$(cd "${1:?usage: render.sh BIN_DIR}" && pwd)
RENDER="$BIN/rscene-render"
SIM="$BIN/rscene-sim"
[[ -x $RENDER && -x $SIM ]] || { echo "soft render bench: rscene-render or rscene-sim not built; skipped"; exit 0; }
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
cd "$DIR"

awk 'BEGIN { n = 64
  for (j = 0; j < n; j++) for (i = 0; i < n; i++) printf "v %.6f %.6f 0\n", 2 * i / (n - 1) - 1, 2 * j / (n - 1) - 1
  for (j = 0; j < n - 1; j++) for (i = 0; i < n - 1; i++) { a = j * n + i + 1; printf "f %d %d %d %d\n", a, a + 1, a + n + 1, a + n } }' > cloth64.obj
head='raisim_engine_scene 1
camera /World/Cam -4 0 3 0.9239 0 0.3827 0 60 0.05 100 1280 720 rgb true id=cam
light /World/Sun 0.2 0.1 -1 3 type=directional
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615'
printf '%s\n%s\n' "$head" "granular /World/Sand particles -1 -1 0 1 0 0 0 1 1 1 boxMax=2,2,0.32 radius=0.02 spacing=0.04 maxParticles=20000 density=1600 normalStiffness=5e4 normalDamping=25 tangentialStiffness=2.5e4 tangentialDamping=6 friction=0.8 rollingFriction=0.02 normalContactModel=linear substeps=5" > bed.rscene
printf '%s\n%s\n' "$head" "deformable /World/Cloth cloth cloth64.obj 0 0 1 1 0 0 0 1 1 1 pinnedVertices=0,63 totalMass=0.5" > cloth.rscene

echo "deformables and granular beds in rscene-render (1280x720, llvmpipe):"
for s in bed cloth; do
  "$SIM" $s.rscene --steps 20 --every 5 --trajectory $s.jsonl -o /dev/null
  rest=$("$RENDER" $s.rscene -v -o rest.png 2>&1 | awk -F'shadow passes ' '/shadow passes/ {
    split($2, a, /[ ,]+/); s = a[1]; n = split($0, w, " ")
    for (i = 1; i < n; i++) if (w[i] == "drawing" || w[i] == "post-processing") s += w[i + 1]
    printf "%.3f", s }')
  frame=$("$RENDER" $s.rscene -v --trajectory $s.jsonl -o "f{frame}.png" 2>&1 | awk '/ files in / {
    for (i = 1; i <= NF; i++) { if ($i == "x") frames = $(i + 1); if ($i == "in") t = $(i + 1) }
    printf "%.3f", t / frames }')
  verdict=$(awk -v r="$rest" -v f="$frame" 'BEGIN { print (f <= 1.5 * r ? "PASS" : "MISS") }')
  points=$(head -1 $s.jsonl | grep -o '\],\[' | wc -l)
  printf '  %-5s %6d points: at rest %s s, along the trajectory %s s per frame  %s\n' "$s" $((points + 1)) "$rest" "$frame" "$verdict"
done
