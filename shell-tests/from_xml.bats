#!/usr/bin/env bats
# End-to-end tests of rscene-from-xml: RaiSim's example worlds and a world
# with every element convert to scenes rscene-validate passes clean; every
# flag; exit statuses; errors at file:line; outputs written atomically.

load helpers
EXAMPLES="$SHARED/spec/raisim/xml-examples"
FROM="$BIN/rscene-from-xml"
VALIDATE="$BIN/rscene-validate"

setup() {
  needs_tools rscene-from-xml
  in_workdir
}

# Validation with no error and no warning.
validates_clean() {
  [ -x "$VALIDATE" ] || return 0
  run -0 "$VALIDATE" --strict "$1"
  [ "$output" = "no issues in 1 file" ]
}

# Skips when the XML front end is still the interim plain parser (no
# templates): the lead merges the front end first.
require_templates() {
  printf '<raisim><params><n value="1"/></params><objects><array idx="@@i" start="0" end="@@n" increment="1">'`
    `'<sphere name="s@@i" mass="1"><dim radius="1"/></sphere></array></objects></raisim>' >probe.xml
  "$FROM" -q probe.xml 2>/dev/null | grep -q '^object /World/s0 ' ||
    skip "the XML front end does not expand templates yet (interim lib/xml/load_world.cpp)"
}

# A world with every element kind, a robot and its URDF.
write_world() {
  cat >arm.urdf <<'EOF'
<robot name="arm">
  <link name="base"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="arm"><inertial><mass value="1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 1"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
EOF
  printf '2 2 4 4\n0 0.1 0.2 0.3\n' >terrain.txt
  printf 'o m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n' >m.obj
  cat >world.xml <<EOF
<?xml version="1.0" ?>
<raisim version="1.0">
    <timeStep value="0.002"/>
    <gravity value="0 0 -9.8"/>
    <erp erp="0.25" erp2="0.05"/>
    <material>
        <default friction="0.7" restitution="0.1" restitution_threshold="0.01"/>
        <pair_prop name1="steel" name2="rubber" friction="0.9" restitution="0.4" restitution_threshold="0.001"/>
    </material>
    <objects>
        <ground name="ground" material="steel"/>
        <sphere name="ball" mass="1" material="rubber" collision_group="collision[1|4|6]" collision_mask="-1">
            <dim radius="0.2"/><state pos="0 0 3"/>
        </sphere>
        <capsule name="cap" mass="1" body_type="kinematic"><dim radius="0.1" height="0.5"/><state pos="1 0 1"/></capsule>
        <cylinder name="cyl" mass="2"><dim radius="0.2" height="0.4"/>
            <inertia xx="0.1" xy="0" xz="0" yy="0.1" yz="0" zz="0.05"/><state pos="-1 0 1"/></cylinder>
        <box name="crate" mass="3"><dim x="0.5" y="0.5" z="0.5"/><state pos="0 1 1" quat="1 0 0 0"/></box>
        <mesh name="rock" mass="1" file_name="$PWD/m.obj" scale="1 1 1" com="0 0 0"><state pos="0 -1 1"/></mesh>
        <compound name="combo" mass="4" com="0 0 0">
            <children>
                <box><dim x="0.2" y="0.2" z="0.2"/><state pos="0 0 0"/></box>
                <sphere material="steel"><dim radius="0.1"/><state pos="0.3 0 0"/></sphere>
            </children>
            <state pos="2 2 1"/>
        </compound>
        <heightmap name="field" x_sample="3" y_sample="2" x_size="4" y_size="2" center_x="5" center_y="5" height="0 0.1 0.2 0.3 0.4 0.5"/>
        <heightmap name="fromtext" center_x="-5" center_y="-5" text="$PWD/terrain.txt"/>
        <articulatedSystem name="robot" urdf_path="$PWD/arm.urdf" collision_mask="collision[0|2]">
            <state qpos="0 0 2 1 0 0 0 0.3" qvel="0 0 0 0 0 0 0"/>
        </articulatedSystem>
    </objects>
    <wire name="rope" type="stiff" length="1.5">
        <object1 name="ball" local_index="0" pos="0 0 0.2"/>
        <object2 name="robot" frame="hinge"/>
    </wire>
</raisim>
EOF
}

