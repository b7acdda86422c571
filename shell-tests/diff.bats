#!/usr/bin/env bats
# End-to-end tests of rscene-diff: output blocks, every flag, exit
# statuses like diff(1), and git's external diff driver in a real
# temporary repository (`git diff` and `git log -p --ext-diff`).

load helpers
DIFF="$BIN/rscene-diff"
OLD="$DATA/diff_old.rscene"
NEW="$DATA/diff_new.rscene"

setup() {
  needs_tools rscene-diff
  in_workdir
}

expected_blocks() {
  cat <<'EOF2'
~ editor_ux
    multiSelect: true -> false
~ group /World
    locked: false -> true
~ terrain_region /World/T
    heights: 25 values, 2 changed, max |delta| 0.03
    heights[6]: 0 -> 0.03
    heights[17]: 0 -> 0.01
+ light /World/Sun
    direction: 0,0,-1
    intensity: 3
    id: light_sun
    type: directional
- light /World/Fill
    direction: 0,0,-1
    intensity: 0.8
    id: light_fill
    type: point
~ object /World/Props/Box (moved from /World/Box)
~ object /World/Crate
    position: 1,0,0.5 -> 1,0,0.5000000001
    mass: 1 -> 3
EOF2
}

@test "blocks of +, - and ~ with name: old -> new; exit 1 when different" {
  run -1 --separate-stderr "$DIFF" "$OLD" "$NEW"
  [ "$output" = "$(expected_blocks)" ]
  [ -z "$stderr" ]
}

@test "the same scene reordered and respelt is no change: exit 0, no output" {
  [ -x "$BIN/rscene-fmt" ] || skip "rscene-fmt not built"
  "$BIN/rscene-fmt" "$ROOT/tests/data/fmt_messy.rscene" >canonical.rscene
  run -0 "$DIFF" "$ROOT/tests/data/fmt_messy.rscene" canonical.rscene
  [ -z "$output" ]
}

@test "--stat prints counts per kind" {
  run -1 "$DIFF" --stat "$OLD" "$NEW"
  [ "${lines[0]}" = " editor_ux       1 changed" ]
  [ "${lines[2]}" = " light           1 added, 1 removed" ]
  [ "${lines[3]}" = " object          2 changed" ]
  [ "${lines[5]}" = " 7 records: 5 changed, 1 added, 1 removed" ]
}

@test "--format json for machines, also when the scenes are the same" {
  command -v jq >/dev/null || skip "jq not installed"
  run -0 bash -c "'$DIFF' --format json '$OLD' '$NEW' | jq -c '.same, .stat, [.records[] | select(.tag == \"object\") | .oldPath // .fields[1].new]'"
  [ "${lines[0]}" = "false" ]
  [ "${lines[1]}" = '{"added":1,"removed":1,"changed":5,"fieldsChanged":5}' ]
  [ "${lines[2]}" = '["/World/Box",3]' ]  # typed values
  run -0 bash -c "'$DIFF' --format=json '$OLD' '$OLD' | jq -c .same"
  [ "$output" = "true" ]
  run -2 "$DIFF" --format yaml "$OLD" "$NEW"
}

@test "--tolerance and --rel-tolerance hide float noise" {
  run -1 "$DIFF" --tolerance 1e-6 "$OLD" "$NEW"
  [[ $output != *"position:"* ]]
  [[ $output == *"mass: 1 -> 3"* ]]
  run -1 "$DIFF" --rel-tolerance 1e-6 "$OLD" "$NEW"
  [[ $output != *"position:"* ]]
  run -2 "$DIFF" --tolerance -1 "$OLD" "$NEW"
  run -2 --separate-stderr "$DIFF" --tolerance x "$OLD" "$NEW"
  [ "${stderr_lines[0]}" = "rscene-diff: error: --tolerance: expected a plain number >= 0 (e.g. 0.001 or 1e-6), not 'x'" ]
}

@test "--format json: old and new values typed by the schema" {
  command -v jq >/dev/null || skip "jq not installed"
  "$DIFF" --format json "$OLD" "$NEW" >out.json || [ $? -eq 1 ]
  run -0 jq -c '[.records[].fields[]? | select(.name == "position" or .name == "locked" or .name == "heights[6]")
    | [.name, .type, .old, .new]]' out.json
  [ "$output" = '[["locked","flag",false,true],["heights[6]","number",0,0.03],["position","vec3",[1,0,0.5],[1,0,0.5000000001]]]' ]
}

