#!/usr/bin/env bats
# rscene-render's batches (CPU backend): several scenes, folders and
# projects in one run, each scene's images named by -o with {stem}/{dir};
# every output checked before anything is drawn; a scene that fails does
# not stop the others; a scene drawn in a batch gives the bytes it gives
# alone.

load helpers
RENDER="$BIN/rscene-render"

# scene NAME [X]: a small scene with a 64x48 camera and a box at X.
scene() {
  cat > "$1" << EOF
raisim_engine_scene 2
light /World/Sun -0.3 0.4 -1.0 3.5 id=sun type=directional position=0,0,5 color=1,1,1
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615 id=ground
object /World/Box box ${2:-1} 0 0.5 1 0 0 0 1 1 1 0.5 1 1.0 default - false true false - dynamic true 1 18446744073709551615 id=box
camera /World/Cam -4 0 1 1 0 0 0 60 0.05 100 64 48 rgb true id=cam
EOF
}

setup() {
  needs_tools rscene-render
  in_workdir
  mkdir -p scenes/sub
  scene scenes/a.rscene 1
  scene scenes/b.rscene 0
  scene scenes/sub/c.rscene -1
  export LP_NUM_THREADS=1  # llvmpipe's bytes do not depend on its threads (README)
}

@test "batch: a folder's scenes become thumbnails named by {stem}, with a summary line" {
  run -0 --separate-stderr "$RENDER" --width 32 --height 20 -o 'thumbs/{stem}.png' scenes/
  for s in a b c; do
    is_png "thumbs/$s.png"
    [ "$(png_size "thumbs/$s.png")" = "32x20" ]
  done
  [ "$(ls thumbs | wc -l)" -eq 3 ]
  [ "${stderr_lines[${#stderr_lines[@]} - 1]}" = "rscene-render: 3 scenes: 3 rendered" ]
  # {dir} keeps the folders apart; several operands are a batch too.
  run -0 "$RENDER" -o 'out/{dir}/{stem}-{name}.png' scenes/a.rscene scenes/sub/c.rscene
  is_png out/scenes/a-World_Cam.png
  is_png out/scenes/sub/c-World_Cam.png
}

@test "batch: a scene drawn in a batch gives the bytes it gives alone" {
  run -0 "$RENDER" -o 'thumbs/{stem}.png' scenes/
  for s in a b; do
    run -0 "$RENDER" -o "$s.png" "scenes/$s.rscene"
    cmp "$s.png" "thumbs/$s.png"
  done
  run -0 "$RENDER" -o c.png scenes/sub/c.rscene
  cmp c.png thumbs/c.png
  # The scenes differ: the batch did not draw one scene three times.
  ! cmp -s thumbs/a.png thumbs/b.png
}

@test "batch: after a scene with post-processing and other lights, a plain scene gives its own bytes" {
  # a0 (bloom, SSAO, FXAA, an emissive sphere) sets uniforms of programs
  # the next scenes use again: they must start as a fresh program's.
  cp "$DATA/render_post.rscene" scenes/a0.rscene
  echo "light /World/Spot 0 0 -1 5 type=spot position=0,0,3 coneDegrees=40 shadows=true" >> scenes/a0.rscene
  run -0 "$RENDER" -o 'thumbs/{stem}.png' scenes/a0.rscene scenes/a.rscene scenes/b.rscene
  run -0 "$RENDER" -o a0.png scenes/a0.rscene
  cmp a0.png thumbs/a0.png
  for s in a b; do
    run -0 "$RENDER" -o "$s.png" "scenes/$s.rscene"
    cmp "$s.png" "thumbs/$s.png"
  done
}

@test "batch: a broken scene is named, the others are written, exit 2" {
  printf 'raisim_engine_scene 2\nobject /World/X box oops\n' > scenes/broken.rscene
  run -2 --separate-stderr "$RENDER" -o 'thumbs/{stem}.png' scenes/
  [[ "$stderr" == *"scenes/broken.rscene:2:"*"error"* ]]
  [[ "$stderr" == *"rscene-render: error: scenes/broken.rscene: not rendered"* ]]
  [ "${stderr_lines[${#stderr_lines[@]} - 1]}" = "rscene-render: 4 scenes: 3 rendered, 1 failed: scenes/broken.rscene" ]
  is_png thumbs/a.png
  is_png thumbs/b.png
  is_png thumbs/c.png
  [ ! -e thumbs/broken.png ]
  # A missing file among the operands: the same.
  run -2 --separate-stderr "$RENDER" -o 'more/{stem}.png' scenes/a.rscene missing.rscene
  [[ "$stderr" == *"missing.rscene"* ]]
  is_png more/a.png
}