@test "--help lists every option; --version prints the version" {
  run -0 "$FROM" --help
  for o in --output --param --absolute-paths --quiet --stdin-filename --help --version; do
    grep -q -- "$o" <<<"$output" || { echo "missing $o"; return 1; }
  done
  run -0 "$FROM" --version
  [[ $output == "rscene-from-xml "* ]]
}

@test "RaiSim's example worlds convert and validate: clean, but for SingleBodies' bodies in the ground (RS7013)" {
  needs_shared spec/raisim/xml-examples
  for f in material heightMapUsingRawValues heightMapUsingTerrainGenerator SingleBodies; do
    run -0 "$FROM" -q "$EXAMPLES/$f.xml" -o "$f.rscene"
    [ -z "$output" ]
    [ "$f" = SingleBodies ] || validates_clean "$f.rscene"
  done
  # SingleBodies' first array sphere (radius 0.5 at z 0.1) and box (1 m
  # tall at z 0.1) start 0.4 m in the ground, as RaiSim's file places them:
  # validate says so, as rscene-sim does (RS7013), and nothing else.
  [ ! -x "$VALIDATE" ] || {
    run -0 --separate-stderr "$VALIDATE" SingleBodies.rscene
    [[ "$output" == *"'/World/sphere_array_0' starts 0.4 m inside '/World/ground'"*"[RS7013]"* ]]
    [ "$(grep -c 'warning:' <<<"$output")" -eq "$(grep -c '\[RS7013\]' <<<"$output")" ]
  }
  grep -qx 'contact_material steel rubber 0.8 0.15 0.001 0.8 0.001 0 0' material.rscene
  grep -q '^terrain_region /World/terrain 5 5 10 10 0 0 0 contactMaterial=default sourceKind=samples heights=1,1,1,1,1,1,0,0,0,1,1,0.5,' \
    heightMapUsingRawValues.rscene
  grep -q '^terrain_region /World/terrain 50 50 20 20 0 0 0 contactMaterial=default sourceKind=procedural proceduralFrequency=0.2 ' \
    heightMapUsingTerrainGenerator.rscene
}

@test "the example worlds' warnings: the camera, the flat procedural terrain" {
  needs_shared spec/raisim/xml-examples
  run -0 --separate-stderr "$FROM" "$EXAMPLES/material.xml"
  [ "$stderr" = "rscene-from-xml: warning: not converted: raisim: <camera>" ]
  run -0 --separate-stderr "$FROM" "$EXAMPLES/heightMapUsingTerrainGenerator.xml"
  [[ $stderr == *"heightMapUsingTerrainGenerator.xml:20"*"warning: <heightmap>: terrain_properties: rscene does not reproduce RaiSim's terrain generator, the samples are left flat [RS8113]"* ]]
  run -0 --separate-stderr "$FROM" -q "$EXAMPLES/heightMapUsingTerrainGenerator.xml"
  [ -z "$stderr" ]
  require_templates
  # 81 boxes named "box" (80 from the array, then one more): one entry.
  run -0 --separate-stderr "$FROM" "$EXAMPLES/SingleBodies.xml"
  [[ $stderr == *"SingleBodies.xml:2:1: warning: <raisim>: repeated names made unique: /World/box -> /World/box_2 ... /World/box_81 (80 paths) [RS8113]"* ]]
  [ "$(grep -c '^object /World/sphere_array_[0-9]* sphere ' <<<"$output")" -eq 80 ]
}

