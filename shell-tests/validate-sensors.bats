#!/usr/bin/env bats
# Sensors through the real tools: rscene-validate, rscene-sim and
# rscene-render refuse a sensor record with the same code at the same
# line:col (scene/sensor_check.hpp); URDF sensor sets (<link sensor=>)
# are read with --check-files, their findings in their own file.

load helpers
V="$BIN/rscene-validate"

setup() {
  needs_tools rscene-validate
  export NO_COLOR=1
  cd "$BATS_TEST_TMPDIR"
  cat >bad.rscene <<'EOF'
raisim_engine_scene 2
time_step 0.01
sensor /World/Cam rgb - 0 0 1 1 0 0 0 width=0 outputPath=../x.png
sensor /World/L lidar - 0 0 1 1 0 0 0 lidarChannels=4096 lidarSamples=4096
sensor /World/S sonar - 0 0 1 1 0 0 0 parentLink=base
sensor /World/D depth - 0 0 1 1 0 0 0 verticalFov=180 nearPlane=1 farPlane=0.5 calibrationFx=500
sensor /World/I imu - 0 0 1 1 0 0 0 updateRate=2e6 noiseStddev=-1
camera /World/C 0 0 1 1 0 0 0 50 0.05 50 64 48 rgb true outputPath=/tmp/c.png
EOF
}

# The "file:line:col: severity: message [CODE]" lines of a run.
findings() { grep -E '^[^ ].*\[RS[0-9]{4}\]$' <<<"$1"; }

EXPECTED='bad.rscene:3:45: error: image width is 0, outside 1..16384 [RS7064]
bad.rscene:3:58: error: sensor outputPath '"'"'../x.png'"'"' has a '"'"'..'"'"' part [RS7069]
bad.rscene:4:71: error: lidar scan of 4096 x 4096 rays is more than 4194304 rays [RS7066]
bad.rscene:5:17: warning: unknown sensor_kind '"'"'sonar'"'"' [RS2007]
bad.rscene:5:50: warning: parentLink '"'"'base'"'"' is not used: the sensor has no parentObject [RS7068]
bad.rscene:6:51: error: vertical field of view is 180 degrees, outside (0, 180) [RS7064]
bad.rscene:6:76: error: far plane 0.5 is not beyond the near plane 1 [RS4012]
bad.rscene:6:94: error: calibration given in part: calibrationFy, calibrationCx, calibrationCy missing [RS7065]
bad.rscene:7:48: error: update rate is 2e+06 Hz, outside 0..1e6 [RS7067]
bad.rscene:7:64: error: noise standard deviation is -1, outside 0..1e12 [RS7067]
bad.rscene:8:68: error: camera outputPath '"'"'/tmp/c.png'"'"' is absolute [RS7069]'

@test "validate: every sensor-record check at its field, exit 1" {
  run --separate-stderr "$V" bad.rscene
  [ "$status" -eq 1 ]
  diff <(findings "$output") <(echo "$EXPECTED")
  [ "$stderr" = "9 errors, 2 warnings in 1 file" ]
}

@test "sim refuses the same records with the same codes at the same places, exit 2" {
  [ -x "$BIN/rscene-sim" ] || skip "rscene-sim not built"
  run --separate-stderr "$BIN/rscene-sim" --steps 1 bad.rscene
  [ "$status" -eq 2 ]
  [ -z "$output" ]
  diff <(findings "$stderr") <(echo "$EXPECTED")
  # A scene with errors gets validate's list (above), whose unknown-kind
  # warning is lib/core's.
  [[ "$stderr" == *"warning: unknown sensor_kind 'sonar' [RS2007]"* ]]
}

@test "render refuses the same records with the same codes at the same places, exit 2" {
  [ -x "$BIN/rscene-render" ] || skip "rscene-render not built"
  run --separate-stderr "$BIN/rscene-render" bad.rscene -o out.png
  [ "$status" -eq 2 ]
  [ ! -e out.png ]
  diff <(findings "$stderr") <(echo "$EXPECTED")
}

@test "sensors within every bound: no finding" {
  cat >good.rscene <<'EOF'
raisim_engine_scene 2
sensor /World/Cam rgb - 0 0 1 1 0 0 0 width=16384 height=1 outputPath=out/cam.png calibrationFx=500 calibrationFy=500 calibrationCx=0 calibrationCy=0
sensor /World/L spinning_lidar - 0 0 1 1 0 0 0 lidarChannels=64 lidarSamples=65536 lidarVerticalFov=180 lidarMinRange=0
sensor /World/Planar lidar - 0 0 1 1 0 0 0 lidarChannels=1 lidarVerticalFov=0
sensor /World/I imu - 0 0 1 1 0 0 0 updateRate=1e6 noiseStddev=0
EOF
  run --separate-stderr "$V" good.rscene
  [ "$status" -eq 0 ]
  [ "$stderr" = "no issues in 1 file" ]
}