@test "batch: two scenes writing one file are refused before anything is drawn" {
  mkdir other
  scene other/a.rscene 2
  run -2 --separate-stderr "$RENDER" -o 'thumbs/{stem}.png' scenes/ other/
  [[ "$stderr" == *"scenes 'scenes/a.rscene' and 'other/a.rscene' would both write 'thumbs/a.png' (-o): they share a file name in different folders: put {dir} in it as well"* ]]
  [ ! -e thumbs ]
  # The same scene twice is the same clash.
  run -2 --separate-stderr "$RENDER" -o 'thumbs/{stem}.png' scenes/a.rscene scenes/a.rscene
  [[ "$stderr" == *"would both write 'thumbs/a.png' (-o): the scene is named twice: name it once"* ]]
  [ ! -e thumbs ]
  # {dir} alone: two scenes of one folder
  run -2 --separate-stderr "$RENDER" -o 'thumbs/{dir}.png' scenes/a.rscene scenes/b.rscene
  [[ "$stderr" == *"would both write 'thumbs/scenes.png' (-o): they are in one folder: put {stem} in it as well"* ]]
  [ ! -e thumbs ]
}

@test "batch: a size no scene can take is said once, before any scene is read" {
  run -2 --separate-stderr "$RENDER" --width 64 --height 48 --max-pixels 3000 -o 'thumbs/{stem}.png' scenes/
  [ "$stderr" = "rscene-render: error: --width/--height: 64x48 is 3072 pixels, more than --max-pixels 3000" ]
  [ ! -e thumbs ]
}

@test "batch: a project among the operands that cannot be read is said; the other scenes are drawn" {
  mkdir proj
  printf 'raisim_engine2_project 9\n' > proj/raisim_engine2_project
  run -2 --separate-stderr "$RENDER" -o 'thumbs/{stem}.png' proj scenes/a.rscene
  [[ "${stderr_lines[0]}" == "proj/raisim_engine2_project:1:"*"error: "* ]]
  is_png thumbs/a.png
  [ "${stderr_lines[${#stderr_lines[@]} - 1]}" = "rscene-render: 1 scene: 1 rendered; 1 operand could not be read" ]
}

@test "batch: a pattern's missing folders are made; a plain -o's folder must exist" {
  run -0 "$RENDER" -o 'new/{stem}/thumb.png' scenes/a.rscene
  is_png new/a/thumb.png
  run -2 --separate-stderr "$RENDER" -o nowhere/a.png scenes/a.rscene
  [[ "$stderr" == "rscene-render: error: nowhere/a.png: cannot create a file in 'nowhere'"* ]]
  [ ! -e nowhere ]
}