@test "a world with every element converts to the mapped records and validates clean" {
  write_world
  run -0 --separate-stderr "$FROM" world.xml -o world.rscene
  [ -z "$stderr" ]
  validates_clean world.rscene
  all=18446744073709551615
  expected="raisim_engine_scene 1
time_step 0.002
gravity 0 0 -9.8
solver 80 1e-07 0.25 accurate erp2=0.05 defaultFriction=0.7 defaultRestitution=0.1 defaultRestitutionThreshold=0.01
contact_material steel rubber 0.9 0.4 0.001 0.9 0.001 0 0
articulated_resource res_arm arm arm.urdf
terrain_region /World/field 3 2 4 2 5 5 0 contactMaterial=default sourceKind=samples heights=0,0.1,0.2,0.3,0.4,0.5
terrain_region /World/fromtext 2 2 4 4 -5 -5 0 contactMaterial=default sourceKind=samples heights=0,0.1,0.2,0.3
object /World/ground ground 0 0 0 1 0 0 0 10 10 1 0 0 0 steel - false true false - static true 1 $all
object /World/ball sphere 0 0 3 1 0 0 0 1 1 1 0.2 0 1 rubber - false true false - dynamic true 82 $all
object /World/cap capsule 1 0 1 1 0 0 0 1 1 1 0.1 0.5 1 default - false true false - kinematic true 1 $all
object /World/cyl cylinder -1 0 1 1 0 0 0 1 1 1 0.2 0.4 2 default - false true false - dynamic true 1 $all customInertia=true inertiaDiagonal=0.1,0.1,0.05
object /World/crate box 0 1 1 1 0 0 0 0.5 0.5 0.5 0 0 3 default - false true false - dynamic true 1 $all
object /World/rock mesh 0 -1 1 1 0 0 0 1 1 1 0 0 1 default - false true false m.obj dynamic true 1 $all centerOfMass=0,0,0
compound /World/combo 2 2 1 1 0 0 0 1 1 1 4 dynamic true true centerOfMass=0,0,0 collisionGroup=1 collisionMask=$all contactMaterial=default
compound_child /World/combo box 0 0 0 1 0 0 0 1 1 1 size=0.2,0.2,0.2 contactMaterial=default
compound_child /World/combo sphere 0.3 0 0 1 0 0 0 1 1 1 radius=0.1 contactMaterial=steel
articulated /World/robot res_arm 0 0 2 1 0 0 0 true true collisionMask=5 generalizedCoordinate=0,0,2,1,0,0,0,0.3 generalizedVelocity=0,0,0,0,0,0,0
wire /World/rope stiff /World/ball /World/robot 1.5 localIndexA=0 localIndexB=1 localPositionA=0,0,0.2 localPositionB=0,0,0"
  [ "$(cat world.rscene)" = "$expected" ]
  # The mesh and the robot are found and read from the scene's folder.
  if [ -x "$VALIDATE" ]; then run -0 "$VALIDATE" --strict --check-files world.rscene; fi
  # The output is canonical: rscene-fmt leaves it as it is.
  if [ -x "$BIN/rscene-fmt" ]; then run -0 "$BIN/rscene-fmt" --check world.rscene; fi
}

@test "--absolute-paths writes asset paths absolute; -o's folder places relative ones" {
  write_world
  mkdir out
  run -0 "$FROM" -q world.xml -o out/world.rscene
  grep -q ' \.\./m\.obj dynamic ' out/world.rscene
  grep -q '^articulated_resource res_arm arm \.\./arm\.urdf$' out/world.rscene
  run -0 "$FROM" -q --absolute-paths world.xml
  [[ $output == *" $PWD/m.obj dynamic "* ]]
  [[ $output == *"articulated_resource res_arm arm $PWD/arm.urdf"* ]]
}

@test "standard input: - or no operand; --stdin-filename names it in messages" {
  write_world
  "$FROM" -q world.xml >expected
  run -0 bash -c "'$FROM' -q - <world.xml"
  [ "$output" = "$(cat expected)" ]
  run -0 bash -c "'$FROM' -q <world.xml"
  [ "$output" = "$(cat expected)" ]
  run -2 --separate-stderr bash -c "printf '<raisim>\n<objects>\n<sphere mass=\"x\"><dim radius=\"1\"/></sphere></objects></raisim>' | '$FROM' --stdin-filename my.xml"
  [[ $stderr == "my.xml:3:9: error: <sphere> mass: 'x' is not a finite number [RS8110]"* ]]
  [ -z "$output" ]
}

@test "errors name the file, line and element; exit 2 and nothing written" {
  printf '<raisim version="1.0">\n<objects>\n<box name="b" mass="1">\n<dim x="1" y="1"/>\n</box>\n</objects>\n</raisim>\n' >bad.xml
  echo original >out.rscene
  run -2 --separate-stderr "$FROM" bad.xml -o out.rscene
  [[ $stderr == "bad.xml:4:1: error: <dim>: 'z' is required [RS8112]"* ]]
  [ "$(cat out.rscene)" = original ]
  run -2 --separate-stderr "$FROM" bad.xml -o new.rscene
  [ ! -e new.rscene ]
  [ -z "$(ls -A | grep -v -e '^bad.xml$' -e '^out.rscene$')" ]
}

