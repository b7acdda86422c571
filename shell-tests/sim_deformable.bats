#!/usr/bin/env bats
# rscene-sim with deformable records (issue 14): the particles in the
# trajectory, the record written back unchanged, pinned vertices held,
# identical runs, and hostile records refused at their key.

load helpers
SIM="$BIN/rscene-sim"

# A 9 x 9 vertex cloth 2 m a side (bench/soft/cloth_gen.sh), 0.7 m above a
# sphere on the ground; EXTRA goes on its deformable line.
scene() {
  bash "$ROOT/bench/soft/cloth_gen.sh" . 9
  sed -i "s|^deformable .*|& $1|" cloth.rscene
}

setup() {
  needs_tools rscene-sim
  in_workdir
}

@test "the trajectory carries the cloth's particles and the record is written back unchanged" {
  scene "pinnedVertices=0,8"
  run -0 --separate-stderr "$SIM" --duration 0.5 --every 50 --trajectory t.jsonl cloth.rscene
  # the one message: the record keeps its start pose in the scene written (RS7079)
  [ "$(grep -c 'warning:' <<<"$stderr")" -eq 1 ]
  [[ "$stderr" == "cloth.rscene:6:1: warning: deformable '/World/Cloth' is written back at the start pose"*"[RS7079]"* ]]
  grep -qxF "$(grep '^deformable' cloth.rscene)" <<<"$output"
  # States at t = 0, 0.25 and 0.5 s (every 50 steps of 5 ms), 81 points each.
  [ "$(grep -c '"path":"/World/Cloth"' t.jsonl)" -eq 3 ]
  python3 - <<'PY'
import json
lines = [json.loads(l) for l in open("t.jsonl") if "/World/Cloth" in l]
first, last = lines[0]["points"], lines[-1]["points"]
assert len(first) == 81 and len(last) == 81
assert first[0] == last[0] == [-1, -1, 1.2], (first[0], last[0])  # pinned: not moved at all
assert first[8] == last[8] == [1, -1, 1.2]
assert last[80][2] < 1.2 - 0.3, last[80]  # the free corner fell
PY
}

@test "runs are byte-identical" {
  scene ""
  "$SIM" --duration 0.5 --trajectory a.jsonl cloth.rscene > a.rscene
  "$SIM" --duration 0.5 --trajectory b.jsonl cloth.rscene > b.rscene
  cmp a.jsonl b.jsonl
  cmp a.rscene b.rscene
}

@test "a pinned vertex outside the mesh is an error at pinnedVertices" {
  scene "pinnedVertices=0,99"
  run -2 --separate-stderr "$SIM" --steps 1 cloth.rscene
  [ "${stderr%%$'\n'*}" = "cloth.rscene:6:208: error: deformable '/World/Cloth': pinnedVertices 99 is not a vertex of cloth.obj (it has 81) [RS7081]" ]
}

@test "a pinned vertex that is no whole number (2.7, 1e30) is validate's RS2003 at the value; -3 is RS7081 at pinnedVertices" {
  for v in 2.7 1e30; do
    scene "pinnedVertices=0,$v"
    run -2 --separate-stderr "$SIM" --steps 1 cloth.rscene
    [[ "${stderr%%$'\n'*}" == "cloth.rscene:6:210: error: expected an integer, found '$v' [RS2003]" ]]
    run -1 "$BIN/rscene-validate" cloth.rscene
    [[ "${lines[0]}" == "cloth.rscene:6:210: error: expected an integer, found '$v' [RS2003]" ]]
  done
  scene "pinnedVertices=0,-3"
  run -2 --separate-stderr "$SIM" --steps 1 cloth.rscene
  [[ "${stderr%%$'\n'*}" == "cloth.rscene:6:208: error: deformable '/World/Cloth': pinnedVertices holds a value that is not a vertex index (a whole number from 0 to 80) [RS7081]" ]]
}

