#!/usr/bin/env bash
# Writes the render benchmark's generated scene to stdout: N objects
# (default 5000) of every primitive kind and 16 materials scattered over a
# 120 m x 120 m yard, a ground, a sun and a camera at 1280x800 looking over
# the yard from one corner (so part of the yard is outside its view, as in
# a real scene).  Deterministic: integer hashing, no random generator.
#   bash bench/render/gen.sh [N] > scene.rscene
set -euo pipefail
n=${1:-5000}
awk -v n="$n" 'BEGIN {
  print "raisim_engine_scene 1"
  print "environment 0.38 0.38 0.38 0.15 0.16 0.2 0 true true 10 - backgroundMode=rayrai_sky"
  print "weather true preset=clear timeOfDay=15"
  for (m = 0; m < 16; ++m) {
    r = 0.2 + 0.05 * (m % 7); g = 0.25 + 0.04 * ((m * 3) % 11); b = 0.3 + 0.03 * ((m * 5) % 13)
    printf "material mat%d %.3f %.3f %.3f 1 %.2f %.2f 0 0 0 0 false - - - - - - id=mat%d\n", m, r, g, b, (m % 4 == 0) ? 0.8 : 0, 0.3 + 0.04 * m, m
  }
  print "light /World/Sun -0.4 0.3 -1 3 type=directional shadows=true"
  print "camera /World/Cam -70 -70 30 0.8876 -0.1124 0.1913 0.4054 55 0.1 400 1280 800 rgb true id=cam"
  print "object /World/Ground ground 0 0 0 1 0 0 0 200 200 1 1 0 0 default mat0 false true true - static true 1 18446744073709551615"
  split("box sphere cylinder capsule box", kinds, " ")
  s = 12345
  for (i = 0; i < n; ++i) {
    s = (s * 1103515245 + 12345) % 2147483648; x = (s % 12000) / 100 - 60
    s = (s * 1103515245 + 12345) % 2147483648; y = (s % 12000) / 100 - 60
    s = (s * 1103515245 + 12345) % 2147483648; k = kinds[1 + s % 5]
    s = (s * 1103515245 + 12345) % 2147483648; sz = 0.3 + (s % 100) / 100
    s = (s * 1103515245 + 12345) % 2147483648; yaw = (s % 628) / 200
    qw = cos(yaw); qz = sin(yaw)
    if (k == "capsule") { rad = 0.15 + 0.05 * (i % 4); h = 0.6 + 0.2 * (i % 3) } else { rad = sz / 2; h = sz }
    z = (k == "box") ? sz / 2 : (k == "capsule") ? rad + h / 2 : (k == "sphere") ? rad : h / 2
    printf "object /World/O%d %s %.2f %.2f %.3f %.4f 0 0 %.4f %.2f %.2f %.2f %.3f %.3f 1 default mat%d false true false - static true 1 18446744073709551615\n", i, k, x, y, z, qw, qz, sz, sz, sz, rad, h, i % 16
  }
}'