@test "batch: a stop signal ends the batch by it after the scene being drawn, saying how far it got" {
  mkdir many
  for i in $(seq 40); do scene "many/s$(printf %02d "$i").rscene" 1; done
  "$RENDER" --width 320 --height 200 -o 'thumbs/{stem}.png' many/ 2> err &
  pid=$!
  for _ in $(seq 200); do [ -f thumbs/s02.png ] && break; sleep 0.05; done
  kill -TERM "$pid"
  status=0
  wait "$pid" || status=$?
  [ "$status" -eq 143 ]
  grep -q "rscene-render: error: stopped by a signal after [0-9]* of 40 scenes; the finished scenes' outputs are written" err
  n=$(grep -o 'after [0-9]*' err | grep -o '[0-9]*')
  [ "$n" -lt 40 ]
  [ "$(ls thumbs | wc -l)" -eq "$n" ]
  for f in thumbs/*.png; do is_png "$f"; done
  [ -z "$(find . -name '.*tmp*')" ]
}

@test "batch: an output that is one of the input scenes is refused before anything is drawn" {
  cp scenes/a.rscene a.before
  run -2 --separate-stderr "$RENDER" -o 'scenes/{stem}.rscene' scenes/
  [ "$stderr" = "rscene-render: error: -o 'scenes/a.rscene' (of scenes/a.rscene) is the scene itself: it would be replaced by what -o writes; write it elsewhere" ]
  cmp a.before scenes/a.rscene
  # A hard link to a scene is that scene: refused as well.
  ln scenes/b.rscene b-link.rscene
  run -2 --separate-stderr "$RENDER" -o '{stem}-link.rscene' scenes/a.rscene scenes/b.rscene
  [ "$stderr" = "rscene-render: error: -o 'b-link.rscene' (of scenes/b.rscene) is the scene itself: it would be replaced by what -o writes; write it elsewhere" ]
  [ ! -e a-link.rscene ]
}

@test "batch: several scenes need -o with {stem} or {dir}; not --trajectory, --reference or standard input" {
  before=$(find . | LC_ALL=C sort)
  run -2 --separate-stderr "$RENDER" -o out.png scenes/a.rscene scenes/b.rscene
  [[ "$stderr" == *"-o: several scenes need an output pattern"*"{stem} or {dir}"* ]]
  run -2 --separate-stderr "$RENDER" -o 'out-{name}.png' scenes/
  [[ "$stderr" == *"{stem} or {dir}"* ]]
  run -2 --separate-stderr "$RENDER" scenes/
  [[ "$stderr" == *"{stem} or {dir}"* ]]
  run -2 --separate-stderr "$RENDER" --reference ref.png -o '{stem}.png' scenes/
  [[ "$stderr" == *"--reference belongs to one scene"* ]]
  run -2 --separate-stderr "$RENDER" -o '{stem}.png' scenes/a.rscene - < scenes/b.rscene
  [[ "$stderr" == *"standard input cannot be one of several scenes"* ]]
  [ "$before" = "$(find . | LC_ALL=C sort)" ]
  # One scene may use {stem} too.
  run -0 "$RENDER" -o '{stem}-one.png' scenes/a.rscene
  is_png a-one.png
}

@test "batch: a project with -o naming scenes is all of its scenes" {
  mkdir -p proj/scenes
  printf 'raisim_engine2_project 1\nname P\nscene_directory scenes\ndefault_scene scenes/a.rscene\n' > proj/raisim_engine2_project
  scene proj/scenes/a.rscene 1
  scene proj/scenes/b.rscene 0
  run -0 --separate-stderr "$RENDER" -o 'thumbs/{stem}.png' proj
  is_png thumbs/a.png
  is_png thumbs/b.png
  [[ "$stderr" == *"2 scenes: 2 rendered"* ]]
  # Without scene fields, a project alone is its default scene (as before).
  run -0 "$RENDER" -o default.png proj
  cmp default.png thumbs/a.png
}

@test "batch: memory stays bounded over a few hundred scenes" {
  mkdir many
  for i in $(seq 1 300); do cp scenes/a.rscene "many/s$i.rscene"; done
  /usr/bin/time -f '%M' -o rss10 "$RENDER" -o 'o10/{stem}.png' many/s1.rscene many/s2.rscene many/s3.rscene \
    many/s4.rscene many/s5.rscene many/s6.rscene many/s7.rscene many/s8.rscene many/s9.rscene many/s10.rscene 2> /dev/null
  /usr/bin/time -f '%M' -o rss300 "$RENDER" -o 'o300/{stem}.png' many/ 2> /dev/null
  [ "$(ls o300 | wc -l)" -eq 300 ]
  # Peak RSS (KiB) of 300 scenes within 20 MiB of 10 scenes'.
  echo "rss 10: $(tail -1 rss10) KiB, 300: $(tail -1 rss300) KiB"
  [ "$(tail -1 rss300)" -le $(($(tail -1 rss10) + 20480)) ]
}

@test "batch: an output a single run would refuse stops the batch before anything is drawn" {
  mkdir thumbs
  echo y > thumbs/b.png
  ln thumbs/b.png thumbs/other
  run -2 --separate-stderr "$RENDER" --width 32 --height 20 -o 'thumbs/{stem}.png' scenes/a.rscene scenes/b.rscene
  [[ "$stderr" == "rscene-render: error: thumbs/b.png: has 2 hard links"* ]]
  [ ! -e thumbs/a.png ]
  [ "$(cat thumbs/b.png)" = y ]
}