@test "--ignore-editor-state and --ignore KEY,..." {
  run -1 "$DIFF" --ignore-editor-state "$OLD" "$NEW"
  [[ $output != *"editor_ux"* && $output != *"locked"* ]]
  run -1 "$DIFF" --ignore heights,object.mass,position "$OLD" "$NEW"
  [[ $output != *"heights"* && $output != *"mass"* && $output != *"position"* ]]
  [[ $output == *"multiSelect"* ]]
}

@test "--ignore NAME that names no field is a usage error with a suggestion" {
  run -2 --separate-stderr "$DIFF" --ignore heights,colr "$OLD" "$NEW"
  [ "$stderr" = "rscene-diff: error: --ignore: no field 'colr'; did you mean 'color'?" ]
  [ -z "$output" ]
  run -2 --separate-stderr "$DIFF" --ignore objct.mass "$OLD" "$NEW"
  [ "$stderr" = "rscene-diff: error: --ignore: no record kind 'objct'; did you mean 'object'?" ]
}

@test "-q and --quiet print nothing; the exit status tells" {
  run -1 "$DIFF" -q "$OLD" "$NEW"
  [ -z "$output" ]
  run -0 "$DIFF" --quiet "$OLD" "$OLD"
  [ -z "$output" ]
}

@test "standard input on one side, named by --stdin-filename" {
  run -1 bash -c "'$DIFF' - '$NEW' < '$OLD'"
  [[ $output == *"mass: 1 -> 3"* ]]
  run -2 --separate-stderr "$DIFF" --stdin-filename old.rscene - "$NEW" <<<"time_step 1"
  [ "${stderr_lines[0]}" = "old.rscene:1:1: error: missing raisim_engine_scene header [RS1001]" ]
  run -2 "$DIFF" - - </dev/null
}

