#!/usr/bin/env bats
# Engine 2 projects (README, "Engine 2 projects"): a folder with a
# raisim_engine2_project file as an operand of every tool, its file checked
# by rscene-validate, and its scenes' assets found through asset_directory.

load helpers

# make_project: ./proj with two scenes, the crate mesh in assets/ and a
# default scene; the scenes name the mesh as `meshes/crate.obj`, found only
# through the project's asset_directory.
make_project() {
  mkdir -p proj/assets/meshes proj/scenes/more
  cp "$DATA/render_assets/crate.obj" "$DATA/render_assets/crate.mtl" "$DATA/render_assets/checker.png" proj/assets/meshes/
  cat > proj/raisim_engine2_project <<'EOF'
raisim_engine2_project 1
name Test Project
asset_directory assets
scene_directory scenes
default_scene scenes/crate.rscene
description Two scenes and a crate.
EOF
  sed 's|render_assets/crate.obj|meshes/crate.obj|' "$DATA/render_mesh.rscene" > proj/scenes/crate.rscene
  printf 'raisim_engine_scene 2\nobject /World/Ball sphere 0 0 1 1 0 0 0 0.5 0.5 0.5 1 1 1 default engine_default false true false - dynamic true 1 18446744073709551615\n' \
    > proj/scenes/more/ball.rscene
}

@test "project: rscene-validate PROJECT/ checks the project file and every scene, finding assets in asset_directory" {
  in_workdir
  make_project
  run -0 --separate-stderr "$BIN/rscene-validate" --check-files proj/
  [ "$output" = "" ]
  [ "$stderr" = "no issues in 3 files" ]
  # The same scene named directly finds the same mesh: its project is found from its folder,
  # however the scene is named (a bare name, ./, an absolute path).
  run -0 "$BIN/rscene-validate" --check-files proj/scenes/crate.rscene
  (cd proj/scenes && "$BIN/rscene-validate" --check-files crate.rscene && "$BIN/rscene-validate" --check-files ./crate.rscene)
  run -0 "$BIN/rscene-validate" --check-files "$PWD/proj/scenes/crate.rscene"
  # Outside the project, the mesh is not found.
  cp proj/scenes/crate.rscene lone.rscene
  run -1 "$BIN/rscene-validate" --check-files lone.rscene
  [[ "$output" == *"lone.rscene:5:"*"[RS5001]"* ]]
}

@test "project: a defect in the project file is reported at file:line:col with its code" {
  in_workdir
  make_project
  sed -i 's|^scene_directory scenes|scene_directory scenez|; s|^name |title |' proj/raisim_engine2_project
  run -1 --separate-stderr "$BIN/rscene-validate" proj
  [[ "$output" == *"proj/raisim_engine2_project:2:1: warning: unknown project record 'title' (ignored) [RS1202]"* ]]
  [[ "$output" == *"proj/raisim_engine2_project:4:17: error: scene_directory 'scenez' does not exist"*"[RS1206]"* ]]
  # a symlink loop is there, but cannot be reached: said so, not "does not exist"
  ln -s scenez2 proj/scenez && ln -s scenez proj/scenez2
  run -1 --separate-stderr "$BIN/rscene-validate" proj
  [[ "$output" == *"proj/raisim_engine2_project:4:17: error: scene_directory 'scenez' cannot be reached: Too many levels of symbolic links (looked for"*"[RS1206]"* ]]
  printf 'raisim_engine2_project 2\n' > proj/raisim_engine2_project
  run -1 "$BIN/rscene-validate" proj/raisim_engine2_project
  [[ "$output" == *"proj/raisim_engine2_project:1:24: error: unsupported project version '2' (only 1 exists) [RS1201]"* ]]
  run -0 "$BIN/rscene-validate" --list-checks
  [[ "$output" == *"RS1207"* ]]
  # a default_scene that is no scene is the project file's finding, and not read as a scene
  make_project
  sed -i 's|^default_scene .*|default_scene assets/meshes/crate.obj|' proj/raisim_engine2_project
  run -1 --separate-stderr "$BIN/rscene-validate" proj
  [[ "$output" == *"proj/raisim_engine2_project:5:15: error: default_scene 'assets/meshes/crate.obj' is not a .rscene file"*"[RS1207]"* ]]
  [[ "$output" != *"crate.obj:1:"* ]]
}