@test "a collisionRadius larger than the body is an error at collisionRadius" {
  scene "collisionRadius=100"
  run -2 --separate-stderr "$SIM" --steps 1 cloth.rscene
  [[ "${stderr%%$'\n'*}" == *"error: deformable '/World/Cloth': collisionRadius 100 m is larger than the body itself"*"[RS7081]" ]]
}

@test "a negative totalMass is an error at totalMass" {
  bash "$ROOT/bench/soft/cloth_gen.sh" . 9
  sed -i 's/totalMass=0.5/totalMass=-1/' cloth.rscene
  run -2 --separate-stderr "$SIM" --steps 1 cloth.rscene
  [[ ${stderr%%$'\n'*} == "cloth.rscene:6:"*": error: deformable '/World/Cloth': totalMass -1 is not in (0, 1e12] kg [RS7081]" ]]
}

@test "fem needs a closed mesh" {
  bash "$ROOT/bench/soft/cloth_gen.sh" . 9
  sed -i 's/ cloth cloth.obj/ fem cloth.obj/' cloth.rscene
  run -2 --separate-stderr "$SIM" --steps 1 cloth.rscene
  [[ ${stderr%%$'\n'*} == "cloth.rscene:6:29: error: deformable '/World/Cloth': a filled body needs a closed mesh: "*"[RS7081]" ]]
}

@test "a fill past a million particles is refused at particleSpacing, at once" {
  bash "$ROOT/bench/soft/cloth_gen.sh" . 9
  printf 'v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n' > cube.obj
  printf 'f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n' >> cube.obj
  sed -i 's/ cloth cloth.obj/ fem cube.obj/; s/^deformable.*/& particleSpacing=0.001/' cloth.rscene
  # 8e9 grid points: counted column by column, refused before one is made.
  run -2 --separate-stderr timeout 20 "$SIM" --steps 1 cloth.rscene
  [ "${stderr%%$'\n'*}" = "cloth.rscene:6:206: error: deformable '/World/Cloth': a fill at this spacing makes more than 1000000 particles [RS7081]" ]
}

# --- issue 24: hostile deformables --------------------------------------

@test "issue 24 (04): a run whose cloth solver work passes the cap is refused up front with its cost, at iterations" {
  scene "iterations=2000 substeps=100"
  # 465 x 2000 x 100 = 9.3e7 updates a step: one step is under the warning's 5e8
  run -0 --separate-stderr "$SIM" --steps 1 -o /dev/null cloth.rscene
  [ "$(grep -c 'RS707[56]' <<<"$stderr")" -eq 0 ]
  # 1000 steps = 9.3e10 updates: refused at once, nothing written
  SECONDS=0
  run -2 --separate-stderr "$SIM" --steps 1000 -o out.rscene cloth.rscene
  [ "$SECONDS" -lt 10 ]
  [ ! -e out.rscene ]
  [[ "${stderr%%$'\n'*}" == "cloth.rscene:6:"*": error: the deformables' solver work for this run is 9.3e+07 updates a step x 1000 steps = 9.3e+10 updates"*"about 31 min of one core"*"takes 9.3e+07 updates a step; the run's 9.3e+10 updates are more than the limit of 3e+10 updates a run (about 10 min); nothing was simulated [RS7075]" ]]
  [[ "$stderr" == *"hint: lower iterations or substeps"* ]]
  # 20 steps = 1.86e9: the cost is a warning before the first step (the run itself is cut short here)
  run --separate-stderr timeout -s INT 5 "$SIM" --steps 20 -o /dev/null cloth.rscene
  [[ "$stderr" == *"= 1.86e+09 updates"*"about 37 s of one core"*"[RS7076]"* ]]
}

