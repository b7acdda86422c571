#!/usr/bin/env bats
# Where bodies and robots start (hostile input round two): an MJCF robot
# at MuJoCo's qpos0, a start pose outside a joint's limits (RS7056), a
# robot link in the ground (RS7057), and a primitive body below the ground
# (RS7013), which validate and sim say alike.

load helpers
GYM="$CORPUS/robots/gymnasium"
V="$BIN/rscene-validate"
SIM="$BIN/rscene-sim"

# hopper Z [KEYS]: the Gymnasium hopper with its record at height Z above a ground at 0.
hopper() {
  printf 'raisim_engine_scene 2\narticulated_resource r R %s\n' "$GYM/hopper.xml"
  printf 'object /World/G ground 0 0 0 1 0 0 0 10 10 1 1 0 0 default - false true true - static true 1 18446744073709551615\n'
  printf 'articulated /World/H r 0 0 %s 1 0 0 0 true true id=h %s\n' "$1" "${2:-}"
}

setup() {
  needs_tools rscene-validate rscene-sim
  export NO_COLOR=1
  in_workdir
}

@test "robots: an MJCF robot without coordinates starts at MuJoCo's qpos0 (hopper's rootz 1.25), standing on the ground" {
  needs_shared corpus/robots/gymnasium/hopper.xml
  hopper 0 > h.rscene
  run -0 --separate-stderr "$SIM" --steps 0 h.rscene
  [[ "$output" == *"articulated /World/H r 0 0 0 1 0 0 0 true true id=h generalizedCoordinate=0,1.25,0,0,0,0 "* ]]
  [[ "$stderr" != *RS7057* && "$stderr" != *RS7056* ]]
  # The record's own coordinates still win.
  hopper 0 "generalizedCoordinate=0,1.5,0,0,0,0" > w.rscene
  run -0 --separate-stderr "$SIM" --steps 0 w.rscene
  [[ "$output" == *"generalizedCoordinate=0,1.5,0,0,0,0 "* ]]
}

@test "robots: a start pose outside a joint's limits is a warning at generalizedCoordinate (validate --check-files, sim) [RS7056]" {
  needs_shared corpus/robots/gymnasium/hopper.xml
  hopper 0 "generalizedCoordinate=0,1.25,0,1,0,0" > h.rscene
  line=$(grep -n '^articulated ' h.rscene | cut -d: -f1)
  run -0 "$V" --check-files h.rscene
  [[ "$output" == *"h.rscene:$line:"*"warning: articulated system '/World/H' starts with joint 'thigh_joint' (entry 3 of generalizedCoordinate) at 1, outside its limits [-2.61799, 0]"*"[RS7056]"* ]]
  [ "$(grep -c RS7056 <<<"$output")" -eq 1 ]
  run -0 "$V" h.rscene  # robot files are --check-files' matter
  [[ "$output" != *RS7056* ]]
  run -0 --separate-stderr "$SIM" --steps 1 h.rscene
  [[ "$stderr" == *"thigh_joint"*"[RS7056]"* ]]
  [ "$(grep -c RS7056 <<<"$stderr")" -eq 1 ]
}

@test "robots: a robot that starts with a link in the ground is refused by sim before the first step [RS7057]" {
  needs_shared corpus/robots/gymnasium/hopper.xml
  hopper -0.3 > h.rscene
  line=$(grep -n '^articulated ' h.rscene | cut -d: -f1)
  # Bullet's multibody solver would throw it: a hopper 0.5 m deep reached 257 m.
  refused "h.rscene:$line:" "$SIM" --steps 2 h.rscene -o out.rscene
  [[ "$stderr" == *"h.rscene:$line:"*"error: articulated system '/World/H' starts with link 'foot' "*" inside '/World/G'"*"nothing was simulated [RS7057]"* ]]
  [ "$(grep -c RS7057 <<<"$stderr")" -eq 1 ]
  # Standing on the ground (within 1 cm) is contact, not a mistake.
  hopper 0 > ok.rscene
  run -0 --separate-stderr "$SIM" --steps 2 ok.rscene -o ok.out.rscene
  [[ "$stderr" != *RS7057* ]]
}

# box Z: a dynamic 1 m box at height Z over a ground at 0.
box_scene() {
  printf 'raisim_engine_scene 2\n'
  printf 'object /World/G ground 0 0 0 1 0 0 0 10 10 1 1 0 0 default - false true true - static true 1 18446744073709551615\n'
  printf 'object /World/B box 0 0 %s 1 0 0 0 1 1 1 0.5 1 1 default - false true false - dynamic true 1 18446744073709551615\n' "$1"
}

