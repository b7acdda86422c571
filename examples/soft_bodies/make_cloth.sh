#!/bin/sh
# Writes cloth_24.obj: a square cloth of N x N vertices (default 24), 1 m
# on a side in the x-y plane, centred on the origin, in the order the
# deformable solver and pinnedVertices number them (row by row along +x,
# rows along +y).  The diagonal of each cell alternates like a
# checkerboard, so the cloth has no preferred shear direction and drapes
# the same way to either side.  Run once; the OBJ is committed (30 KB).
#   sh make_cloth.sh [N] > cloth_N.obj
set -eu
awk -v n="${1:-24}" 'BEGIN {
  last = n - 1
  printf "# %dx%d-vertex cloth, 1 m x 1 m in the x-y plane, centred on the origin\n", n, n
  printf "# (examples/soft_bodies/make_cloth.sh %d).  Corners: vertex 0 at (-0.5,-0.5),\n", n
  printf "# %d at (0.5,-0.5), %d at (-0.5,0.5), %d at (0.5,0.5); pinnedVertices counts from 0.\n", last, n * last, n * n - 1
  for (j = 0; j < n; j++)
    for (i = 0; i < n; i++)
      printf "v %.6g %.6g 0\n", -0.5 + i / last, -0.5 + j / last
  for (j = 0; j < last; j++)
    for (i = 0; i < last; i++) {
      a = j * n + i + 1; b = a + 1; c = a + n; d = c + 1   # OBJ counts from 1
      if ((i + j) % 2 == 0) printf "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c
      else                  printf "f %d %d %d\nf %d %d %d\n", a, b, c, b, d, c
    }
}'