@test "formatting is never a difference: every fixture, example and corpus scene against its formatted self" {
  [ -x "$BIN/rscene-fmt" ] || skip "rscene-fmt not built"
  n=0
  # tests/data/**, examples/ and ../shared/corpus/ (which may be absent)
  for f in $(find "$DATA" -name '*.rscene') "$ROOT"/examples/*.rscene "$CORPUS"/*.rscene; do
    [ -f "$f" ] || continue
    "$BIN/rscene-fmt" "$f" >formatted.rscene 2>/dev/null || continue  # fixtures of parse errors
    run "$DIFF" "$f" formatted.rscene
    [ "$status" -eq 0 ] || { echo "$f:"; echo "$output"; false; }
    n=$((n + 1))
  done
  [ "$n" -ge 15 ]
}

@test "issue 9: terrain_field.rscene against its formatted self, with a process substitution" {
  [ -x "$BIN/rscene-fmt" ] || skip "rscene-fmt not built"
  run -0 bash -c "'$DIFF' '$ROOT/examples/terrain_field.rscene' <('$BIN/rscene-fmt' '$ROOT/examples/terrain_field.rscene')"
  [ -z "$output" ]
}

@test "children are named by parent path and place; long lists name changed entries" {
  { cat "$OLD"; echo "compound /World/Cart 0 0 1 1 0 0 0 1 1 1 5 dynamic true true id=cart"
    echo "compound_child /World/Cart box 0 0 0 1 0 0 0 1 1 1 size=1.0,0.6,0.10"
    echo "compound_child /World/Cart sphere 0 0 0.5 1 0 0 0 1 1 1 radius=0.25"
    echo "deformable /World/Cloth cloth - 0 0 2 1 0 0 0 1 1 1 id=cloth scale=1"
    printf 'instanced_visual /World/Grass box id=grass instances=0,0,0,1,0,0,0,1,1,1'
    for i in 1 2 3 4; do printf ';%d,0,0,1,0,0,0,1,1,1' "$i"; done; echo; } >a.rscene
  sed -e 's/radius=0.25/radius=0.3/' -e 's/size=1.0,0.6,0.10/size=1,0.6,0.1/' -e 's/scale=1$/scale=2/' \
    -e 's/;3,0,0,1,0,0,0,1,1,1/;3,0,0.5,1,0,0,0,2,2,2/' a.rscene >b.rscene
  run -1 "$DIFF" a.rscene b.rscene
  [ "$output" = "~ compound_child /World/Cart[1]
    radius: 0.25 -> 0.3
~ deformable /World/Cloth
    scale (key): 1 -> 2
~ instanced_visual /World/Grass
    instances: 5 entries, 1 changed, max |delta| 1
    instances[3].position: 3,0,0 -> 3,0,0.5
    instances[3].scale: 1,1,1 -> 2,2,2" ]
}

@test "trouble is exit 2: unreadable file, wrong operand count" {
  run -2 --separate-stderr "$DIFF" "$OLD" missing.rscene
  [ "${stderr_lines[0]}" = "rscene-diff: error: cannot read 'missing.rscene': No such file or directory" ]
  run -2 "$DIFF" "$OLD"
  run -2 "$DIFF" a b c
}

@test "seven arguments: git's external diff form exits 0" {
  run -0 "$DIFF" scene.rscene "$OLD" 1111111 100644 "$NEW" 2222222 100644
  [ "${lines[0]}" = "rscene-diff a/scene.rscene b/scene.rscene" ]
  [ "${lines[1]}" = "~ editor_ux" ]
  # An added scene: /dev/null as git writes it, and every record with its
  # values (issue 27); a deleted one the same way round.
  run -0 "$DIFF" new.rscene /dev/null . . "$NEW" 2222222 100644
  [ "${lines[0]}" = "rscene-diff /dev/null b/new.rscene" ]
  [ "${lines[1]}" = "+ raisim_engine_scene" ]
  [ "${lines[2]}" = "    version: 1" ]
  [ "${lines[3]}" = "+ time_step" ]
  [ "${lines[4]}" = "    dt: 0.0025" ]
  [[ $output == *$'\n+ object /World/Crate\n    primitive: box\n    position: 1,0,0.5000000001\n'* ]]
  [[ $output == *$'\n    mass: 3\n'* ]]
  run -0 "$DIFF" old.rscene "$OLD" 1111111 100644 /dev/null . .
  [ "${lines[0]}" = "rscene-diff a/old.rscene /dev/null" ]
  [ "${lines[3]}" = "- time_step" ]
  [ "${lines[4]}" = "    dt: 0.0025" ]
  [[ $output == *$'\n- light /World/Fill\n    direction: 0,0,-1\n    intensity: 0.8\n'* ]]
  # Outside git's mode, an added record lists its values too.
  run -1 "$DIFF" "$OLD" "$NEW"
  [[ $output == *$'\n+ light /World/Sun\n    direction: 0,0,-1\n    intensity: 3\n'* ]]
}

@test "git mode: a side that does not parse gives a header and a line diff, exit 0" {
  printf 'raisim_engine_scene 1\ntime_step 0.0025\nobject /World/Box box 0 0\n' >broken.rscene
  run -0 --separate-stderr "$DIFF" scene.rscene "$OLD" 1111111 100644 broken.rscene 2222222 100644
  [ "${lines[0]}" = "rscene-diff a/scene.rscene b/scene.rscene" ]
  [ "${lines[1]}" = "--- a/scene.rscene" ]
  [ "${lines[2]}" = "+++ b/scene.rscene" ]
  [[ ${lines[3]} == "@@ "* ]]
  [[ $output == *$'\n+object /World/Box box 0 0'* ]]
  [[ $output == *$'\n-solver 80 1e-07 0.2 accurate'* ]]
  [ "$stderr" = "b/scene.rscene:3:26: warning: object has 4 positional fields, expected 25, 19 or 17; showing a line diff [RS1007]" ]
  # Outside git's mode a parse error is still trouble.
  run -2 "$DIFF" "$OLD" broken.rscene
}

@test "git mode: added or deleted broken scenes, binary junk, nine arguments for a rename" {
  printf 'not a scene\n' >broken.rscene
  run -0 --separate-stderr "$DIFF" new.rscene /dev/null . . broken.rscene 2222222 100644
  [ "$output" = $'rscene-diff /dev/null b/new.rscene\n--- /dev/null\n+++ b/new.rscene\n@@ -0,0 +1,1 @@\n+not a scene' ]
  run -0 --separate-stderr "$DIFF" old.rscene broken.rscene 1111111 100644 /dev/null . .
  [ "${lines[0]}" = "rscene-diff a/old.rscene /dev/null" ]
  [ "${lines[1]}" = "--- a/old.rscene" ]
  [ "${lines[2]}" = "+++ /dev/null" ]
  printf 'junk\0\001\n' >junk.rscene
  run -0 --separate-stderr "$DIFF" junk.rscene "$OLD" 1111111 100644 junk.rscene 2222222 100644
  [ "$output" = $'rscene-diff a/junk.rscene b/junk.rscene\nBinary files a/junk.rscene and b/junk.rscene differ' ]
  run -0 --separate-stderr "$DIFF" junk.rscene junk.rscene 1111111 100644 junk.rscene 2222222 100644
  [ -z "$output" ]
  run -0 "$DIFF" old.rscene "$OLD" 1111111 100644 "$NEW" 2222222 100644 new.rscene "similarity index 90%"
  [ "${lines[0]}" = "rscene-diff a/old.rscene b/new.rscene" ]
  [ "${lines[1]}" = "~ editor_ux" ]
  run -2 "$DIFF" a b c d e f g h
  # git's operands may start with `-`: never read as options.
  hex=0123456789abcdef0123456789abcdef01234567
  cp "$NEW" ./-new.rscene
  run -0 "$DIFF" --stat -x.rscene "$OLD" $hex 100644 -new.rscene $hex 100644
  [ "${lines[0]}" = "rscene-diff a/-x.rscene b/-x.rscene" ]
  [ "${lines[1]}" = " editor_ux       1 changed" ]
}

@test "git diff and git log -p --ext-diff use it through .gitattributes" {
  command -v git >/dev/null || skip "git not installed"
  git init -q repo
  cd repo
  git config user.email t@example.com
  git config user.name t
  git config diff.rscene.command "$DIFF"
  echo '*.rscene diff=rscene' >.gitattributes
  cp "$OLD" scene.rscene
  git add .gitattributes scene.rscene
  git commit -q -m one
  cp "$NEW" scene.rscene
  run -0 git diff
  [ "${lines[0]}" = "rscene-diff a/scene.rscene b/scene.rscene" ]
  [[ $output == *"~ object /World/Props/Box (moved from /World/Box)"* ]]
  [[ $output != *"@@"* ]]
  git commit -q -am two
  run -0 git log -p --ext-diff --format=%s
  [[ $output == *"mass: 1 -> 3"* ]]
  [[ $output == *"+ time_step"* ]]  # the first commit adds the file
  run -0 git log -p --format=%s
  [[ $output == *"@@"* ]]  # without --ext-diff, log keeps line diffs
}

@test "--help and --version" {
  run -0 "$DIFF" --help
  [[ $output == *"--ignore-editor-state"* && $output == *"--rel-tolerance"* ]]
  run -0 "$DIFF" --version
  [[ $output == "rscene-diff "* ]]
  run -2 "$DIFF" --no-such-flag "$OLD" "$NEW"
}

# Robots (issue 11): generalizedCoordinate entries named by joint.
ROBOTS="$DATA/robots/check"

walker() {  # $1: the knee value of the left leg; $2: the robot file
  printf '%s\n' "raisim_engine_scene 1" "articulated_resource walker_res Walker ${2:-$ROBOTS/walker.urdf}" \
    "articulated /World/W walker_res 0 0 0.5 1 0 0 0 true true id=walker generalizedCoordinate=0,0,0.5,1,0,0,0,0.3,$1,0.3,-0.6 generalizedVelocity=0,0,0,0,0,0,0,0,0,0"
}

@test "robots: generalizedCoordinate diffs name the joint when the model is readable; JSON too" {
  walker -0.6 > a.rscene
  walker -0.55 > b.rscene
  run -1 "$DIFF" a.rscene b.rscene
  [ "$output" = "~ articulated /World/W
    generalizedCoordinate[L_KNEE]: -0.6 -> -0.55" ]
  run -1 "$DIFF" --format json a.rscene b.rscene
  echo "$output" > d.json
  run -0 jq -r '.records[0].fields[0] | "\(.name) \(.old) \(.new)"' d.json
  [ "$output" = "generalizedCoordinate[L_KNEE] -0.6 -0.55" ]
  run -0 "$DIFF" --tolerance 0.1 a.rscene b.rscene
}

@test "robots: without a readable model the list changes as a whole" {
  walker -0.6 nowhere.urdf > a.rscene
  walker -0.55 nowhere.urdf > b.rscene
  run -1 "$DIFF" a.rscene b.rscene
  [ "${lines[1]}" = "    generalizedCoordinate: 0,0,0.5,1,0,0,0,0.3,-0.6,0.3,-0.6 -> 0,0,0.5,1,0,0,0,0.3,-0.55,0.3,-0.6" ]
}

@test "robots: a new jointOrder that reorders the numbers to match is no change in the coordinate" {
  # Left leg 0.3,-0.6 and right leg 0.2,-0.5 on both sides, written in two orders.
  order() {
    printf '%s\n' "raisim_engine_scene 1" "articulated_resource walker_res Walker $ROBOTS/walker.urdf" \
      "articulated /World/W walker_res 0 0 0.5 1 0 0 0 true true id=walker $1 generalizedCoordinate=0,0,0.5,1,0,0,0,$2"
  }
  order "" 0.3,-0.6,0.2,-0.5 > a.rscene
  order "jointOrder=R_HIP;R_KNEE;L_HIP;L_KNEE" 0.2,-0.5,0.3,-0.6 > b.rscene
  run -1 "$DIFF" a.rscene b.rscene
  [ "$output" = "~ articulated /World/W
    + jointOrder: R_HIP;R_KNEE;L_HIP;L_KNEE" ]
}

@test "robots: the ANYmal C's 19 coordinates keep the summary line, the changed entry named" {
  needs_shared corpus/robots/anymal_c
  anymal() {
    printf '%s\n' "raisim_engine_scene 1" \
      "articulated_resource anymal_res ANYmal $CORPUS/robots/anymal_c/urdf/anymal.urdf" \
      "articulated /World/Anymal anymal_res 0 0 0.54 1 0 0 0 true true generalizedCoordinate=0,0,0.54,1,0,0,0,0.03,0.4,$1,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8"
  }
  anymal -0.8 > a.rscene
  anymal -0.75 > b.rscene
  run -1 "$DIFF" a.rscene b.rscene
  [ "${lines[2]}" = "    generalizedCoordinate[LF_KFE]: -0.8 -> -0.75" ]
}

@test "robots: git's external diff names joints too (the old side is a temporary file)" {
  git init -q repo && cd repo
  git config user.email t@example.org && git config user.name t
  cp "$ROBOTS/walker.urdf" .
  walker -0.6 walker.urdf > s.rscene
  git add . && git commit -qm one
  walker -0.5 walker.urdf > s.rscene
  echo '*.rscene diff=rscene' > .gitattributes
  git config diff.rscene.command "$DIFF"
  run -0 git diff
  [[ "$output" == *"generalizedCoordinate[L_KNEE]: -0.6 -> -0.5"* ]]
}

# Issue 27: a scene sent through rscene-to-xml and back has no ids; its
# records are matched by path, not shown as removed and added.
@test "a round trip through XML: records match by path; --ignore id matches by path alone" {
  needs_tools rscene-to-xml rscene-from-xml
  "$BIN/rscene-to-xml" -o crates.xml "$ROOT/examples/warehouse_crates.rscene" 2>/dev/null
  "$BIN/rscene-from-xml" -o back.rscene crates.xml
  ! grep -q ' id=' back.rscene  # the XML carries no ids
  run -1 "$DIFF" "$ROOT/examples/warehouse_crates.rscene" back.rscene
  [[ $output != *"+ object"* && $output != *"- object"* ]]
  [[ $output == *$'\n~ object /World/Props/CrateA\n'*$'\n    - id: object_cratea\n    - parentGroupId: folder_props\n'* ]]
  # What the XML cannot carry: lights, camera, materials' looks,
  # environment, weather, groups (removed), an object's material, and the
  # unused radius and height of a box.
  run -1 "$DIFF" --stat "$ROOT/examples/warehouse_crates.rscene" back.rscene
  [ "${lines[6]}" = " object       5 changed" ]
  [ "${lines[8]}" = " 16 records: 5 changed, 11 removed" ]
  run -1 "$DIFF" --ignore id,parentGroupId,radius,height,material --ignore-editor-state --tolerance 0.002 \
    "$ROOT/examples/warehouse_crates.rscene" back.rscene
  # Left: the ground's drawn size (a ground is a half-space in XML); the crates are the same.
  [ "$(grep -A1 '^~' <<<"$output")" = $'~ object /World/Ground\n    scale: 18,18,1 -> 10,10,1' ]
  # Another id at the same path is another record, unless ids are ignored.
  sed 's/id=object_cratea/id=crate_one/' "$ROOT/examples/warehouse_crates.rscene" >renamed.rscene
  run -1 "$DIFF" "$ROOT/examples/warehouse_crates.rscene" renamed.rscene
  [ "${lines[0]}" = "+ object /World/Props/CrateA" ]
  [[ $output == *$'\n- object /World/Props/CrateA\n'* ]]
  run -0 "$DIFF" --ignore id "$ROOT/examples/warehouse_crates.rscene" renamed.rscene
  [ -z "$output" ]
  run -0 "$DIFF" --ignore object.id "$ROOT/examples/warehouse_crates.rscene" renamed.rscene
  run -1 "$DIFF" --ignore light.id "$ROOT/examples/warehouse_crates.rscene" renamed.rscene
}

@test "--review DIR with --camera, --width and --height (diff_review.bats tests the review itself)" {
  "$DIFF" --help | grep -q -- --review || skip "rscene-diff built without lib/render"
  LP_NUM_THREADS=1 run "$DIFF" -q --review r --camera auto --width 48 --height 32 "$OLD" "$OLD"
  [ "$status" -eq 0 ]
  [ -s r/before.png ] && [ -s r/after.png ] && [ -s r/changes.png ] && [ -s r/review.md ] && [ -s r/index.html ]
}
