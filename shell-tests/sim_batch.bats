#!/usr/bin/env bats
# rscene-sim with several scenes (rscene-sim(1), BATCHES): outputs named by
# {stem} and {dir}, a failing scene that does not stop the others, outputs
# checked against each other before any work, --report lines, and a batch
# scene's outputs byte-identical to the same scene simulated alone.

load helpers
SIM="$BIN/rscene-sim"

# Three small scenes under scenes/: boxes dropped from different heights.
make_scenes() {
  mkdir -p scenes out
  local i
  for i in 1 2 3; do
    sed "s|^object /World/Box box 0 0 1 |object /World/Box box 0 0 $i |" "$DATA/sim_drop.rscene" > "scenes/s$i.rscene"
  done
}

setup() {
  needs_tools rscene-sim
  in_workdir
  make_scenes
}

@test "batch: a folder's scenes are written by the -o pattern, with a summary line" {
  run -0 --separate-stderr "$SIM" --steps 50 -o 'out/{stem}.settled.rscene' scenes/
  [ -z "$output" ]
  [ "$stderr" = "rscene-sim: 3 scenes: 3 simulated" ]
  [ "$(ls out)" = "$(printf 's1.settled.rscene\ns2.settled.rscene\ns3.settled.rscene')" ]
  # {dir} is the folder as given.
  mkdir -p out/scenes
  run -0 "$SIM" --steps 5 -o 'out/{dir}/{stem}.rscene' scenes/s1.rscene scenes/s2.rscene
  [ -f out/scenes/s1.rscene ] && [ -f out/scenes/s2.rscene ]
}

@test "batch: each scene's output is byte-identical to the scene simulated alone" {
  # A bad scene between the good ones must not change them either.
  cp "$DATA/sim_bad_mass.rscene" scenes/s2a.rscene
  run -2 "$SIM" --duration 0.5 -o 'out/{stem}.rscene' --trajectory 'out/{stem}.jsonl' scenes
  for i in 1 2 3; do
    "$SIM" --duration 0.5 -o "alone$i.rscene" --trajectory "alone$i.jsonl" "scenes/s$i.rscene"
    cmp "alone$i.rscene" "out/s$i.rscene"
    cmp "alone$i.jsonl" "out/s$i.jsonl"
  done
  # The scenes differ (else the comparison above proves little).
  ! cmp -s out/s1.rscene out/s3.rscene
}

@test "batch: a broken scene among good ones: the others are written, its error names its file, exit 2" {
  cp "$DATA/sim_bad_mass.rscene" scenes/s2a.rscene
  printf 'raisim_engine_scene 1\nobject /World/X box\n' > scenes/s0.rscene
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{stem}.rscene' scenes/
  [ -z "$output" ]
  [[ "$stderr" == *"scenes/s2a.rscene:2:"*"error: "* ]]
  [[ "$stderr" == *"scenes/s0.rscene:2:"*"error: "* ]]
  [ "${stderr_lines[-1]}" = "rscene-sim: 5 scenes: 3 simulated, 2 failed: scenes/s0.rscene, scenes/s2a.rscene" ]
  [ -f out/s1.rscene ] && [ -f out/s2.rscene ] && [ -f out/s3.rscene ]
  [ ! -e out/s2a.rscene ] && [ ! -e out/s0.rscene ]
  # A missing file operand is one failed scene too.
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{stem}.b.rscene' scenes/s1.rscene nothere.rscene
  [[ "$stderr" == *"rscene-sim: error: cannot read 'nothere.rscene'"* ]]
  [ "${stderr_lines[-1]}" = "rscene-sim: 2 scenes: 1 simulated, 1 failed: nothere.rscene" ]
  [ -f out/s1.b.rscene ]
}

