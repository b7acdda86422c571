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
  [ -z "$stderr" ]
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