@test "XML that is not well-formed: exit 2 with the file and line, no output file" {
  printf '<raisim>\n<objects>\n<sphere mass="1">\n</objects>\n' >broken.xml
  run -2 --separate-stderr "$FROM" broken.xml -o out.rscene
  [[ $stderr == "broken.xml:"[0-9]*"error:"*"[RS8101]"* ]]
  [ ! -e out.rscene ]
  run -2 --separate-stderr "$FROM" missing.xml
  [[ $stderr == *"missing.xml"* ]]
}

@test "unknown elements and attributes are warned at their line and listed; -q hides both" {
  printf '<raisim>\n<objects>\n<sphere name="s" mass="1" colour="red">\n<dim radius="1"/>\n<state pos="0 0 1" lin_vel="1 0 0"/>\n</sphere>\n<teapot/>\n</objects>\n</raisim>\n' >odd.xml
  run -0 --separate-stderr "$FROM" odd.xml
  [[ $stderr == *"odd.xml:3"*"warning: <sphere> colour: unknown attribute, not converted [RS8111]"* ]]
  [[ $stderr == *"odd.xml:7"*"warning: <teapot>: unknown object, not converted [RS8111]"* ]]
  [[ $stderr == *"rscene-from-xml: warning: not converted: sphere 's': colour, sphere 's': lin_vel, <teapot>" ]]
  [[ $output == *"object /World/s sphere 0 0 1 "* ]]
  run -0 --separate-stderr "$FROM" -q odd.xml
  [ -z "$stderr" ]
}

@test "collision groups in the three notations" {
  printf '<raisim><objects>
<sphere name="a" mass="1" collision_group="collision[1|4|6]" collision_mask="-1"><dim radius="1"/></sphere>
<sphere name="b" mass="1" collisionGroup="12" collisionMask="collision[-1]"><dim radius="1"/></sphere>
</objects></raisim>' >g.xml
  run -0 "$FROM" g.xml
  [[ $output == *"/World/a sphere "*" dynamic true 82 18446744073709551615"* ]]
  [[ $output == *"/World/b sphere "*" dynamic true 12 18446744073709551615"* ]]
  printf '<raisim><objects>\n<sphere mass="1" collision_group="collision[64]"><dim radius="1"/></sphere></objects></raisim>' >g2.xml
  run -2 --separate-stderr "$FROM" g2.xml
  [[ $stderr == "g2.xml:2:18: error: <sphere> collision_group: 'collision[64]' names a group outside 0..63 (or -1 for all) [RS8110]"* ]]
}

@test "-o writes atomically: a regular file is replaced, a directory refused, a FIFO written through" {
  needs_shared spec/raisim/xml-examples
  echo old >out.rscene
  chmod 640 out.rscene
  run -0 "$FROM" -q "$EXAMPLES/material.xml" -o out.rscene
  [ "$(head -1 out.rscene)" = "raisim_engine_scene 1" ]
  [ "$(stat -c %a out.rscene)" = 640 ]
  [ -z "$(ls -A | grep -v '^out.rscene$')" ]
  mkdir dir.rscene
  run -2 --separate-stderr "$FROM" -q "$EXAMPLES/material.xml" -o dir.rscene
  [[ $stderr == "rscene-from-xml: error: "*"dir.rscene"* ]]
  mkfifo pipe
  cat pipe >from_pipe &
  run -0 "$FROM" -q "$EXAMPLES/material.xml" -o pipe
  wait
  [ -p pipe ]
  [ "$(head -1 from_pipe)" = "raisim_engine_scene 1" ]
}

@test "--param: a malformed one is a usage error" {
  for bad in noequals '=1' '@@n=1' 'a b=1'; do
    run -2 --separate-stderr "$FROM" --param "$bad" /dev/null
    [[ $stderr == "rscene-from-xml: error: --param '$bad': expected NAME=VALUE"* ]] || { echo "$bad: $stderr"; return 1; }
  done
}