@test "batch: two scenes whose outputs are one file are refused before any work" {
  mkdir other && cp scenes/s1.rscene other/
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{stem}.rscene' scenes/ other/
  [ "$stderr" = "rscene-sim: error: scenes 'scenes/s1.rscene' and 'other/s1.rscene' would both write 'out/s1.rscene' (-o): they share a file name in different folders: put {dir} in it as well" ]
  [ -z "$(ls out)" ]
  # -o of one scene and --trajectory of another.
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{stem}' --trajectory 'out/s2' scenes/s1.rscene scenes/s2.rscene
  [[ "$stderr" == "rscene-sim: error: --trajectory 'out/s2' names one file for 2 scenes"* ]]
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{stem}' --trajectory 'out/{stem}x' scenes/s1.rscene scenes/s1x.rscene scenes/s2.rscene
  [[ "$stderr" == "rscene-sim: error: scenes 'scenes/s1.rscene' and 'scenes/s1x.rscene' would both write 'out/s1x' (--trajectory and -o):"* ]]
  [ -z "$(ls out)" ]
  # The same scene twice.
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{stem}' scenes/s1.rscene scenes/s1.rscene
  [[ "$stderr" == *"would both write 'out/s1'"* ]]
  [[ "$stderr" == *"would both write 'out/s1' (-o): the scene is named twice: name it once" ]]
  # {dir} alone: two scenes of one folder
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{dir}.rscene' scenes/s1.rscene scenes/s2.rscene
  [[ "$stderr" == *"would both write 'out/scenes.rscene' (-o): they are in one folder: put {stem} in it as well" ]]
  # An output folder that cannot be made (a file is in the way), for any scene.
  touch afile
  run -2 --separate-stderr "$SIM" --steps 10 -o 'afile/{stem}.rscene' scenes/
  [[ "$stderr" == "rscene-sim: error: -o: cannot create the folder 'afile': "* ]]
  [ -z "$(ls out)" ]
}

@test "batch: the missing folders of a pattern's outputs are made; a plain -o's folder must exist" {
  run -0 --separate-stderr "$SIM" --steps 5 -o 'new/{dir}/{stem}.rscene' --trajectory 'traj/{dir}/{stem}.jsonl' scenes/
  [ -s new/scenes/s1.rscene ] && [ -s new/scenes/s3.rscene ] && [ -s traj/scenes/s2.jsonl ]
  # one scene named by a pattern: the same
  run -0 "$SIM" --steps 5 -o 'one/{stem}/settled.rscene' scenes/s1.rscene
  [ -s one/s1/settled.rscene ]
  run -2 --separate-stderr "$SIM" --steps 5 -o nowhere/x.rscene scenes/s1.rscene
  [[ "$stderr" == "rscene-sim: error: nowhere/x.rscene: cannot create a file in 'nowhere'"* ]]
  [ ! -e nowhere ]
}

@test "batch: an output pattern that names the scenes themselves simulates them in place" {
  cp -r scenes before
  run -0 --separate-stderr "$SIM" --steps 50 -o 'scenes/{stem}.rscene' scenes/
  [ "$stderr" = "rscene-sim: 3 scenes: 3 simulated" ]
  for i in 1 2 3; do
    "$SIM" --steps 50 -o "alone$i.rscene" "before/s$i.rscene"
    cmp "alone$i.rscene" "scenes/s$i.rscene"
    ! cmp -s "before/s$i.rscene" "scenes/s$i.rscene"
  done
}

@test "batch: --sensors makes no folder for a scene without sensors" {
  run -0 --separate-stderr "$SIM" --steps 5 -o 'out/{stem}.rscene' --sensors 'sens/{stem}' scenes/
  [ -f out/s1.rscene ]
  [ ! -e sens/s1 ] && [ ! -e sens/s2 ] && [ ! -e sens/s3 ]
}

@test "batch: -o without {stem} or {dir}, or standard output, is refused for several scenes" {
  run -2 --separate-stderr "$SIM" --steps 10 -o out/one.rscene scenes/s1.rscene scenes/s2.rscene
  [ "$stderr" = "rscene-sim: error: -o 'out/one.rscene' names one file for 2 scenes: put {stem} (the scene's file name without .rscene) or {dir} (its folder) in it" ]
  run -2 --separate-stderr "$SIM" --steps 10 scenes/
  [ "$output" = "" ]
  [[ "$stderr" == "rscene-sim: error: -o - (standard output) cannot take several scenes (3 scenes)"* ]]
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{stem}' --sensors sensors scenes/
  [[ "$stderr" == "rscene-sim: error: --sensors 'sensors' names one file for 3 scenes"* ]]
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{name}' scenes/
  [[ "$stderr" == "rscene-sim: error: -o 'out/{name}' names one file"* ]]
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{stem}{name}' scenes/
  [ "$stderr" = "rscene-sim: error: -o: unknown field {name} in output pattern 'out/{stem}{name}' (fields: {stem}, {dir})" ]
  [ -z "$(ls out)" ]
}