@test "bodies: a primitive that starts in the ground is RS7013 from validate and sim alike, once each" {
  box_scene 0.2 > b.rscene
  run -0 "$V" b.rscene
  [[ "$output" == *"b.rscene:3:"*"warning: dynamic body '/World/B' starts 0.3 m inside '/World/G'"*"[RS7013]"* ]]
  [ "$(grep -c RS7013 <<<"$output")" -eq 1 ]
  run -0 --separate-stderr "$SIM" --steps 2 b.rscene
  [[ "$stderr" == *"b.rscene:3:"*"warning: dynamic body '/World/B' starts 0.3 m inside '/World/G'"*"[RS7013]"* ]]
  [ "$(grep -c RS7013 <<<"$stderr")" -eq 1 ]
  box_scene 0.495 > ok.rscene  # 5 mm: contact, not a mistake
  run -0 "$V" ok.rscene
  [[ "$output" != *RS7013* ]]
  run -0 --separate-stderr "$SIM" --steps 2 ok.rscene
  [[ "$stderr" != *RS7013* ]]
}

# two_bodies PRIM Z: a dynamic 1 m cube resting on a ground at 0 and a
# dynamic PRIM (0.5 m box, or radius 0.25 and height 0.5) at height Z on it.
two_bodies() {
  printf 'raisim_engine_scene 2\n'
  printf 'object /World/G ground 0 0 0 1 0 0 0 10 10 1 1 0 0 default - false true true - static true 1 18446744073709551615\n'
  printf 'object /World/Cube box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 10 default - false true false - dynamic true 1 18446744073709551615\n'
  local scale="1 1 1"
  [ "$1" = box ] && scale="0.5 0.5 0.5"
  printf 'object /World/Top %s 0.2 0 %s 1 0 0 0 %s 0.25 0.5 1 default - false true false - dynamic true 1 18446744073709551615\n' "$1" "$2" "$scale"
}

@test "bodies: a box that starts inside another is RS7013 from validate and sim alike, once each; resting on it is not" {
  two_bodies box 1.224 > in.rscene  # 2.6 cm into the cube
  run -0 "$V" in.rscene
  [[ "$output" == *"in.rscene:4:"*"warning: dynamic body '/World/Top' starts 0.026 m inside '/World/Cube'"*"[RS7013]"* ]]
  [ "$(grep -c RS7013 <<<"$output")" -eq 1 ]
  run -0 --separate-stderr "$SIM" --steps 2 in.rscene
  [[ "$stderr" == *"in.rscene:4:"*"warning: dynamic body '/World/Top' starts 0.026 m inside '/World/Cube'"*"[RS7013]"* ]]
  [ "$(grep -c RS7013 <<<"$stderr")" -eq 1 ]
  for prim in box sphere capsule; do
    z=1.245; [ $prim = capsule ] && z=1.495  # 5 mm into the cube: contact
    two_bodies $prim $z > ok.rscene
    run -0 "$V" ok.rscene
    [[ "$output" != *RS7013* ]] || { echo "$prim: $output"; false; }
    run -0 --separate-stderr "$SIM" --steps 2 ok.rscene
    [[ "$stderr" != *RS7013* ]] || { echo "$prim: $stderr"; false; }
  done
}

@test "bodies: a cylinder inside a box is rscene-sim's RS7013 (no exact test in validate)" {
  two_bodies cylinder 1.1 > cyl.rscene
  run -0 "$V" cyl.rscene
  [[ "$output" != *RS7013* ]]
  run -0 --separate-stderr "$SIM" --steps 2 cyl.rscene
  # (named by the first body of Bullet's contact: either may come first)
  [[ "$stderr" == *"warning: dynamic body '/World/"*"' starts 0.15 m inside '/World/"*"[RS7013]"* ]]
  [ "$(grep -c RS7013 <<<"$stderr")" -eq 1 ]
}

@test "bodies: a dynamic box inside a static one is rscene-sim's RS7013 (validate judges dynamic pairs)" {
  two_bodies box 1.224 | sed 's|/World/Cube box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 10 default - false true false - dynamic|/World/Cube box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 10 default - false true false - static|' > st.rscene
  grep -q 'Cube.* static ' st.rscene
  run -0 "$V" st.rscene
  [[ "$output" != *RS7013* ]]
  run -0 --separate-stderr "$SIM" --steps 2 st.rscene
  [[ "$stderr" == *"st.rscene:4:"*"warning: dynamic body '/World/Top' starts "*" inside '/World/Cube'"*"[RS7013]"* ]]
  [ "$(grep -c RS7013 <<<"$stderr")" -eq 1 ]
}