# A one-link robot whose link names the sensor set FILE (line 3).
robot() {
  mkdir -p robot/urdf
  cat >robot/urdf/r.urdf <<EOF
<robot name="r">
  <link name="base"/>
  <link name="cam" sensor="$1"/>
  <joint name="j" type="fixed"><parent link="base"/><child link="cam"/></joint>
</robot>
EOF
  cat >robot.rscene <<'EOF'
raisim_engine_scene 2
articulated_resource r R robot/urdf/r.urdf
articulated /World/R r 0 0 0 1 0 0 0 true true
EOF
}

@test "validate --check-files: a sensor set not found lists the places searched, at the URDF link" {
  robot gone.xml
  run --separate-stderr "$V" --check-files robot.rscene
  [ "$status" -eq 1 ]
  [[ "${lines[0]}" == "robot/urdf/r.urdf:3: error: sensor set 'gone.xml' not found (tried robot/urdf/gone.xml, robot/urdf/sensor/gone.xml, robot/urdf/sensors/gone.xml, robot/gone.xml, robot/sensors/gone.xml) [RS7060]" ]]
}

@test "validate --check-files: a sensor set's bound is the record's code, at the set file's line" {
  robot cam.xml
  mkdir -p robot/sensors
  cat >robot/sensors/cam.xml <<'EOF'
<sensor_set name="cam">
  <link>
    <sensor name="color" type="rgb" update_rate="30">
      <camera horizontal_fov="1.0">
        <image width="640" height="100000"/>
      </camera>
    </sensor>
  </link>
</sensor_set>
EOF
  run --separate-stderr "$V" --check-files robot.rscene
  [ "$status" -eq 1 ]
  [ "${lines[0]}" = "robot/sensors/cam.xml:5: error: sensor 'color' of sensor set 'cam': image height is 100000, outside 1..16384 [RS7064]" ]
  # Within bounds, the same robot is clean.
  sed -i 's/100000/480/' robot/sensors/cam.xml
  run --separate-stderr "$V" --check-files robot.rscene
  [ "$status" -eq 0 ]
  [ "$stderr" = "no issues in 1 file" ]
}

@test "validate --check-files: a sensor set that is not XML is RS7061" {
  robot cam.xml
  echo '<sensor_set name="cam"><link>' >robot/urdf/cam.xml
  run --separate-stderr "$V" --check-files robot.rscene
  [ "$status" -eq 1 ]
  [[ "${lines[0]}" == "robot/urdf/cam.xml:1: error: sensor set file is not well-formed XML"*"[RS7061]" ]]
}

@test "ANYmal C with its sensor sets validates (only the ouster's missing visual mesh is said)" {
  needs_shared corpus/robots/anymal_c/urdf/anymal_sensored.urdf
  cat >anymal.rscene <<EOF
raisim_engine_scene 2
articulated_resource anymal ANYmal $CORPUS/robots/anymal_c/urdf/anymal_sensored.urdf
articulated /World/Anymal anymal 0 0 0.54 1 0 0 0 true true id=anymal generalizedCoordinate=0,0,0.54,1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8
sensor /World/Anymal/Front rgb anymal 0 0 0 1 0 0 0 parentLink=depth_camera_front_camera_parent
sensor /World/Anymal/Typo rgb anymal 0 0 0 1 0 0 0 parentLink=depth_camera_front_camera_parnt
EOF
  run --separate-stderr "$V" --check-files anymal.rscene
  [ "$status" -eq 1 ]
  [ "${#lines[@]}" -gt 0 ]
  [ "$(findings "$output" | grep -c RS7031)" -eq 1 ]
  [[ "$(findings "$output" | grep RS7031)" == *"sensors/ouster1-64.xml:35: warning: visual mesh"* ]]
  # The typo is one RS7045 with its suggestion; nothing else.
  [ "$(findings "$output" | grep -c RS7045)" -eq 1 ]
  [[ "$output" == *"hint: did you mean 'depth_camera_front_camera_parent'?"* ]]
  [ "$stderr" = "1 error, 1 warning in 1 file" ]
}

# The three tools' findings of one scene: validate exits 1, sim and render 2,
# each with the same "file:line:col: ... [CODE]" lines.
same_in_all_three() {
  run --separate-stderr "$V" "$1"
  [ "$status" -eq 1 ]
  local want
  want=$(findings "$output")
  [ -n "$want" ]
  if [ -x "$BIN/rscene-sim" ]; then
    run --separate-stderr "$BIN/rscene-sim" --steps 1 "$1"
    [ "$status" -eq 2 ]
    diff <(findings "$stderr") <(echo "$want")
  fi
  if [ -x "$BIN/rscene-render" ]; then
    run --separate-stderr "$BIN/rscene-render" "$1" -o out.png
    [ "$status" -eq 2 ]
    [ ! -e out.png ]
    diff <(findings "$stderr") <(echo "$want")
  fi
  echo "$want"
}