@test "issue 24 (07): a cloth starting below the ground is refused at its position (RS7077), nothing written" {
  scene ""
  sed -i 's|cloth.obj 0 0 1.2 |cloth.obj 0 0 -0.2 |' cloth.rscene
  run -2 --separate-stderr "$SIM" --steps 100 --trajectory t.jsonl -o out.rscene cloth.rscene
  [[ "${stderr%%$'\n'*}" == "cloth.rscene:6:"*": error: deformable '/World/Cloth': particle 0 at (-1, -1, -0.2) starts 0.2 m inside the ground or another body"*"[RS7077]" ]]
  [ ! -e out.rscene ] && [ ! -e t.jsonl ]
}

@test "a cloth starting up to half its collisionRadius into the ground is moved out with a warning (RS7016) and rests, not diverged (RS7024)" {
  # 4 mm and 0.5 mm into the ground (radius 1 cm), at the repro's 1 ms step.
  for z in 0.006 0.0095; do
    scene ""
    sed -i "/^object \/World\/Ball/d; s|cloth.obj 0 0 1.2 |cloth.obj 0 0 $z |; s|^time_step .*|time_step 0.001|" cloth.rscene
    run -0 --separate-stderr "$SIM" --duration 1 --until-rest --report --trajectory t.jsonl -o out.rscene cloth.rscene
    [[ "${stderr_lines[0]}" == "cloth.rscene:5:"*": warning: deformable '/World/Cloth': 81 particles start inside the ground or another body, up to "*" m deep (its sphere of collisionRadius 0.01 m overlapping it); moved out along the contact normal before the first step [RS7016]" ]]
    [[ $stderr != *RS7024* ]]
    jq -e '.atRest == true' <<<"${stderr_lines[-1]}"
  done
  # resting on the ground from the start: nothing to say
  sed -i "s|cloth.obj 0 0 0.0095 |cloth.obj 0 0 0.01 |" cloth.rscene
  run -0 --separate-stderr "$SIM" --steps 10 -o out.rscene cloth.rscene
  [[ $stderr != *RS7016* ]]
}

@test "issue 24 (07): a thickness of 1e-300 is refused by validate and sim alike (RS7081 at thickness)" {
  scene "youngsModulus=1e6 thickness=1e-300"
  run -1 "$BIN/rscene-validate" cloth.rscene
  [[ "${lines[0]}" == "cloth.rscene:6:"*": error: deformable '/World/Cloth': thickness 1e-300 m is not 0 or in [1e-06, 10] m [RS7081]" ]]
  run -2 --separate-stderr "$SIM" --steps 1 cloth.rscene
  [[ "${stderr%%$'\n'*}" == "cloth.rscene:6:"*"thickness 1e-300 m is not 0 or in [1e-06, 10] m [RS7081]" ]]
}

@test "issue 24 (07): a cloth 100 times heavier than a dynamic box it may touch is refused at totalMass (RS7078)" {
  scene "totalMass=100"
  sed -i 's|^object /World/Ball sphere 0 0 0.5 1 0 0 0 1 1 1 0.5 1 0 \(.*\) static |object /World/Ball sphere 0 0 0.5 1 0 0 0 1 1 1 0.5 1 1 \1 dynamic |' cloth.rscene
  grep -q 'Ball.* dynamic ' cloth.rscene
  run -2 --separate-stderr "$SIM" --steps 100 -o out.rscene cloth.rscene
  [[ "${stderr%%$'\n'*}" == *"error: deformable '/World/Cloth': totalMass 100 kg is more than 20 times the mass of dynamic body '/World/Ball'"*"[RS7078]" ]]
  [ ! -e out.rscene ]
}

@test "issue 24 (12): rscene-sim | rscene-render: the written scene warns once that the cloth keeps its start pose, and the README shows --trajectory" {
  scene ""
  run -0 --separate-stderr "$SIM" --steps 10 -o out.rscene cloth.rscene
  [ "$(grep -c 'RS7079' <<<"$stderr")" -eq 1 ]
  [[ "$stderr" == *"hint: to draw the simulated particles, write them with rscene-sim --trajectory t.jsonl and draw with rscene-render --trajectory t.jsonl"* ]]
  grep -qF 'rscene-sim --trajectory t.jsonl -o out.rscene examples/soft_bodies.rscene' "$ROOT/README.md"
  grep -qF 'rscene-render --trajectory t.jsonl out.rscene' "$ROOT/README.md"
  # a scene without deformables says nothing of them
  grep -v '^deformable' cloth.rscene > rigid.rscene
  run -0 --separate-stderr "$SIM" --steps 10 -o /dev/null rigid.rscene
  [ -z "$stderr" ]
}