@test "project: rscene-fmt --check PROJECT formats its scenes, not its project file" {
  in_workdir
  make_project
  printf 'raisim_engine_scene 2\nobject /World/B box 0 0 1 1 0 0 0 1.0 1 1 1 1 1 default engine_default false true false - dynamic true 1 18446744073709551615\n' \
    > proj/scenes/b.rscene
  cp proj/raisim_engine2_project before
  run -1 "$BIN/rscene-fmt" --check proj
  [[ "$output" == *"proj/scenes/b.rscene"* ]]
  [[ "$output" != *"raisim_engine2_project"* ]]
  run -0 "$BIN/rscene-fmt" -i proj
  cmp before proj/raisim_engine2_project
  run -0 "$BIN/rscene-fmt" --check proj
  # its project file stands for the project as the folder does: many
  # scenes' text on one standard output is refused alike
  for p in proj proj/raisim_engine2_project; do
    run -2 --separate-stderr "$BIN/rscene-fmt" "$p"
    [ -z "$output" ]
    [ "$stderr" = "rscene-fmt: error: a directory or project operand needs --check, --diff or --in-place" ]
  done
  run -0 "$BIN/rscene-fmt" --check proj/raisim_engine2_project
}

@test "project: where one scene is meant, a project is its default scene" {
  needs_tools rscene-sim rscene-to-json rscene-render
  in_workdir
  make_project
  run -0 "$BIN/rscene-to-json" proj
  [[ "$output" == *'"/World/Crate"'* ]]
  run -0 "$BIN/rscene-sim" --steps 2 proj -o out.rscene
  grep -q '^object /World/Crate mesh' out.rscene
  # The mesh is found through asset_directory: drawn, the crate covers the image's middle.
  run -0 "$BIN/rscene-render" proj -o crate.png
  run -0 "$BIN/rscene-render" proj/scenes/crate.rscene -o direct.png
  cmp crate.png direct.png
  sed -i '/^default_scene/d' proj/raisim_engine2_project
  run -2 --separate-stderr "$BIN/rscene-to-json" proj
  [ "$output" = "" ]
  [ "$stderr" = "rscene-to-json: error: project 'proj' has no default_scene: name one of its scenes" ]
  sed -i 's|^raisim_engine2_project 1|raisim_engine2_project 9|' proj/raisim_engine2_project
  refused "proj/raisim_engine2_project:1:24: error: unsupported project version '9'" "$BIN/rscene-sim" --steps 1 proj
}

@test "project: a project file that is not a regular file is refused at once, never read" {
  in_workdir
  make_project
  for kind in fifo zero dir loop; do
    rm -rf proj/raisim_engine2_project
    case $kind in
      fifo) mkfifo proj/raisim_engine2_project ;;
      zero) ln -s /dev/zero proj/raisim_engine2_project ;;
      dir) mkdir proj/raisim_engine2_project ;;
      loop) ln -s raisim_engine2_project proj/raisim_engine2_project ;;
    esac
    run -1 bounded 1000000 10 "$BIN/rscene-validate" proj
    [[ "$output" == *"proj/raisim_engine2_project: error: cannot read the project file"*"[RS1201]"* ]] || { echo "$kind: $output"; false; }
    run -2 --separate-stderr bounded 1000000 10 "$BIN/rscene-to-json" proj
    [[ "$stderr" == *"proj/raisim_engine2_project: error: cannot read the project file"*"[RS1201]"* ]] || { echo "$kind: $stderr"; false; }
  done
  rm -f proj/raisim_engine2_project
  printf '\xef\xbb\xbfraisim_engine2_project 1\nscene_directory scenes\n' > proj/raisim_engine2_project
  run -1 "$BIN/rscene-validate" proj
  [[ "$output" == *"proj/raisim_engine2_project:1:1: error: project file starts with a UTF-8 byte order mark [RS1201]"* ]]
}

@test "project: a stop signal ends a tool waiting to read a FIFO operand" {
  needs_tools rscene-sim
  in_workdir
  mkfifo wait.rscene
  "$BIN/rscene-sim" --steps 1 wait.rscene -o out.rscene &
  pid=$!
  sleep 0.5
  kill -TERM "$pid"
  rc=0
  wait "$pid" || rc=$?
  [ "$rc" -eq 143 ]
  [ ! -e out.rscene ]
}