@test "a parentObject that is no body is refused by validate, sim and render alike" {
  cat >mount.rscene <<'EOF2'
raisim_engine_scene 2
material steel 0.5 0.5 0.5 1 0 0.5 0 0 0 0 false - - - - - -
articulated_resource arm Arm arm.urdf
sensor /World/A imu nosuch 0 0 0 1 0 0 0
camera /World/Cam 0 0 1 1 0 0 0 50 0.05 50 64 48 rgb true id=cam_over
sensor /World/B imu cam_over 0 0 0 1 0 0 0
sensor /World/C imu steel 0 0 0 1 0 0 0
sensor /World/D imu arm 0 0 0 1 0 0 0
group /World/G id=g
sensor /World/E rgb g 0 0 0 1 0 0 0 parentLink=x
EOF2
  run same_in_all_three mount.rscene
  [ "$status" -eq 0 ]
  diff <(echo "$output") - <<'EOF2'
mount.rscene:4:21: error: body 'nosuch' does not exist [RS3012]
mount.rscene:6:21: error: 'cam_over' is a camera, not a body a sensor can ride on [RS7063]
mount.rscene:7:21: error: body 'steel' does not exist [RS3012]
mount.rscene:8:21: error: body 'arm' does not exist [RS3012]
mount.rscene:10:21: error: 'g' is a group, not a body a sensor can ride on [RS7063]
EOF2
  # validate says RS3012 once (its core check and the scene model's agree).
  run --separate-stderr "$V" mount.rscene
  [ "$(grep -c '^mount.rscene:4:21:' <<<"$output")" -eq 1 ]
}

