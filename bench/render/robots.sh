#!/usr/bin/env bash
# Writes a robot scene for the render benchmark to stdout: N ANYmal C robots
# (default 1) standing on a ground in a grid 1.5 m apart, lit by a shadowing
# sun, no camera (rscene-render frames them itself).  The robot is
# ../shared's ANYmal C URDF with its COLLADA meshes and JPEG textures.
#   bash bench/render/robots.sh URDF [N] > scene.rscene
set -euo pipefail
urdf=${1:?usage: robots.sh URDF [N]}
n=${2:-1}
awk -v n="$n" -v urdf="$urdf" 'BEGIN {
  print "raisim_engine_scene 1"
  print "environment 0.38 0.38 0.38 0.15 0.16 0.2 0 true true 10 - backgroundMode=rayrai_sky"
  print "weather true preset=clear timeOfDay=15"
  print "material ground 0.45 0.47 0.5 1 0 0.8 0 0 0 0 false - - - - - - id=ground"
  print "light /World/Sun -0.4 0.3 -1 3 type=directional shadows=true"
  print "object /World/Ground ground 0 0 0 1 0 0 0 50 50 1 1 0 0 default ground false true true - static true 1 18446744073709551615"
  printf "articulated_resource anymal ANYmal %s\n", urdf
  side = int(sqrt(n)); if (side * side < n) ++side
  for (i = 0; i < n; ++i) {
    x = 1.5 * (i % side); y = 1.5 * int(i / side)
    printf "articulated /World/Anymal%d anymal %g %g 0.54 1 0 0 0 true true generalizedCoordinate=%g,%g,0.54,1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8\n", i, x, y, x, y
  }
}'