@test "batch: --trajectory and --sensors by pattern" {
  run -0 "$SIM" --steps 10 --every 5 -o 'out/{stem}.rscene' --trajectory 'out/{stem}.csv' --trajectory-format csv \
    --sensors 'out/{stem}-sensors' scenes/
  for i in 1 2 3; do
    [ "$(head -c 5 "out/s$i.csv")" = "time," ]
    "$SIM" --steps 10 --every 5 --trajectory-format csv --trajectory alone.csv "scenes/s$i.rscene" > /dev/null
    cmp alone.csv "out/s$i.csv"
  done
  # Scenes with sensors: each records into its own folder, as alone.
  mkdir cell && cp -r "$ROOT/examples/robots" cell/
  cp "$ROOT/examples/robot_cell.rscene" cell/a.rscene
  cp "$ROOT/examples/robot_cell.rscene" cell/b.rscene
  run -0 "$SIM" --duration 0.1 --pd-gains 100,2 --sensors 'out/{stem}-sensors' -o 'out/{stem}.cell.rscene' cell/
  [ -f out/a-sensors/World+Robot+Imu.csv ] && [ -f out/b-sensors/World+Robot+Imu.csv ]
  "$SIM" --duration 0.1 --pd-gains 100,2 --sensors alone -o alone.rscene cell/b.rscene
  diff -r alone out/b-sensors
  cmp alone.rscene out/b.cell.rscene
}

@test "batch: --report prints one JSON line per scene, a failed one with its status and first error" {
  cp "$DATA/sim_bad_mass.rscene" scenes/s2a.rscene
  run -2 --separate-stderr "$SIM" --steps 10 --report -o 'out/{stem}.rscene' scenes/
  jq -s -e 'length == 4' <(grep '^{' <<<"$stderr")
  grep '^{' <<<"$stderr" | jq -s -e '
    [.[].scene] == ["scenes/s1.rscene", "scenes/s2.rscene", "scenes/s2a.rscene", "scenes/s3.rscene"] and
    ([.[] | select(.status == 0) | .steps] == [10, 10, 10]) and
    (.[2].status == 2) and (.[2].error | test("^scenes/s2a.rscene:2:[0-9]+: error: .*\\[RS[0-9]+\\]$"))'
  # One scene: the object alone, as before.
  run -0 --separate-stderr "$SIM" --steps 10 --report -o out/one.rscene scenes/s1.rscene
  jq -e 'has("scene") | not' <<<"$stderr"
}

@test "batch: a robot file shared by scenes: every scene naming a broken one says so, the others match single runs" {
  cp "$DATA/robots/urdf/two_link.urdf" good.urdf
  cp "$DATA/robots/urdf/bad_xml.urdf" bad.urdf
  for r in good bad; do
    for i in 1 2; do
      printf 'raisim_engine_scene 1\narticulated_resource res R ../%s.urdf\narticulated /World/R res 0 0 %s 1 0 0 0 true true id=r\n' \
        "$r" "$i" > "scenes/$r$i.rscene"
    done
  done
  run -2 --separate-stderr "$SIM" --steps 20 -o 'out/{stem}.rscene' scenes/
  [ "$(grep -c 'bad.urdf:.*error' <<<"$stderr")" -ge 2 ]
  [[ "$stderr" == *"error"*"error"* ]]
  [ "${stderr_lines[-1]}" = "rscene-sim: 7 scenes: 5 simulated, 2 failed: scenes/bad1.rscene, scenes/bad2.rscene" ]
  for i in 1 2; do
    "$SIM" --steps 20 -o "alone$i.rscene" "scenes/good$i.rscene"
    cmp "alone$i.rscene" "out/good$i.rscene"
    "$SIM" --steps 20 -o /dev/null "scenes/bad$i.rscene" 2> "alone-bad$i.err" || true
    grep -F -f "alone-bad$i.err" <<<"$stderr" > /dev/null
  done
}

@test "batch: an Engine 2 project with a pattern is all its scenes; without one, its default scene" {
  mkdir -p proj/scenes/more
  printf 'raisim_engine2_project 1\nname P\nscene_directory scenes\ndefault_scene scenes/s1.rscene\n' > proj/raisim_engine2_project
  cp scenes/s1.rscene proj/scenes/
  cp scenes/s2.rscene proj/scenes/more/
  run -0 --separate-stderr "$SIM" --steps 10 -o 'out/{stem}.rscene' proj
  [ "$stderr" = "rscene-sim: 2 scenes: 2 simulated" ]
  [ -f out/s1.rscene ] && [ -f out/s2.rscene ]
  run -0 --separate-stderr "$SIM" --steps 10 -o out/default.rscene proj
  [ -z "$stderr" ]
  cmp out/default.rscene out/s1.rscene
}

