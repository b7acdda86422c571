#!/usr/bin/env bats
# End-to-end tests of MJCF robots (lib/robot/mjcf*.cpp) through
# rscene-validate --check-files: MuJoCo's compile error at its file and
# line, and generalizedCoordinate lengths against the compiled model.
# They skip while rscene-validate does not read robot models (the robot
# checks of issue 11 land on another branch).

load helpers
MJCF="$BATS_TEST_DIRNAME/../tests/data/robots/mjcf"
V="$BIN/rscene-validate"

# scene FILE Q: a scene with one articulated system of FILE, q = Q.
scene() {
  printf 'raisim_engine_scene 2\narticulated_resource r R %s\n' "$1"
  printf 'articulated /World/R r 0 0 1 1 0 0 0 true true id=a1 generalizedCoordinate=%s\n' "$2"
}

setup() {
  needs_tools rscene-validate
  export NO_COLOR=1
  cd "$BATS_TEST_TMPDIR"
  scene "$MJCF/unknown_attribute.xml" 0 > probe.rscene
  if "$V" --check-files probe.rscene 2>&1 | grep -q 'RS70[34]'; then :; else
    skip "rscene-validate does not read robot models yet"
  fi
}

@test "mjcf: MuJoCo's compile error names the XML file and its line [RS7030]" {
  scene "$MJCF/unknown_attribute.xml" 0 > s.rscene
  run "$V" --check-files s.rscene
  [ "$status" -ne 0 ]
  [[ "$output" == *"unknown_attribute.xml:5"*"unrecognized attribute: 'colour'"*"[RS7030]"* ]]
}

@test "mjcf: a fixed-base model's coordinates are its joints, a ball joint 4 of them" {
  # joints.xml: hinge, slide, hinge, hinge, ball = 1 + 1 + 1 + 1 + 4.
  scene "$MJCF/joints.xml" 0.3,0.1,0,0,1,0,0,0 > good.rscene
  run "$V" --check-files good.rscene
  [[ "$output" != *"RS7040"* ]]
  scene "$MJCF/joints.xml" 0.3,0.1,0,0,1,0,0 > short.rscene
  run "$V" --check-files short.rscene
  [ "$status" -eq 1 ]
  [[ "$output" == *"[RS7040]"* ]]
}

@test "mjcf: a composite is refused where it is written [RS7036]" {
  scene "$MJCF/composite.xml" 0 > s.rscene
  run "$V" --check-files s.rscene
  [ "$status" -ne 0 ]
  [[ "$output" == *"composite.xml:7"*"[RS7036]"* ]]
}

@test "mjcf: <size nuser_body=400000000> is refused at its line before MuJoCo allocates [RS7053]" {
  cp "$SHARED/repro/03-mjcf-size-unbounded-alloc/nuser_body.xml" .
  scene nuser_body.xml 0 > s.rscene
  # 9.4 GB before: under a 1 GiB address-space limit it must still answer.
  run bash -c 'ulimit -v 1048576; exec "$1" --check-files s.rscene' _ "$V"
  [ "$status" -eq 1 ]
  [[ "$output" == *"nuser_body.xml:2: error: <size nuser_body=\"400000000\"> is over the cap of 1000"*"[RS7053]"* ]]
}

@test "mjcf: a missing visual-only mesh is a warning as in a URDF (RS7031); a missing colliding one RS5001" {
  mkdir meshes
  printf '<mujoco>\n  <compiler meshdir="meshes"/>\n  <asset>\n    <mesh name="gone" file="gone.stl"/>\n  </asset>\n  <worldbody><body name="b"><freejoint/><geom type="box" size="0.1 0.1 0.1"/>\n    <geom type="mesh" mesh="gone" contype="%s" conaffinity="0"/></body></worldbody>\n</mujoco>\n' 0 > look.xml
  sed 's/contype="0"/contype="1"/' look.xml > hit.xml
  scene "$PWD/look.xml" 0,0,1,1,0,0,0 > look.rscene
  run -0 "$V" --check-files look.rscene
  [[ "$output" == *"look.xml:4: warning: visual mesh '"*"gone.stl' not found (mesh 'gone'): its geoms are left out [RS7031]"* ]]
  [[ "$output" != *RS7030* ]]
  scene "$PWD/hit.xml" 0,0,1,1,0,0,0 > hit.rscene
  run -1 "$V" --check-files hit.rscene
  [[ "$output" == *"hit.xml:4: error: collision mesh '"*"gone.stl' not found (mesh 'gone') [RS5001]"* ]]
}
