#!/usr/bin/env bats
# Issue 15's round trips, end to end through the real tools:
#  - every RaiSim example world (../shared/spec/raisim/xml-examples):
#    rscene-from-xml | rscene-to-xml | rscene-from-xml reproduces the first
#    .rscene byte for byte;
#  - every physics fixture of the project: rscene-to-xml | rscene-from-xml
#    gives back its physics records (rscene-diff on the physics records,
#    visual keys ignored);
#  - the same physics: rscene-sim's trajectories of a scene and of its
#    round trip agree to 1e-9 over 2 s;
#  - the templated world: sphere_count=20 gives 20 spheres where the
#    expressions put them, exist=false removes them.

BIN="${RSCENE_BIN:-$BATS_TEST_DIRNAME/../build/bin}"
ROOT="$BATS_TEST_DIRNAME/.."
DATA="$ROOT/tests/data"
SHARED="$ROOT/../shared"
EXAMPLES="$SHARED/spec/raisim/xml-examples"
TO="$BIN/rscene-to-xml"
FROM="$BIN/rscene-from-xml"

bats_require_minimum_version 1.5.0

setup() {
  [ -x "$TO" ] && [ -x "$FROM" ] || skip "rscene-to-xml/rscene-from-xml not built in $BIN"
  mkdir "$BATS_TEST_TMPDIR/w"
  cd "$BATS_TEST_TMPDIR/w"
}

# The parameters an example needs (spheres.xml uses four it does not set).
example_params() {
  case $1 in
    spheres.xml)
      echo "--param sphere_count=20 --param spawn_sphere=true --param spawn_box=true --param sphere_height_offset=0.1" ;;
  esac
}

# from-xml | to-xml | from-xml of example $1 in the current folder: first.rscene,
# world.xml, second.rscene (all in one folder, so relative paths agree).
example_round_trip() {
  # shellcheck disable=SC2046
  "$FROM" -q "$EXAMPLES/$1" $(example_params "$1") -o first.rscene
  "$TO" -q first.rscene -o world.xml
  "$FROM" -q world.xml -o second.rscene
}