@test "batch: a stop signal ends the batch by it; finished scenes stay written, the current one leaves nothing" {
  # The last scene's time step is 100 times shorter: 2,000,000 steps, seconds of stepping.
  printf 'raisim_engine_scene 1\ntime_step 0.00001\nobject /World/B box 0 0 1 1 0 0 0 1 1 1 1 1 1 default engine_default false true false - dynamic true 1 18446744073709551615\n' > scenes/z_long.rscene
  "$SIM" --duration 20 --every 1000 -o 'out/{stem}.rscene' --trajectory 'out/{stem}.jsonl' scenes/ 2> err &
  pid=$!
  for _ in $(seq 100); do [ -f out/s3.rscene ] && [ -e out/s3.jsonl ] && break; sleep 0.1; done
  sleep 0.3
  kill -TERM "$pid"
  status=0
  wait "$pid" || status=$?
  [ "$status" -eq 143 ]
  [ -f out/s1.rscene ] && [ -f out/s2.rscene ] && [ -f out/s3.rscene ]
  [ ! -e out/z_long.rscene ] && [ ! -e out/z_long.jsonl ]
  [ -z "$(find . -name '*.tmp*')" ]
  grep -q "stopped by a signal after 3 of 4 scenes" err
}

@test "batch: a mesh shared by scenes: an unreadable one fails every scene naming it, the others match single runs" {
  mkdir meshes
  printf 'not an obj\001' > meshes/rock.obj
  cp "$DATA/render_assets/crate.obj" meshes/
  rm scenes/*.rscene
  for i in 1 2; do
    sed 's|meshes/rock.obj|../meshes/rock.obj|' "$DATA/sim_missing_mesh.rscene" > "scenes/rock$i.rscene"
    sed 's|meshes/rock.obj|../meshes/crate.obj|' "$DATA/sim_missing_mesh.rscene" > "scenes/crate$i.rscene"
  done
  run -2 --separate-stderr "$SIM" --steps 10 -o 'out/{stem}.rscene' scenes/
  [[ "$stderr" == *"scenes/rock1.rscene:2:93: error: body '/World/Rock': cannot read mesh"*"[RS7007]"* ]]
  [[ "$stderr" == *"scenes/rock2.rscene:2:93: error: body '/World/Rock': cannot read mesh"*"[RS7007]"* ]]
  [ "${stderr_lines[-1]}" = "rscene-sim: 4 scenes: 2 simulated, 2 failed: scenes/rock1.rscene, scenes/rock2.rscene" ]
  for i in 1 2; do
    "$SIM" --steps 10 "scenes/crate$i.rscene" | cmp - "out/crate$i.rscene"
  done
}

@test "no output replaces a scene being read: --trajectory on the scene, one scene's output on another's" {
  cp scenes/s1.rscene single.rscene
  cp single.rscene before.rscene
  run -2 --separate-stderr "$SIM" --steps 5 -o out1.rscene --trajectory single.rscene single.rscene
  [ "$stderr" = "rscene-sim: error: --trajectory 'single.rscene' is the scene itself: it would be replaced by what --trajectory writes; write it elsewhere" ]
  cmp single.rscene before.rscene
  [ ! -e out1.rscene ]
  # in a batch: one scene's output is a later scene's input (order does not matter)
  mkdir -p x/a/b
  cp scenes/s1.rscene x/a/c.rscene
  cp scenes/s2.rscene x/a/b/c.rscene
  cp x/a/b/c.rscene c.before
  for order in "x/a/c.rscene x/a/b/c.rscene" "x/a/b/c.rscene x/a/c.rscene"; do
    # shellcheck disable=SC2086
    run -2 --separate-stderr "$SIM" --steps 5 -o '{dir}/b/{stem}.rscene' $order
    [[ "$stderr" == "rscene-sim: error: -o 'x/a/b/c.rscene' (of x/a/c.rscene) is the scene x/a/b/c.rscene, another input: it would be replaced before it is read; write it elsewhere" ]]
    cmp x/a/b/c.rscene c.before
  done
  [ ! -e x/a/b/b ]
  # a hard link to a scene is that scene
  ln x/a/c.rscene link.jsonl
  run -2 --separate-stderr "$SIM" --steps 5 -o 'o/{stem}.rscene' --trajectory link.jsonl x/a/c.rscene
  [[ "$stderr" == "rscene-sim: error: --trajectory 'link.jsonl' is the scene itself"* ]]
  rm link.jsonl
  # -o may still write each scene back in place
  run -0 "$SIM" --steps 5 -o '{dir}/{stem}.rscene' x/a/c.rscene x/a/b/c.rscene
}