@test "--param sets the templated spheres example: 20 spheres where the expressions say; exist false removes them" {
  needs_shared spec/raisim/xml-examples/spheres.xml
  require_templates
  run -0 "$FROM" -q --param sphere_count=20 --param spawn_sphere=true --param spawn_box=false \
    --param sphere_height_offset=0.1 "$EXAMPLES/spheres.xml" -o spheres.rscene
  validates_clean spheres.rscene
  [ "$(grep -c '^object /World/sphere_array_[0-9]* sphere ' spheres.rscene)" -eq 20 ]
  grep -q '^object /World/sphere_array_0 sphere 0.1 0 0.1 1 0 0 0 1 1 1 0.5 0 1 ' spheres.rscene
  ! grep -q ' box ' spheres.rscene
  run -0 "$FROM" -q --param sphere_count=20 --param spawn_sphere=false --param spawn_box=false \
    --param sphere_height_offset=0.1 "$EXAMPLES/spheres.xml"
  [[ $output != *"sphere_array"* ]]
}

@test "includes: the files spliced in convert and validate clean; a cycle is exit 2 naming it" {
  require_templates
  run -0 --separate-stderr "$FROM" "$ROOT/tests/data/xml/include_top.xml" -o inc.rscene
  validates_clean inc.rscene
  grep -q '^object /World/top_ball sphere ' inc.rscene
  # The included files use the top file's params: the floor at -2, the rock of 3 kg.
  grep -q '^object /World/floor ground 0 0 -2 ' inc.rscene
  grep -q '^object /World/rock mesh 0 0 0 1 0 0 0 1 1 1 0 0 3 default ' inc.rscene
  [ "$(grep -c '^object ' inc.rscene)" -eq 3 ]
  run -2 --separate-stderr "$FROM" "$ROOT/tests/data/xml/cycle_a.xml" -o cycle.rscene
  [[ $stderr == *"include cycle"*"[RS8103]"* ]]
  [ ! -e cycle.rscene ]
}

@test "the mapping is rscene-to-xml's inverse: from-xml | to-xml | from-xml reproduces the scene" {
  needs_tools rscene-to-xml
  write_world
  run -0 "$FROM" -q world.xml -o first.rscene
  run -0 "$BIN/rscene-to-xml" -q first.rscene -o back.xml
  run -0 "$FROM" -q back.xml -o second.rscene
  cmp first.rscene second.rscene
  # Every kind of the world made the trip.
  for kind in contact_material articulated_resource terrain_region object compound compound_child articulated wire; do
    grep -q "^$kind " second.rscene || { echo "no $kind"; return 1; }
  done
}

# Hand-written fixtures in the forms of RaiSim's real files
# (tests/data/xml/raisim/: exportedWorld.xml, laikago.xml, heightMapUsingPng.xml,
# heightMapUsingTxt.xml, newtonsCradle.xml); the walker test robot stands in
# for anymal and laikago.
RAISIM="$ROOT/tests/data/xml/raisim"

@test "RaiSim's real forms: each fixture converts (exit 0) and validates clean" {
  for f in exported_world laikago_world heightmap_png heightmap_txt wire_frame; do
    run -0 "$FROM" -q "$RAISIM/$f.xml" -o "$f.rscene"
    [ -z "$output" ]
    validates_clean "$f.rscene"
  done
  # exportedWorld.xml: the ground's height from <dim>, its group kept; the
  # robot's default group and mask left out; comma vectors read.
  grep -qx 'object /World/unnamed_0 ground 0 0 0 1 0 0 0 10 10 1 0 0 0 default - false true false - static true 2147483648 4294967295' \
    exported_world.rscene
  grep -q '^articulated /World/walkerA res_walker -3 0 0.54 1 0 0 0 true true resourceDirectory=[^ ]* collisionMask=4294967295 generalizedCoordinate=-3,0,0.54,' \
    exported_world.rscene
  grep -qx 'gravity 0 0 -9.81' exported_world.rscene
  [ "$(grep -c '^wire ' exported_world.rscene)" -eq 3 ]
  # laikago.xml: collisionGroup="-2147483648" is its 64-bit two's complement.
  grep -q '^object /World/ground ground .* static true 18446744071562067968 18446744073709551615$' laikago_world.rscene
  grep -q '^object /World/crate box .* dynamic true 18446744071562067968 18446744073709551614$' laikago_world.rscene
  # heightMapUsingPng.xml: 4 x 3 pixels are the samples; the bottom row
  # (y = 0) is 255 200 100 0 -> 255/255 * 0.5 - 1 = -0.5 ...
  grep -q '^terrain_region /World/terrain 4 3 6 4 0 0 0 contactMaterial=default sourceKind=png sourcePath=[^ ]*heights.png pngHeightScale=0.5 pngHeightOffset=-1 heights=-0.5,-0.6078' \
    heightmap_png.rscene
  # heightMapUsingTxt.xml: the file's first four numbers are the grid.
  grep -q '^terrain_region /World/terrain 5 5 10 10 0 0 0 contactMaterial=default sourceKind=samples heights=1,1,1,1,1,1,2,2,2,1,1,2,3,' \
    heightmap_txt.rscene
  # newtonsCradle.xml: a wire end on a robot frame (the fixed L_FOOT under
  # L_SHANK: body 2, 0.2 below its joint).
  grep -qx 'wire /World/tether stiff /World/ball /World/walker 0.4 localIndexA=0 localIndexB=2 localPositionA=0,0,0 localPositionB=0,0,-0.2' \
    wire_frame.rscene
}