@test "issue 24: what sim writes, sim reads: the examples with deformables settle, are written, validate clean and settle again" {
  needs_tools rscene-validate
  cp -R "$ROOT/examples/." .
  n=0
  for f in soft_bodies*.rscene; do
    grep -q '^deformable ' "$f" || continue
    n=$((n + 1))
    run -0 --separate-stderr "$SIM" --duration 1 -o "settled-$f" "$f"
    run -0 "$BIN/rscene-validate" --check-files "settled-$f"
    [ "$(grep -c 'error\|warning' <<<"$output")" -eq 0 ]
    run -0 --separate-stderr "$SIM" --duration 1 -o "again-$f" "settled-$f"
    # the only message is the deformables' start pose, as on the first run
    [ -z "$(grep -v RS7079 <<<"$stderr" | grep 'error:\|warning:')" ]
  done
  [ "$n" -ge 1 ]
}

@test "RS7078 counts robot links: a cloth more than 20 times a moving link's mass is refused, naming the link; groups that never meet are not" {
  scene "totalMass=20"
  cat > arm.urdf <<'URDF'
<robot name="arm">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base">
    <inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.4 0.4"/></geometry></collision>
  </link>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><origin xyz="0 0 0.5"/><axis xyz="1 0 0"/>
    <limit lower="-3" upper="3" effort="10" velocity="1"/>
  </joint>
  <link name="arm">
    <inertial><mass value="0.5"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><origin xyz="0 0 0.2"/><geometry><box size="0.1 0.1 0.4"/></geometry></collision>
  </link>
</robot>
URDF
  { cat cloth.rscene; echo "articulated_resource arm_res Arm arm.urdf"
    echo "articulated /World/Arm arm_res 4 0 0.2 1 0 0 0 true true ${ARM_EXTRA:-}"; } > arm.rscene
  run -2 --separate-stderr "$SIM" --steps 10 -o out.rscene arm.rscene
  [[ "${stderr%%$'\n'*}" == *"error: deformable '/World/Cloth': totalMass 20 kg is more than 20 times the mass of link 'arm' of articulated system '/World/Arm' (0.5 kg) it may touch"*"[RS7078]" ]]
  [ ! -e out.rscene ]
  # The robot's collisionMask leaves out the cloth's group 1: they never meet.
  sed -i 's|^articulated /World/Arm .*|& collisionMask=2|' arm.rscene
  run -0 --separate-stderr "$SIM" --steps 10 -o out.rscene arm.rscene
  [[ $stderr != *RS7078* ]]
}

@test "the per-step work cap (RS7081) is the scene model's: validate --check-files and sim refuse at the same place with the same words" {
  scene "iterations=10000 substeps=1000"
  # 465 x 10000 x 1000 = 4.65e9 updates a step, past 1e9: counting the
  # constraints needs the mesh, so validate says it with --check-files.
  run -1 --separate-stderr "$BIN/rscene-validate" --check-files cloth.rscene
  v=$(grep 'RS7081' <<<"$output")
  [[ $v == "cloth.rscene:6:"*": error: deformable '/World/Cloth': iterations x substeps x (constraints + particles) is 4.65e+09 a step (at most 1e+09) [RS7081]" ]]
  run -2 --separate-stderr "$SIM" --steps 1 -o out.rscene cloth.rscene
  [ "${stderr%%$'\n'*}" = "$v" ]
  [ ! -e out.rscene ]
}