@test "a value that does not parse is one finding, not also a bound on its default" {
  printf 'raisim_engine_scene 2\nsensor /World/S rgb - 0 0 1 1 0 0 0 calibrationFx=nan calibrationFy=500 calibrationCx=320 calibrationCy=240 width=abc\n' >nan.rscene
  run --separate-stderr "$V" nan.rscene
  [ "$status" -eq 1 ]
  [ "$(findings "$output" | sed 's/ error: .*\[/ [/')" = "nan.rscene:2:51: [RS2002]
nan.rscene:2:115: [RS2003]" ]
  [[ "$output" != *RS7065* && "$output" != *RS7064* ]]
  if [ -x "$BIN/rscene-render" ]; then
    run --separate-stderr "$BIN/rscene-render" nan.rscene -o out.png
    [ "$status" -eq 2 ]
    [[ "$stderr" != *RS7065* && "$stderr" != *RS7064* ]]
  fi
}

@test "two enabled sensor records with one outputPath: RS7070 in validate, sim and render" {
  cat >same.rscene <<'EOF2'
raisim_engine_scene 2
sensor /World/A imu - 0 0 1 1 0 0 0 outputPath=a.csv
sensor /World/Off imu - 0 0 1 1 0 0 0 outputPath=a.csv enabled=false
sensor /World/B imu - 0 0 1 1 0 0 0 outputPath=a.csv
EOF2
  run same_in_all_three same.rscene
  [ "$status" -eq 0 ]
  [ "$output" = "same.rscene:4:48: error: sensor '/World/B' and sensor '/World/A' would both write 'a.csv' [RS7070]" ]
}

# A sensor set for robot(): an IMU named imu (line 3) and the given extra
# lines inside the set's <link>.
imu_set() {
  mkdir -p robot/sensors
  cat >robot/sensors/cam.xml <<EOF2
<sensor_set name="cam">
  <link>
    <sensor name="imu" type="imu" update_rate="100"/>
$1
  </link>
</sensor_set>
EOF2
}

@test "validate without --check-files: a sensor set's numbers, as sim and render refuse them" {
  robot cam.xml
  imu_set '    <sensor name="color" type="rgb"><camera horizontal_fov="nan"><image width="100000" height="480"/></camera></sensor>
    <sensor name="scan" type="spinning_lidar"><yaw samples="1000000000"/><pitch samples="16"/></sensor>'
  run --separate-stderr "$V" robot.rscene
  [ "$status" -eq 1 ]
  [ "$(findings "$output" | sed 's/: error: .*\[/ [/')" = "robot/sensors/cam.xml:4 [RS7061]
robot/sensors/cam.xml:5 [RS7066]" ]
  if [ -x "$BIN/rscene-sim" ]; then
    run --separate-stderr "$BIN/rscene-sim" --steps 1 robot.rscene
    [ "$status" -eq 2 ]
    [[ "$stderr" == *"robot/sensors/cam.xml:4: error: "*"[RS7061]"* ]]
    [[ "$stderr" == *"robot/sensors/cam.xml:5: error: "*"[RS7066]"* ]]
  fi
  # A sensor set that is not found stays a --check-files finding.
  robot gone.xml
  run --separate-stderr "$V" robot.rscene
  [ "$status" -eq 0 ]
  run --separate-stderr "$V" --check-files robot.rscene
  [ "$status" -eq 1 ]
  [[ "$output" == *"[RS7060]"* ]]
}

@test "a sensor record named as a robot's sensor: RS7070 at the record in validate and sim --sensors" {
  robot cam.xml
  imu_set ''
  echo 'sensor /World/R/cam/imu imu - 0 0 1 1 0 0 0' >>robot.rscene
  run --separate-stderr "$V" robot.rscene
  [ "$status" -eq 1 ]
  [ "$(findings "$output")" = "robot.rscene:4:8: error: the sensor record '/World/R/cam/imu' and the URDF sensor 'imu' of the sensor set on link 'cam' (robot/sensors/cam.xml:3) would both write 'World+R+cam+imu.csv' [RS7070]" ]
  if [ -x "$BIN/rscene-sim" ]; then
    run --separate-stderr "$BIN/rscene-sim" --steps 1 --sensors rec robot.rscene
    [ "$status" -eq 2 ]
    [[ "$(findings "$stderr")" == "robot.rscene:4:8: error: "*"[RS7070]" ]]
  fi
  # Renamed, it is clean.
  sed -i 's|/World/R/cam/imu|/World/R/Imu|' robot.rscene
  run --separate-stderr "$V" robot.rscene
  [ "$status" -eq 0 ]
}

@test "ANYmal C's sensor sets with bad numbers: plain validate says what sim says, at the XML lines" {
  needs_shared corpus/robots/anymal_c
  cp -r "$CORPUS/robots/anymal_c" anymal_c
  sed -i 's/<image width="640" height="480"\/>/<image width="100000" height="480"\/>/' anymal_c/sensors/realsense435.xml
  sed -i 's/samples="512"/samples="1000000000"/' anymal_c/sensors/ouster1-64.xml
  cat >anymal.rscene <<EOF2
raisim_engine_scene 2
articulated_resource anymal ANYmal anymal_c/urdf/anymal_sensored.urdf
articulated /World/Anymal anymal 0 0 0.54 1 0 0 0 true true id=anymal generalizedCoordinate=0,0,0.54,1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8
EOF2
  run --separate-stderr "$V" anymal.rscene
  [ "$status" -eq 1 ]
  local want
  want=$(findings "$output" | grep -E 'RS706[0-9]')
  [[ "$want" == *"ouster1-64.xml:42: error: "*"[RS7066]"* ]]
  [[ "$want" == *"realsense435.xml:"*"[RS7064]"* ]]
  [ -x "$BIN/rscene-sim" ] || return 0
  run --separate-stderr "$BIN/rscene-sim" --steps 1 anymal.rscene
  [ "$status" -eq 2 ]
  diff <(findings "$stderr" | grep -E 'RS706[0-9]') <(echo "$want")
}

@test "orthoScale under an orthographic projection, a flat multi-channel LiDAR, segmentation on a LiDAR: one verdict in all three" {
  C="0 0 5 1 0 0 0 45 0.05 50 64 48 rgb true"
  cat >ortho.rscene <<EOF2
raisim_engine_scene 2
camera /World/C $C projection=orthographic orthoScale=-6
camera /World/D $C projection=orthographic orthoScale=1e300
camera /World/E $C orthoScale=0
sensor /World/L lidar - 0 0 1 1 0 0 0 lidarVerticalFov=0 lidarChannels=4
sensor /World/M lidar - 0 0 1 1 0 0 0 lidarVerticalFov=0 lidarChannels=1 segmentation=true
sensor /World/N segmentation - 0 0 1 1 0 0 0 segmentation=true
EOF2
  run same_in_all_three ortho.rscene
  [ "$status" -eq 0 ]
  [ "$(sed 's/ error: .*\[/ [/; s/ warning: .*\[/ [/' <<<"$output")" = "ortho.rscene:2:92: [RS7074]
ortho.rscene:3:92: [RS7074]
ortho.rscene:5:56: [RS7072]
ortho.rscene:6:87: [RS7073]" ]
  # A perspective camera's orthoScale (row 4) is not used and not judged; one channel may be flat.
  [[ $output == *"orthoScale is -6 under an orthographic projection; it must be within (0, 1e12]"* ]]
}