@test "RaiSim's real forms: only what has no field is listed (stretch_type both, compression_only)" {
  run -0 --separate-stderr "$FROM" "$RAISIM/exported_world.xml"
  [ "$stderr" = "rscene-from-xml: warning: not converted: wire 'unnamed_7': stretch_type both (rscene wires resist stretch only), wire 'unnamed_8': stretch_type compression_only (rscene wires resist stretch only)" ]
  for f in laikago_world heightmap_png heightmap_txt wire_frame; do
    run -0 --separate-stderr "$FROM" "$RAISIM/$f.xml"
    [ -z "$stderr" ] || { echo "$f: $stderr"; return 1; }
  done
}

@test "RaiSim's real forms round-trip: from-xml | to-xml | from-xml is identical (a PNG source comes back as its samples)" {
  needs_tools rscene-to-xml
  for f in exported_world laikago_world heightmap_txt wire_frame; do
    run -0 "$FROM" -q "$RAISIM/$f.xml" -o "$f.1.rscene"
    run -0 "$BIN/rscene-to-xml" -q "$f.1.rscene" -o "$f.xml"
    run -0 "$FROM" -q "$f.xml" -o "$f.2.rscene"
    cmp "$f.1.rscene" "$f.2.rscene"
  done
  grep -q 'stretch_type="stretch_only"' exported_world.xml
  grep -q '<ground name="/World/unnamed_0" height="0" material="default" collision_group="collision\[31\]"' exported_world.xml
  # rscene-to-xml writes a heightmap's samples: the PNG's decoded heights
  # come back exactly, the source keys do not.
  run -0 "$FROM" -q "$RAISIM/heightmap_png.xml" -o png.1.rscene
  run -0 "$BIN/rscene-to-xml" -q png.1.rscene -o png.xml
  run -0 "$FROM" -q png.xml -o png.2.rscene
  [ "$(grep -o ' heights=.*' png.1.rscene)" = "$(grep -o ' heights=.*' png.2.rscene)" ]
  grep -q 'sourceKind=samples' png.2.rscene
}

@test "templatedWorld.xml's form: a top-level include's objects join; a parameter only --param sets" {
  require_templates
  run -2 --separate-stderr "$FROM" "$ROOT/tests/data/xml/templated/world.xml" -o t.rscene
  [[ $stderr == *"world.xml:14:"*"@@start_x is not set"*"[RS8104]"* ]]
  [ ! -e t.rscene ]
  run -0 "$FROM" -q --param start_x=2 "$ROOT/tests/data/xml/templated/world.xml" -o t.rscene
  validates_clean t.rscene
  grep -q '^object /World/floor ground 0 0 0.25 ' t.rscene
  grep -q '^object /World/ball sphere 2 0 1 ' t.rscene
}

# Each value rscene-validate, rscene-sim or rscene-to-xml would refuse:
# the world holding the objects $1 is refused (helpers.bash) with a first
# error line starting with $2, at file:line:col of the element.
fragment_refused() {
  printf '<raisim version="1.0">\n<objects>\n%s\n</objects>\n</raisim>\n' "$1" >bad.xml
  refused "$2" "$FROM" bad.xml -o out.rscene
}