@test "every xml-example: from-xml | to-xml | from-xml reproduces the first .rscene byte for byte" {
  [ -d "$EXAMPLES" ] || skip "no $EXAMPLES"
  n=0
  for path in "$EXAMPLES"/*.xml; do
    f=$(basename "$path")
    mkdir "$f.d"
    (cd "$f.d" && example_round_trip "$f") || { echo "$f: a conversion failed"; return 1; }
    cmp "$f.d/first.rscene" "$f.d/second.rscene" || { diff "$f.d/first.rscene" "$f.d/second.rscene" | head -20; echo "$f differs"; return 1; }
    # The first .rscene is canonical and a scene rscene-sim accepts.
    "$BIN/rscene-fmt" --check "$f.d/first.rscene"
    n=$((n + 1))
  done
  [ "$n" -eq 5 ]
}

@test "SingleBodies.xml: the missing monkey mesh is converted as written (a path, not a failure); sim names it" {
  [ -f "$EXAMPLES/SingleBodies.xml" ] || skip "no $EXAMPLES"
  # The mesh refers to ../../monkey/monkey.obj, which RaiSim's examples
  # ship and ../shared does not: from-xml writes the path (relative to the
  # output's folder) and succeeds, as rscene-to-xml writes a missing mesh's
  # path; only the simulator needs the file.
  run -0 --separate-stderr "$FROM" "$EXAMPLES/SingleBodies.xml" -o single.rscene
  run -0 grep -c '^object /World/mesh mesh .*monkey/monkey.obj' single.rscene
  [ "$output" = 1 ]
  run -2 --separate-stderr "$BIN/rscene-sim" --steps 1 single.rscene
  [[ $stderr == *"monkey.obj"* ]]
  run -0 "$BIN/rscene-sim" --steps 1 --allow-missing-assets single.rscene
}

@test "spheres.xml with sphere_count=20: 20 spheres and 20 boxes where the expressions put them" {
  [ -f "$EXAMPLES/spheres.xml" ] || skip "no $EXAMPLES"
  run -0 "$FROM" -q "$EXAMPLES/spheres.xml" $(example_params spheres.xml)
  scene=$output
  run -0 grep -c '^object /World/sphere_array_[0-9]* sphere ' <<<"$scene"
  [ "$output" = 20 ]
  # 20 boxes all named "box": the first keeps /World/box, the others _2 ... _20.
  run -0 grep -c '^object /World/box\(_[0-9]*\)\? box ' <<<"$scene"
  [ "$output" = 20 ]
  # Sphere idx: position (cos(0.1 idx)(0.2 idx + 0.1), sin(0.1 idx)(0.2 idx + 0.1), 0.1 + idx),
  # radius 0.5 + 0.001 idx; compared to 1e-12 against awk's own evaluation.
  for idx in 0 1 7 19; do
    line=$(awk -v p="/World/sphere_array_$idx" '$1 == "object" && $2 == p' <<<"$scene")
    [ -n "$line" ] || { echo "no sphere $idx"; return 1; }
    awk -v i="$idx" '{
      r = 0.2 * i + 0.1
      want[1] = cos(0.1 * i) * r; want[2] = sin(0.1 * i) * r; want[3] = 0.1 + i * 1.0
      for (k = 1; k <= 3; ++k) if ((d = $(3 + k) - want[k]) > 1e-12 || d < -1e-12) { print "sphere " i " coordinate " k ": " $(3 + k) " want " want[k]; exit 1 }
      if ((d = $14 * $11 - (0.5 + i * 0.001)) > 1e-12 || d < -1e-12) { print "sphere " i " radius " $14 " x " $11; exit 1 }
    }' <<<"$line"
  done
  # Box idx: (cos(0.1 idx)(0.3 idx + 0.2), sin(0.1 idx)(0.3 idx + 0.2), 0.1 + idx); the 8th is idx 7.
  line=$(awk '$1 == "object" && $2 == "/World/box_8"' <<<"$scene")
  awk '{ i = 7; r = 0.3 * i + 0.2
    if ((d = $4 - cos(0.1 * i) * r) > 1e-12 || d < -1e-12 || (d = $5 - sin(0.1 * i) * r) > 1e-12 || d < -1e-12 || $6 != 7.1) { print "box_8 at " $4, $5, $6; exit 1 } }' <<<"$line"
}

@test "spheres.xml: exist=false removes the spheres or the boxes; sphere_count=0 leaves an empty world" {
  [ -f "$EXAMPLES/spheres.xml" ] || skip "no $EXAMPLES"
  common="--param sphere_count=20 --param sphere_height_offset=0.1"
  run -0 "$FROM" -q "$EXAMPLES/spheres.xml" $common --param spawn_sphere=false --param spawn_box=true
  [ "$(grep -c ' sphere ' <<<"$output")" = 0 ]
  [ "$(grep -c '^object /World/box.* box ' <<<"$output")" = 20 ]
  run -0 "$FROM" -q "$EXAMPLES/spheres.xml" $common --param spawn_sphere=true --param spawn_box=false
  [ "$(grep -c '^object /World/sphere_array_.* sphere ' <<<"$output")" = 20 ]
  [ "$(grep -c ' box ' <<<"$output")" = 0 ]
  run -0 "$FROM" -q "$EXAMPLES/spheres.xml" --param sphere_count=0 --param spawn_sphere=true --param spawn_box=true \
    --param sphere_height_offset=0.1
  [ "$(grep -c '^object ' <<<"$output")" = 0 ]
  # A parameter used and not set is an error naming it.
  run -2 --separate-stderr "$FROM" "$EXAMPLES/spheres.xml" --param sphere_count=20 --param spawn_box=true \
    --param sphere_height_offset=0.1
  [[ $stderr == *"spheres.xml:"*"spawn_sphere"* ]]
}

# --- physics fixtures: to-xml | from-xml keeps the physics records --------

# The fixtures of the project with simulated bodies that rscene-sim
# accepts (the others are refused on purpose: bad masses, broken
# compounds, syntax errors, or hold no body at all).
physics_fixtures() {
  printf '%s\n' \
    examples/gallery.rscene examples/robot_cell.rscene examples/showroom_v2.rscene examples/soft_bodies.rscene \
    examples/terrain_field.rscene examples/warehouse_crates.rscene \
    tests/data/diff_new.rscene tests/data/diff_old.rscene tests/data/fmt_canonical.rscene \
    tests/data/fmt_v2_escapes.rscene tests/data/render_mesh.rscene tests/data/render_minimal.rscene \
    tests/data/render_post.rscene tests/data/render_skipped.rscene tests/data/sim_drop.rscene \
    tests/data/sim_missing_mesh.rscene tests/data/sim_unsupported.rscene tests/data/validate_clean.rscene \
    tests/data/validate_mesh.rscene tests/data/robots/check/walker.rscene \
    tests/data/xml/bodies.rscene tests/data/xml/robot.rscene
}

# The physics records of scene $1 (stdin): the kinds rscene-to-xml writes,
# less visual-only objects (#17 visualOnly=true or bodyMode visual_only, or
# collidable=false), in canonical order.
physics_records() {
  "$BIN/rscene-fmt" - | awk '
    $1 == "raisim_engine_scene" || $1 == "time_step" || $1 == "gravity" || $1 == "solver" || $1 == "contact_material" { print; next }
    $1 == "compound" || $1 == "compound_child" || $1 == "terrain_region" || $1 == "articulated_resource" || $1 == "articulated" || $1 == "wire" { print; next }
    $1 == "object" { if (NF >= 25 && ($19 == "true" || $23 ~ /^visual/ || $24 == "false")) next; print }'
}

# Fields with no XML equivalent (visual, editor, identity): rscene-diff
# --ignore list.  Ids are ignored because the XML names bodies by path
# (a wire's bodyA=/World/Box where the original wrote bodyA=box is the
# same body; bodyA/bodyB are compared through to-xml below).
VISUAL_KEYS=id,parentGroupId,material,visible,visualOnly,locked,castShadow,receiveShadow,semanticClass,instanceId,segmentationColor,materialRemaps,renderMeshPath,visualUseMeshColor,visualTwoSided,visualShadowCasting,baseTexture,textureSplattingEnabled,texturePrimary,textureSecondary,textureBlend,wetness,holes,vertexColors,lodLevels,collisionShapeSize,location,enabled,visualizationWidth

# Round trip of fixture $1 (relative to $ROOT) into rt.xml and rt.rscene
# here.  Both tools run in the fixture's folder, reading and writing
# through pipes named as files there (--stdin-filename), so the asset paths
# of rt.rscene are relative to the same folder as the fixture's and mean
# the same files; nothing is written into the repository.
round_trip() {
  local dir
  dir="$ROOT/$(dirname "$1")"
  (cd "$dir" && "$TO" -q "$(basename "$1")") >rt.xml || { echo "$1: rscene-to-xml failed"; return 1; }
  (cd "$dir" && "$FROM" -q - --stdin-filename rt.xml) <rt.xml >rt.rscene || { echo "$1: rscene-from-xml failed"; return 1; }
}

@test "every physics fixture: to-xml | from-xml gives back its physics records (rscene-diff exits 0)" {
  n=0
  while read -r f; do
    [ -f "$ROOT/$f" ] || { echo "fixture $f is gone: update physics_fixtures"; return 1; }
    round_trip "$f"
    physics_records <"$ROOT/$f" >orig.rscene
    run "$BIN/rscene-diff" --ignore-editor-state --ignore "$VISUAL_KEYS" orig.rscene rt.rscene
    [ "$status" -eq 0 ] || { echo "$f: the round trip lost or changed physics:"; echo "$output" | head -30; return 1; }
    n=$((n + 1))
  done < <(physics_fixtures)
  [ "$n" -eq 22 ]
}

# Compares two rscene-sim CSV trajectories: the same lines and paths, and
# every number within $3; prints the largest difference.  Fails otherwise.
same_trajectory() {
  awk -F, -v tol="$3" '
    NR == FNR { first[FNR] = $0; n = FNR; next }
    {
      m = FNR
      if (!(FNR in first)) { print "line " FNR " only in the second"; bad = 1; exit }
      k = split(first[FNR], a, ",")
      if (k != NF) { print "line " FNR ": " k " fields against " NF; bad = 1; exit }
      for (i = 1; i <= NF; ++i) {
        if (a[i] == $i) continue
        if (a[i] !~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/ || $i !~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/) {
          print "line " FNR " field " i ": " a[i] " against " $i; bad = 1; exit
        }
        d = a[i] - $i; if (d < 0) d = -d
        if (d > max) { max = d; where = "line " FNR " field " i }
      }
    }
    END {
      if (!bad && m != n) { print n " lines against " m; bad = 1 }
      printf "max |delta| %.3g (%s) over %d lines\n", max, where == "" ? "none" : where, m
      exit bad || max > tol
    }' "$1" "$2"
}

@test "the same physics: rscene-sim trajectories of a scene and of its XML round trip agree to 1e-9 over 2 s" {
  # bodies: dynamic spheres, boxes (one with a custom inertia), a capsule, a
  # cylinder, a mesh, a compound, a height field, a stiff wire, contact
  # materials with restitution; robot: a floating-base URDF robot with joint
  # velocities and a wire to a crate; robot_cell: the example (robot, cart
  # compound, wire between them, sensors that are not exported).
  for f in tests/data/xml/bodies.rscene tests/data/xml/robot.rscene examples/robot_cell.rscene; do
    round_trip "$f"
    dir="$ROOT/$(dirname "$f")"
    "$BIN/rscene-sim" --duration 2 --trajectory-format csv --trajectory orig.csv -o /dev/null "$ROOT/$f" 2>/dev/null
    "$BIN/rscene-sim" --duration 2 --trajectory-format csv --trajectory rt.csv --base-dir "$dir" -o /dev/null rt.rscene 2>/dev/null
    [ "$(wc -l <orig.csv)" -gt 1000 ]
    run same_trajectory orig.csv rt.csv 1e-9
    echo "# $f: $output" >&3
    [ "$status" -eq 0 ] || { echo "$f: $output"; return 1; }
  done
}

@test "same_trajectory fails on a difference above the tolerance and on a missing body" {
  printf 'time,path,px\n0,/World/a,1\n0.1,/World/a,1.5\n' >a.csv
  printf 'time,path,px\n0,/World/a,1\n0.1,/World/a,1.5000001\n' >b.csv
  run -1 same_trajectory a.csv b.csv 1e-9
  [[ $output == *"max |delta| 1e-07 (line 3 field 3)"* ]]
  run -0 same_trajectory a.csv b.csv 1e-6
  head -2 a.csv >c.csv
  run -1 same_trajectory a.csv c.csv 1e-9
  sed 's#/World/a#/World/b#' a.csv >d.csv
  run -1 same_trajectory a.csv d.csv 1e-9
  [[ $output == *"field 2: /World/a against /World/b"* ]]
}
