#!/usr/bin/env bash
# bench/soft/cloth_gen.sh DIR [N] - writes DIR/cloth.obj (an N x N vertex
# cloth, 2 m a side, two triangles a cell with alternating diagonals) and
# DIR/cloth.rscene (the cloth 0.7 m above a static sphere of radius 0.5 on
# the ground, RaiSim's 5 ms step) and DIR/free.rscene (the same cloth not
# collidable: the solver's time without contacts).  Default N = 64.
set -euo pipefail
dir=$1
n=${2:-64}
awk -v n="$n" 'BEGIN {
  for (j = 0; j < n; j++) for (i = 0; i < n; i++) printf "v %.9g %.9g 0\n", -1 + 2 * i / (n - 1), -1 + 2 * j / (n - 1)
  for (j = 0; j + 1 < n; j++) for (i = 0; i + 1 < n; i++) {
    a = j * n + i + 1; b = a + 1; c = a + n; d = c + 1
    if ((i + j) % 2) printf "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c
    else printf "f %d %d %d\nf %d %d %d\n", a, b, c, b, d, c
  }
}' > "$dir/cloth.obj"
scene() {  # scene COLLIDABLE
  cat <<SCENE
raisim_engine_scene 1
time_step 0.005
gravity 0 0 -9.81
object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/Ball sphere 0 0 0.5 1 0 0 0 1 1 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
deformable /World/Cloth cloth cloth.obj 0 0 1.2 1 0 0 0 1 1 1 totalMass=0.5 distanceCompliance=0 bendCompliance=1000 damping=0.01 collisionRadius=0.01 iterations=10 substeps=1 collidable=$1
SCENE
}
scene true > "$dir/cloth.rscene"
scene false > "$dir/free.rscene"