@test "values the other tools refuse are errors at their attribute, exit 2 and nothing written" {
  fragment_refused '<sphere mass="1"><dim radius="-1"/></sphere>' \
    'bad.xml:3:23: error: <dim> radius: -1 is not a positive length [RS8110]'
  fragment_refused '<sphere mass="1"><dim radius="0"/></sphere>' \
    'bad.xml:3:23: error: <dim> radius: 0 is not a positive length [RS8110]'
  fragment_refused '<box mass="1"><dim x="1" y="-2" z="1"/></box>' \
    'bad.xml:3:26: error: <dim> y: -2 is not a positive length [RS8110]'
  fragment_refused '<capsule mass="1"><dim radius="1" height="-3"/></capsule>' \
    'bad.xml:3:35: error: <dim> height: -3 is not a positive length [RS8110]'
  fragment_refused '<sphere mass="-5"><dim radius="1"/></sphere>' \
    'bad.xml:3:9: error: <sphere> mass: -5 is not a positive mass [RS8110]'
  fragment_refused '<sphere mass="1"><dim radius="1"/><state pos="0 0 0" quat="0 0 0 0"/></sphere>' \
    'bad.xml:3:54: error: <state> quat: the zero quaternion is no orientation [RS8110]'
}

@test "records the scene checks refuse are RS8125 at their element, naming the check's code" {
  urdf="$ROOT/tests/data/robots/check/walker.urdf"
  [ -f "$urdf" ] || skip "no walker.urdf"
  fragment_refused "<articulatedSystem name=\"w\" urdf_path=\"$urdf\"><state qpos=\"0 0 0.5 0 0 0 0 0 0 0 0\"/></articulatedSystem>" \
    'bad.xml:3:'
  [[ $stderr == *"error: <state> qpos: generalizedCoordinate holds a zero quaternion"*"(RS7043 in the converted scene) [RS8125]"* ]]
  fragment_refused '<sphere mass="1"><dim radius="1"/><state pos="1e300 0 0"/></sphere>' \
    'bad.xml:3:42: error: <state> pos: '
  [[ $stderr == *"(RS7021 in the converted scene) [RS8125]"* ]]
  # The same robot with a unit quaternion converts, and the tools accept it.
  printf '<raisim version="1.0">\n<objects>\n<articulatedSystem name="w" urdf_path="%s"><state qpos="0 0 0.5 1 0 0 0 0 0 0 0"/></articulatedSystem>\n</objects>\n</raisim>\n' "$urdf" >good.xml
  run -0 "$FROM" -q good.xml -o good.rscene
  validates_clean good.rscene
}

@test "a mesh file that does not exist is a warning at file_name; the scene is still written" {
  printf '<raisim version="1.0">\n<objects>\n<mesh mass="1" file_name="nope.obj"/>\n</objects>\n</raisim>\n' >m.xml
  run -0 --separate-stderr "$FROM" m.xml -o m.rscene
  [[ $stderr == "m.xml:3:16: warning: <mesh> file_name: mesh file 'nope.obj' not found: rscene-sim will refuse the body until it exists [RS8113]"* ]]
  grep -q '^object /World/mesh mesh .* nope.obj dynamic' m.rscene
  run -0 --separate-stderr "$FROM" -q m.xml
  [ -z "$stderr" ]
  # With the file there, no warning.
  touch nope.obj
  run -0 --separate-stderr "$FROM" m.xml -o m.rscene
  [[ $stderr != *RS8113* ]]
}

@test "--relative-to DIR: asset paths from DIR on standard output, as -o into DIR writes them" {
  mkdir -p out/sub
  "$BIN/rscene-to-xml" -q "$ROOT/examples/robot_cell.rscene" -o w.xml
  "$FROM" -q w.xml --relative-to out/sub > out/sub/s.rscene
  "$FROM" -q w.xml -o out/sub/o.rscene
  cmp out/sub/s.rscene out/sub/o.rscene
  "$FROM" -q w.xml > here.rscene
  ! cmp -s here.rscene out/sub/s.rscene
  run -2 --separate-stderr "$FROM" w.xml --relative-to out -o x.rscene
  [ "$stderr" = "rscene-from-xml: error: --relative-to is for standard output: with -o FILE, paths are relative to FILE's folder" ]
  [ ! -e x.rscene ]
  run -2 "$FROM" w.xml --relative-to out --absolute-paths
}
