#!/usr/bin/env bats
# End-to-end tests of rscene-render on the CPU backend: every flag, exit
# statuses, exact messages for bad input, and baseline comparison.

load helpers
RENDER="$BIN/rscene-render"

setup() {
  needs_tools rscene-render
  in_workdir
}

@test "--help lists every flag" {
  run "$RENDER" --help
  [ "$status" -eq 0 ]
  for f in --output --width --height --samples --max-pixels --max-instances --max-texture-pixels \
           --transparent --no-post --backend --camera --all-cameras --trajectory --every --stdin-filename \
           --base-dir --allow-missing-assets --reference --threshold --fail-pixels --pixel-threshold --diff-output \
           --camera-position --look-at --fov --verbose --version; do
    [[ "$output" == *"$f"* ]] || { echo "missing $f"; return 1; }
  done
}

@test "--version" {
  run "$RENDER" --version
  [ "$status" -eq 0 ]
  [[ "$output" == "rscene-render "* ]]
}

@test "renders the camera record's size to a file" {
  run "$RENDER" "$DATA/render_mesh.rscene" -o out.png
  [ "$status" -eq 0 ]
  [ -z "$output" ]
  is_png out.png
  [ "$(png_size out.png)" = "64x48" ]
}

@test "--width/--height/--samples/--camera auto" {
  run "$RENDER" "$DATA/render_minimal.rscene" --camera auto --width 40 --height 30 --samples 1 -o out.png
  [ "$status" -eq 0 ]
  [ "$(png_size out.png)" = "40x30" ]
}

@test "-o - writes the PNG to standard output, stdin in" {
  "$RENDER" --width 32 --height 16 -o - < "$DATA/render_minimal.rscene" > out.png
  is_png out.png
  [ "$(png_size out.png)" = "32x16" ]
}

@test "same input, same bytes" {
  "$RENDER" "$DATA/render_minimal.rscene" --camera auto --width 64 --height 36 -o a.png
  "$RENDER" "$DATA/render_minimal.rscene" --camera auto --width 64 --height 36 -o b.png
  cmp a.png b.png
}

@test "--transparent leaves alpha 0 outside geometry" {
  "$RENDER" "$DATA/render_mesh.rscene" --transparent -o out.png
  # Colour type 6 (RGBA) and a baseline made from it compares equal to itself.
  [ "$(od -An -tu1 -j25 -N1 out.png | tr -d ' ')" = "6" ]
  run "$RENDER" "$DATA/render_mesh.rscene" --reference out.png --threshold 0
  [ "$status" -eq 1 ]   # the opaque render differs from the transparent one
}

@test "--backend cpu --verbose names the renderer and timings" {
  run --separate-stderr "$RENDER" "$DATA/render_mesh.rscene" --backend cpu -v -o out.png
  [ "$status" -eq 0 ]
  [[ "$stderr" == *"rscene-render: backend cpu via EGL"* ]]
  [[ "$stderr" == *"renderer "* ]]
  [[ "$stderr" == *"start-up "*"drawing "*"png encoding "* ]]
  # The split (issue 13): every part in the order of the work, each a number of seconds.
  [[ "$stderr" =~ start-up\ [0-9.]+\ s,\ scene\ build\ [0-9.]+\ s,\ upload\ [0-9.]+\ s,\ shadow\ passes\ [0-9.]+\ s,\ drawing\ [0-9.]+\ s,\ post-processing\ [0-9.]+\ s,\ png\ encoding\ [0-9.]+\ s ]]
  [[ "$stderr" == *"start-up "*"drawing "*"post-processing "*"png encoding "* ]]
}

@test "post-processing: the scene's bloom, SSAO and FXAA change the picture; --no-post draws it without them" {
  sed 's/ bloomIntensity=[^ ]*//; s/ fxaa=true//; s/ ssao=true//' "$DATA/render_post.rscene" > plain.rscene
  ! cmp -s "$DATA/render_post.rscene" plain.rscene
  run -0 "$RENDER" plain.rscene -o plain.png
  run -0 "$RENDER" "$DATA/render_post.rscene" --no-post -o nopost.png
  cmp plain.png nopost.png
  run -0 --separate-stderr "$RENDER" "$DATA/render_post.rscene" -v -o post.png
  [[ "$stderr" =~ post-processing\ [0-9.]+\ s ]]
  # The glow around the lamp, the darker contact under the crate: more than
  # a tenth of the pixels change by more than 16/255.
  run -1 "$RENDER" "$DATA/render_post.rscene" --reference plain.png --threshold 0.1
}

@test "--backend rejects other names" {
  run "$RENDER" "$DATA/render_mesh.rscene" --backend vulkan -o out.png
  [ "$status" -eq 2 ]
}

@test "--camera by path and id; unknown camera is exit 2" {
  run "$RENDER" "$DATA/render_mesh.rscene" --camera /World/Cam -o a.png
  [ "$status" -eq 0 ]
  run "$RENDER" "$DATA/render_mesh.rscene" --camera cam_main -o b.png
  [ "$status" -eq 0 ]
  cmp a.png b.png
  run "$RENDER" "$DATA/render_mesh.rscene" --camera /World/Nope -o c.png
  [ "$status" -eq 2 ]
  [ "$output" = "rscene-render: error: no camera or camera-like sensor with path or id '/World/Nope'; the views of the scene: /World/Cam" ]
  [ ! -e c.png ]
  run -2 "$RENDER" "$DATA/render_mesh.rscene" --camera cam_mian -o c.png
  [ "$output" = "rscene-render: error: no camera or camera-like sensor with path or id 'cam_mian'; did you mean 'cam_main'?" ]
}

@test "missing mesh: exit 2 naming the resolved path; --allow-missing-assets draws a placeholder" {
  cp "$DATA/render_mesh.rscene" scene.rscene
  run "$RENDER" scene.rscene -o out.png
  [ "$status" -eq 2 ]
  [[ "${lines[0]}" == "scene.rscene:5:"*": error: mesh file 'render_assets/crate.obj' does not exist [RS5001]" ]]
  # At the field, in the words of rscene-sim and rscene-validate --check-files.
  col=$(awk 'NR == 5 { print index($0, "render_assets/crate.obj") }' scene.rscene)
  [[ "${lines[0]}" == "scene.rscene:5:$col: error: "* ]]
  [ ! -e out.png ]
  run "$RENDER" scene.rscene --allow-missing-assets -o out.png
  [ "$status" -eq 0 ]
  [[ "${lines[0]}" == "scene.rscene:5:$col: warning: mesh file 'render_assets/crate.obj' does not exist [RS5001]" ]]
  is_png out.png
}

@test "--base-dir and --stdin-filename resolve assets" {
  run "$RENDER" --base-dir "$DATA" -o a.png < "$DATA/render_mesh.rscene"
  [ "$status" -eq 0 ]
  run "$RENDER" --stdin-filename "$DATA/render_mesh.rscene" -o b.png < "$DATA/render_mesh.rscene"
  [ "$status" -eq 0 ]
  cmp a.png b.png
}

@test "every record kind is drawn: no skipped-records warning" {
  # local_fog and reflection_probe (issue 13) were the last kinds listed.
  run "$RENDER" "$DATA/render_skipped.rscene" -o out.png
  [ "$status" -eq 0 ]
  [ "$output" = "" ]
  { cat "$DATA/render_skipped.rscene"; echo "reflection_probe /World/Probe 0 0 1 2"; } > probe.rscene
  run "$RENDER" probe.rscene -o out.png
  [ "$status" -eq 0 ]
  [ "$output" = "" ]
}

@test "decals, fog spheres, irradiance volumes and height fog are drawn" {
  { sed 's/^raisim_engine_scene 1$/&\nenvironment 0 0 0 0.2 0.2 0.2 0 true true 10 - backgroundMode=plain_color heightFogEnabled=true heightFogDensity=0.1/' "$DATA/render_skipped.rscene"
    echo "projected_decal /World/Decal 4.5 0 0 0 0.7071 0 0.7071 1 1 1 halfExtents=1,1,1 color=1,0,0,1"
    echo "irradiance_volume /World/Light 5 0 0 1 0 0 0 1 1 1 halfExtents=2,2,2 color=0,1,0,1"; } > fx.rscene
  run "$RENDER" fx.rscene -o fx.png
  [ "$status" -eq 0 ]
  [ "$output" = "" ]
  is_png fx.png
  grep -v -e projected_decal -e irradiance_volume -e local_fog -e heightFog fx.rscene > plain.rscene
  run "$RENDER" plain.rscene -o plain.png
  [ "$status" -eq 0 ]
  ! cmp -s fx.png plain.png
}

@test "missing decal texture: exit 2 at the field; --allow-missing-assets draws the decal's color" {
  { cat "$DATA/render_skipped.rscene"
    echo "projected_decal /World/Decal 4.5 0 0 1 0 0 0 1 1 1 halfExtents=1,1,1 normalTexture=tex/bumps.png"; } > scene.rscene
  run -2 "$RENDER" scene.rscene -o out.png
  col=$(awk 'NR == 7 { print index($0, "tex/bumps.png") }' scene.rscene)
  [ "${lines[0]}" = "scene.rscene:7:$col: error: decal texture file 'tex/bumps.png' does not exist [RS5001]" ]
  [ ! -e out.png ]
  run "$RENDER" scene.rscene --allow-missing-assets -o out.png
  [ "$status" -eq 0 ]
  [ "${lines[0]}" = "scene.rscene:7:$col: warning: decal texture file 'tex/bumps.png' does not exist [RS5001]" ]
  is_png out.png
}

@test "reflection probes are drawn, not skipped; past 8 the rest warn RS9061" {
  {
    echo "raisim_engine_scene 1"
    echo "camera /World/Cam 0 0 1 1 0 0 0 60 0.05 100 64 48 rgb true id=cam_main"
    echo "material chrome 1 1 1 1 1 0.05 0 0 0 0 false - - - - - - id=chrome"
    echo "object /World/Ball sphere 3 0 1 1 0 0 0 0.5 0.5 0.5 1 1 1 default chrome false true false - static true 1 18446744073709551615"
    echo "reflection_probe /World/Probe 2 0 1 4 cubemapSize=16 prefilteredResolution=16"
  } > probe.rscene
  run "$RENDER" probe.rscene -o out.png
  [ "$status" -eq 0 ]
  [ "$output" = "" ]
  is_png out.png
  for i in 1 2 3 4 5 6 7 8; do echo "reflection_probe /World/P$i 2 0 1 4 cubemapSize=8 prefilteredResolution=8"; done >> probe.rscene
  run "$RENDER" probe.rscene -o out.png
  [ "$status" -eq 0 ]
  [ "${lines[0]}" = "probe.rscene:13:1: warning: 9 reflection probes; only the first 8 are drawn [RS9061]" ]
  [ "${lines[1]}" = "  reflection_probe /World/P8 2 0 1 4 cubemapSize=8 prefilteredResolution=8" ]
}

@test "a camera that sees nothing warns" {
  sed 's#^camera /World/Cam 0 0 0 1 0 0 0#camera /World/Cam 0 0 0 0 0 0 1#' "$DATA/render_skipped.rscene" |
    grep -v -e sensor -e local_fog > back.rscene
  run "$RENDER" back.rscene -o out.png
  [ "$status" -eq 0 ]
  [ "$output" = "rscene-render: warning: camera '/World/Cam' sees none of the scene's geometry" ]
}

@test "--reference: missing baseline is written and exits 1, then matches" {
  run "$RENDER" "$DATA/render_mesh.rscene" --reference base.png
  [ "$status" -eq 1 ]
  [ "$output" = "rscene-render: warning: reference 'base.png' did not exist; wrote this render there" ]
  is_png base.png
  run "$RENDER" "$DATA/render_mesh.rscene" --reference base.png --threshold 0
  [ "$status" -eq 0 ]
  [[ "$output" == "difference 0.000000 (pixels off by more than 16/255), threshold 0, mean error 0.000000, max 0/255; 0 pixel(s) off by more than 32/255, fail pixels 50" ]]
}

@test "--reference/--threshold/--diff-output: a different render exits 1 and writes the diff" {
  "$RENDER" "$DATA/render_minimal.rscene" --camera auto --width 64 --height 36 -o base.png
  run "$RENDER" "$DATA/render_minimal.rscene" --width 64 --height 36 --reference base.png --threshold 0.001 \
      --diff-output diff.png
  [ "$status" -eq 1 ]
  [[ "$output" == "difference 0."* ]]
  is_png diff.png
  # --threshold 1 accepts any fraction; the local measure still finds the
  # strongly changed pixels, unless --fail-pixels allows them all.
  run "$RENDER" "$DATA/render_minimal.rscene" --width 64 --height 36 --reference base.png --threshold 1
  [ "$status" -eq 1 ]
  run "$RENDER" "$DATA/render_minimal.rscene" --width 64 --height 36 --reference base.png --threshold 1 \
      --fail-pixels 2304
  [ "$status" -eq 0 ]
}

# Issue 27: a crate moved 10 cm changes under 1 % of the image, which the
# fraction (--threshold) forgives; the local measure (--fail-pixels,
# --pixel-threshold) finds it, and an identical render passes both.
@test "--fail-pixels/--pixel-threshold: a crate moved 10 cm fails, the same scene passes" {
  sed 's|^object /World/Props/CrateC box 0.35 |object /World/Props/CrateC box 0.45 |' "$ROOT/examples/warehouse_crates.rscene" > moved.rscene
  ! cmp -s moved.rscene "$ROOT/examples/warehouse_crates.rscene"
  "$RENDER" "$ROOT/examples/warehouse_crates.rscene" --width 480 --height 270 -o base.png
  run "$RENDER" "$ROOT/examples/warehouse_crates.rscene" --width 480 --height 270 --reference base.png
  [ "$status" -eq 0 ]
  [[ "$output" == *"; 0 pixel(s) off by more than 32/255, fail pixels 50" ]]
  # The fraction alone passes the moved crate ...
  run "$RENDER" moved.rscene --width 480 --height 270 --reference base.png --fail-pixels 100000
  [ "$status" -eq 0 ]
  [[ "$output" =~ ^difference\ 0\.00[0-9]+\ .*threshold\ 0\.01 ]]
  # ... the local measure does not, with its defaults.
  run "$RENDER" moved.rscene --width 480 --height 270 --reference base.png --diff-output diff.png
  [ "$status" -eq 1 ]
  n=$(sed -E 's/.*; ([0-9]+) pixel\(s\) off by more than 32\/255.*/\1/' <<< "$output")
  [ "$n" -gt 50 ]
  is_png diff.png
  # A higher --pixel-threshold counts fewer pixels.
  run "$RENDER" moved.rscene --width 480 --height 270 --reference base.png --pixel-threshold 255
  [ "$status" -eq 0 ]
  [[ "$output" == *"; 0 pixel(s) off by more than 255/255, fail pixels 50" ]]
}

@test "--fail-pixels and --pixel-threshold need --reference and take whole numbers in range" {
  run -2 --separate-stderr "$RENDER" "$DATA/render_mesh.rscene" -o x.png --fail-pixels 3
  [ "$stderr" = "rscene-render: error: --fail-pixels needs --reference" ]
  run -2 --separate-stderr "$RENDER" "$DATA/render_mesh.rscene" -o x.png --pixel-threshold 3
  [ "$stderr" = "rscene-render: error: --pixel-threshold needs --reference" ]
  for bad in "--pixel-threshold 256" "--pixel-threshold -1" "--fail-pixels -1" "--fail-pixels nan" "--pixel-threshold 1.5"; do
    run -2 "$RENDER" "$DATA/render_mesh.rscene" --reference r.png $bad
  done
  [ ! -e x.png ] && [ ! -e r.png ]
}

# Issue 27: a camera placed by two points instead of a quaternion.  Seen
# from (-5,0,1) towards (0,0,1) it is the camera record with the identity
# orientation at (-5,0,1): the same image, pixel for pixel.
@test "--camera-position/--look-at/--fov: the image of the equivalent camera record" {
  printf '%s\n' 'raisim_engine_scene 1' \
    'material red 0.8 0.1 0.1 1 0 0.6 0 0 0 0 false - - - - - - id=red' \
    'object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default engine_default false true true - static true 1 18446744073709551615' \
    'object /World/Box box 0 0 1 1 0 0 0 0.4 0.4 0.4 0.5 1 1 default red false true false - static true 1 18446744073709551615' \
    'camera /World/Cam -5 0 1 1 0 0 0 40 0.05 1000 96 64 rgb true id=cam' > s.rscene
  "$RENDER" s.rscene --camera /World/Cam -o record.png
  run "$RENDER" s.rscene --camera-position -5,0,1 --look-at 0,0,1 --fov 40 --width 96 --height 64 \
      --reference record.png --fail-pixels 0 --pixel-threshold 0 --threshold 0
  [ "$status" -eq 0 ]
  # An -o pattern names the view look-at.
  run "$RENDER" s.rscene --camera-position -5,0,1 --look-at 0,0,1 --width 32 --height 24 -o '{name}.png'
  [ "$status" -eq 0 ]
  [ "$(png_size look-at.png)" = "32x24" ]
}

@test "--camera-position/--look-at: refused with --camera or --all-cameras, alone, equal, not finite, or not three numbers" {
  s="$DATA/render_mesh.rscene"
  run -2 --separate-stderr "$RENDER" "$s" -o x.png --camera-position 1,2,3 --look-at 0,0,0 --camera /World/Cam
  [ "$stderr" = "rscene-render: error: --camera-position/--look-at place a camera of their own: not with --camera" ]
  run -2 --separate-stderr "$RENDER" "$s" -o '{name}.png' --camera-position 1,2,3 --look-at 0,0,0 --all-cameras
  [ "$stderr" = "rscene-render: error: --camera-position/--look-at place a camera of their own: not with --all-cameras" ]
  run -2 --separate-stderr "$RENDER" "$s" -o x.png --look-at 0,0,0
  [ "$stderr" = "rscene-render: error: --look-at needs --camera-position X,Y,Z and --look-at X,Y,Z together" ]
  run -2 --separate-stderr "$RENDER" "$s" -o x.png --camera-position 0,0,0
  [ "$stderr" = "rscene-render: error: --camera-position needs --camera-position X,Y,Z and --look-at X,Y,Z together" ]
  run -2 --separate-stderr "$RENDER" "$s" -o x.png --fov 30
  [ "$stderr" = "rscene-render: error: --fov needs --camera-position X,Y,Z and --look-at X,Y,Z together" ]
  run -2 --separate-stderr "$RENDER" "$s" -o x.png --camera-position 1,2,3 --look-at 1,2,3
  [ "$stderr" = "rscene-render: error: --camera-position/--look-at/--fov: the camera position and the look-at point are the same point" ]
  run -2 --separate-stderr "$RENDER" "$s" -o x.png --camera-position nan,2,3 --look-at 0,0,0
  [ "$stderr" = "rscene-render: error: --camera-position/--look-at/--fov: the camera position is not a finite point" ]
  run -2 --separate-stderr "$RENDER" "$s" -o x.png --camera-position 1,2,3 --look-at 0,inf,0
  [ "$stderr" = "rscene-render: error: --camera-position/--look-at/--fov: the look-at point is not a finite point" ]
  run -2 --separate-stderr "$RENDER" "$s" -o x.png --camera-position 1,2,3 --look-at 0,0,0 --fov 180
  [ "$stderr" = "rscene-render: error: --camera-position/--look-at/--fov: the field of view must be 1 to 175 degrees" ]
  for bad in 1,2 1,2,3,4 1,,3 a,b,c "1, 2,3" ""; do
    run -2 --separate-stderr "$RENDER" "$s" -o x.png --camera-position "$bad" --look-at 0,0,0
    [ "$stderr" = "rscene-render: error: --camera-position '$bad': give three numbers X,Y,Z (metres, +z up)" ] || { echo "$bad: $stderr"; false; }
  done
  [ ! -e x.png ]
}

@test "--reference with another size exits 1" {
  "$RENDER" "$DATA/render_mesh.rscene" --width 10 --height 10 -o base.png
  run "$RENDER" "$DATA/render_mesh.rscene" --reference base.png
  [ "$status" -eq 1 ]
  [ "$output" = "size differs: render 64x48, reference 10x10" ]
}

@test "a reference that is not a PNG is exit 2" {
  echo hello > base.png
  run "$RENDER" "$DATA/render_mesh.rscene" --reference base.png
  [ "$status" -eq 2 ]
  [ "$output" = "rscene-render: error: cannot read reference 'base.png': not a png file" ]
}

@test "parse errors are exit 2 in the shared format and write nothing" {
  printf 'raisim_engine_scene 7\n' > bad.rscene
  run "$RENDER" bad.rscene -o out.png
  [ "$status" -eq 2 ]
  [[ "${lines[0]}" == "bad.rscene:1:"*"error: "*"[RS"* ]]
  [ ! -e out.png ]
}

@test "nothing to write is a usage error" {
  run "$RENDER" "$DATA/render_mesh.rscene"
  [ "$status" -eq 2 ]
  [ "$output" = "rscene-render: error: nothing to write: '/World/Cam' has no outputPath; give -o FILE (-o - for standard output), --reference FILE or -o PATTERN such as '{name}.{kind}.png'" ]
  run "$RENDER" "$DATA/render_mesh.rscene" -o x.png --diff-output d.png
  [ "$status" -eq 2 ]
  [ "$output" = "rscene-render: error: --diff-output needs --reference" ]
}

@test "bad numbers are usage errors" {
  run "$RENDER" "$DATA/render_mesh.rscene" -o x.png --width 0
  [ "$status" -eq 2 ]
  run "$RENDER" "$DATA/render_mesh.rscene" -o x.png --samples 0
  [ "$status" -eq 2 ]
  run "$RENDER" "$DATA/render_mesh.rscene" --reference x.png --threshold 2
  [ "$status" -eq 2 ]
  [ ! -e x.png ]
}

@test "real corpus scenes render with --allow-missing-assets" {
  needs_shared corpus/rayrai_warehouse.rscene
  run "$RENDER" "$CORPUS/rayrai_warehouse.rscene" --allow-missing-assets --width 160 --height 100 -o out.png
  [ "$status" -eq 0 ]
  is_png out.png
}

# --- Resource limits (README, "Resource limits: rscene-render") ---------
# Each reproducer of issue 10 item 5 runs under a memory and time bound
# (bounded, helpers.bash; GL start-up alone needs ~1 GB of address space)
# and asserts the documented outcome.

BOX='object /World/B box 3 0 0 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - static true 1 18446744073709551615'

@test "limits: an 8192x8192 terrain without heights renders in bounded memory" {
  printf 'raisim_engine_scene 2\nterrain_region /World/T 8192 8192 100 100 0 0 0\n' > t.rscene
  run bounded 2000000 60 "$RENDER" t.rscene --width 64 --height 48 -o t.png
  [ "$status" -eq 0 ]
  is_png t.png
}

@test "limits: --max-instances refuses 2 M instances at the record, before allocating them" {
  { printf 'raisim_engine_scene 2\n'
    awk 'BEGIN { printf "instanced_visual /World/I box size=0.1,0.1,0.1 instances=0,0,0,1,0,0,0,1,1,1"
                 for (i = 1; i < 2000000; ++i) printf ";%d,0,0,1,0,0,0,1,1,1", i % 1000; print "" }'; } > i.rscene
  run -2 --separate-stderr bounded 2000000 60 "$RENDER" i.rscene --width 64 --height 48 -o i.png
  [ "${stderr_lines[0]}" = "i.rscene:2:1: error: instanced_visual draws 2000000 instances, more than the 1000000 left of --max-instances 1000000 [RS9014]" ]
  [ ! -e i.png ]
}

@test "limits: maxRenderedInstances and renderedInstanceStride are honoured; --max-instances raises or lowers the cap" {
  { printf 'raisim_engine_scene 2\ncamera /World/Cam -8 0 1 1 0 0 0 60 0.05 100 64 48 rgb true id=cam\n'
    awk -v extra="$1" 'BEGIN { printf "instanced_visual /World/I box size=0.1,0.1,0.1 EXTRA instances=0,0,0,1,0,0,0,1,1,1"
                 for (i = 1; i < 100; ++i) printf ";0,%d,0,1,0,0,0,1,1,1", i; print "" }'; } > base.rscene
  sed 's/EXTRA//' base.rscene > all.rscene
  run -2 --separate-stderr "$RENDER" all.rscene --max-instances 50 -o x.png
  [ "${stderr_lines[0]}" = "all.rscene:3:1: error: instanced_visual draws 100 instances, more than the 50 left of --max-instances 50 [RS9014]" ]
  [ "${stderr_lines[3]}" = "  hint: set maxRenderedInstances or renderedInstanceStride on the record, or raise --max-instances" ]
  run "$RENDER" all.rscene --max-instances 100 -o x.png
  [ "$status" -eq 0 ]
  sed 's/EXTRA/maxRenderedInstances=50/' base.rscene > max.rscene
  run "$RENDER" max.rscene --max-instances 50 -o x.png
  [ "$status" -eq 0 ]
  sed 's/EXTRA/renderedInstanceStride=2/' base.rscene > stride.rscene
  run "$RENDER" stride.rscene --max-instances 50 -o x.png
  [ "$status" -eq 0 ]
  sed 's/EXTRA/renderedInstanceStride=1/' base.rscene > one.rscene
  run "$RENDER" one.rscene --max-instances 50 -o x.png
  [ "$status" -eq 2 ]
}

@test "limits: --width 16384 --height 16384 is refused before any framebuffer; --max-pixels raises the cap" {
  printf 'raisim_engine_scene 2\n%s\n' "$BOX" > b.rscene
  run -2 --separate-stderr bounded 2000000 30 "$RENDER" b.rscene --width 16384 --height 16384 -o b.png
  [ "$stderr" = "rscene-render: error: --width/--height: 16384x16384 is 268435456 pixels, more than --max-pixels 16777216" ]
  [ ! -e b.png ]
  run -2 --separate-stderr "$RENDER" b.rscene --width 64 --height 48 --max-pixels 3000 -o b.png
  [ "$stderr" = "rscene-render: error: --width/--height: 64x48 is 3072 pixels, more than --max-pixels 3000" ]
  run "$RENDER" b.rscene --width 64 --height 48 --max-pixels 3072 -o b.png
  [ "$status" -eq 0 ]
  [ "$(png_size b.png)" = "64x48" ]
  run "$RENDER" b.rscene --max-pixels 0 -o b.png
  [ "$status" -eq 2 ]
}

@test "limits: a camera asking for too many pixels is an error at its width field" {
  printf 'raisim_engine_scene 2\ncamera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 8192 8192 rgb true id=cam\n%s\n' "$BOX" > c.rscene
  run -2 --separate-stderr "$RENDER" c.rscene -o c.png
  [ "${stderr_lines[0]}" = "c.rscene:2:45: error: camera image 8192x8192 is 67108864 pixels, more than --max-pixels 16777216 [RS9013]" ]
  [ ! -e c.png ]
  # --width/--height override the camera's size.
  run "$RENDER" c.rscene --width 32 --height 32 -o c.png
  [ "$status" -eq 0 ]
}

@test "limits: a camera width of 4294967297 is RS2003 at the field, not 1 pixel" {
  printf 'raisim_engine_scene 2\ncamera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 4294967297 48 rgb true id=cam\n%s\n' "$BOX" > w.rscene
  run -2 --separate-stderr "$RENDER" w.rscene -o w.png
  [ "${stderr_lines[0]}" = "w.rscene:2:45: error: expected a 32-bit integer, found '4294967297' [RS2003]" ]  # validate's words
  [ ! -e w.png ]
}

@test "limits: a texture or HDR that is /dev/zero or a FIFO is not read (RS5001 as validate says; HDR: the sky)" {
  mkfifo pipe.png
  for tex in /dev/zero "$PWD/pipe.png"; do
    rm -f t.png
    printf 'raisim_engine_scene 2\nmaterial m 1 1 1 1 0 0.5 0 0 0 0 false %s - - - - - id=m\n%s\n' "$tex" "${BOX/engine_default/m}" > t.rscene
    run --separate-stderr bounded 2000000 20 "$RENDER" t.rscene --width 32 --height 32 -o t.png
    [ "$status" -eq 2 ]
    [[ "${stderr_lines[0]}" == "t.rscene:2:40: error: texture file '$tex' is a "*", not a regular file [RS5001]" ]]
    [ ! -e t.png ]
    run -1 --separate-stderr "$RSCENE_BIN/rscene-validate" --check-files t.rscene
    [[ "${lines[0]}" == "t.rscene:2:40: error: "*"[RS5001]" ]]
    run --separate-stderr bounded 2000000 20 "$RENDER" t.rscene --allow-missing-assets --width 32 --height 32 -o t.png
    [ "$status" -eq 0 ]
    [[ "${stderr_lines[0]}" == "t.rscene:2:40: warning: texture file '$tex' is a "*", not a regular file [RS5001]" ]]
    printf 'raisim_engine_scene 2\nenvironment 0.2 0.2 0.2 0.2 0.2 0.2 0 true true 10 %s backgroundMode=hdr\n%s\n' "$tex" "$BOX" > h.rscene
    run --separate-stderr bounded 2000000 20 "$RENDER" h.rscene --width 32 --height 32 -o h.png
    [ "$status" -eq 0 ]
    [ "${stderr_lines[0]}" = "h.rscene:2:1: warning: hdr background $tex: not a regular file; drawing the procedural sky [RS9003]" ]
  done
}

@test "limits: a 261 KB PNG declaring 16384x16384 is not decoded; --max-texture-pixels sets the cap" {
  command -v python3 >/dev/null || skip "no python3 to write the PNG"
  python3 - <<'PY'
import struct, zlib
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
w = h = 16384
with open('big.png', 'wb') as f:
    f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 0, 0, 0, 0))
            + chunk(b'IDAT', zlib.compress(b'\0' * ((w + 1) * h), 9)) + chunk(b'IEND', b''))
PY
  printf 'raisim_engine_scene 2\nmaterial m 1 1 1 1 0 0.5 0 0 0 0 false big.png - - - - - id=m\n%s\n' "${BOX/engine_default/m}" > p.rscene
  run --separate-stderr bounded 2000000 30 "$RENDER" p.rscene --width 32 --height 32 -o p.png
  [ "$status" -eq 0 ]
  [[ "${stderr_lines[0]}" == "p.rscene:2:1: warning: texture "*"big.png is not drawn: png image too large: 16384x16384 pixels (limit 67108864) [RS9002]" ]]
  run --separate-stderr "$RENDER" p.rscene --width 32 --height 32 --max-texture-pixels 1000 -o p.png
  [[ "${stderr_lines[0]}" == *"(limit 1000) [RS9002]" ]]
  run "$RENDER" p.rscene --max-texture-pixels 0 -o p.png
  [ "$status" -eq 2 ]
}

@test "--threshold nan (or 2) is a usage error: NaN must not make every image pass" {
  for t in nan NaN 2 -0.5; do
    run -2 --separate-stderr "$RENDER" "$DATA/render_mesh.rscene" --reference base.png --threshold "$t" -o out.png
    [[ $stderr == *"--threshold: expected a fraction from 0 to 1 (e.g. 0.01), not '$t'"* ]]
  done
}

# A two-link arm fixed to the world: a red 0.6 m box at the base and a
# green 0.4 m box 1 m up the arm, which turns about x.  $1 replaces the
# green box's geometry.
write_arm() {
  local arm=${1:-'<box size="0.4 0.4 0.4"/>'}
  cat > arm.urdf <<URDF
<robot name="arm">
  <material name="red"><color rgba="0.9 0.05 0.05 1"/></material>
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base">
    <visual><geometry><box size="0.6 0.6 0.6"/></geometry><material name="red"/></visual>
  </link>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><axis xyz="1 0 0"/>
    <limit lower="-3" upper="3" effort="10" velocity="1"/>
  </joint>
  <link name="arm">
    <visual>
      <origin xyz="0 0 1"/>
      <geometry>$arm</geometry>
      <material name="green"><color rgba="0.05 0.9 0.05 1"/></material>
    </visual>
  </link>
</robot>
URDF
}

# The arm 5 m in front of a camera looking along +x, on black.  $1: keys
# of the articulated record; $2: its visible flag; $3: its group's.
write_cell() {
  cat > cell.rscene <<SCENE
raisim_engine_scene 2
environment 0 0 0 0.3 0.3 0.3 0 true true 10 - backgroundMode=plain_color colorMode=linear
articulated_resource arm_res Arm arm.urdf
group /World id=world parentId=- visible=${3:-true}
light /World/Sun 1 0 0 3 type=directional
camera /World/Cam 0 0 0 1 0 0 0 60 0.05 100 64 64 rgb true id=cam
articulated /World/Arm arm_res 5 0 0 1 0 0 0 ${2:-true} true id=arm parentGroupId=world ${1:-}
SCENE
}

@test "robots: an articulated record is drawn; visible=false and a hidden group are not" {
  write_arm
  write_cell
  grep -v '^articulated ' cell.rscene > none.rscene
  "$RENDER" none.rscene -o none.png
  run --separate-stderr "$RENDER" cell.rscene --reference none.png --threshold 0.02
  [ "$status" -eq 1 ]  # the two boxes cover more than 2% of the image
  [ -z "$stderr" ]
  write_cell "" false
  run "$RENDER" cell.rscene --reference none.png --threshold 0
  [ "$status" -eq 0 ]
  write_cell "" true false
  run "$RENDER" cell.rscene --reference none.png --threshold 0
  [ "$status" -eq 0 ]
}

@test "robots: generalizedCoordinate and scale= change the picture; the same state gives the same bytes" {
  write_arm
  write_cell
  "$RENDER" cell.rscene -o rest.png
  "$RENDER" cell.rscene -o again.png
  cmp rest.png again.png
  write_cell "generalizedCoordinate=1.5707963"
  run "$RENDER" cell.rscene --reference rest.png --threshold 0.01
  [ "$status" -eq 1 ]
  write_cell "generalizedCoordinate=0"
  run "$RENDER" cell.rscene --reference rest.png --threshold 0
  [ "$status" -eq 0 ]
  write_cell "scale=1.5,1.5,1.5"
  run "$RENDER" cell.rscene --reference rest.png --threshold 0.01
  [ "$status" -eq 1 ]
}

@test "robots: --camera auto frames a robot far from the origin" {
  write_arm
  write_cell
  sed -i 's/ 5 0 0 1 0 0 0 true/ 40 -30 6 1 0 0 0 true/' cell.rscene
  grep -v '^articulated ' cell.rscene > none.rscene
  "$RENDER" none.rscene --camera auto -o none.png
  run "$RENDER" cell.rscene --camera auto --reference none.png --threshold 0.05
  [ "$status" -eq 1 ]  # the framed arm fills more than 5% of the image
}

@test "robots: a visual mesh that is not found is the loader's warning (RS7031), as in validate; the rest is drawn" {
  write_arm
  write_cell
  "$RENDER" cell.rscene -o whole.png
  write_arm '<mesh filename="gone.dae"/>'
  run --separate-stderr "$RENDER" cell.rscene -o out.png
  [ "$status" -eq 0 ]
  [ "$stderr" = "arm.urdf:15: warning: visual mesh 'gone.dae' not found; the <visual> is skipped [RS7031]" ]
  run "$RENDER" cell.rscene --reference whole.png --threshold 0.001
  [ "$status" -eq 1 ]  # the green box is gone
  grep -v '^articulated ' cell.rscene > none.rscene
  run "$RENDER" none.rscene --reference out.png --threshold 0.001
  [ "$status" -eq 1 ]  # the red base is still there
}

@test "robots: a robot file that does not exist is an error; --allow-missing-assets leaves the robot out, as sim does" {
  write_cell
  run -2 --separate-stderr "$RENDER" cell.rscene -o out.png
  [ "${stderr_lines[0]}" = "cell.rscene:3:34: error: robot file 'arm.urdf' does not exist [RS5001]" ]
  [ ! -e out.png ]
  run -0 --separate-stderr "$RENDER" cell.rscene --allow-missing-assets -o out.png
  [[ ${stderr_lines[0]} == "cell.rscene:3:34: warning: robot file 'arm.urdf' does not exist; articulated system '"*"' is left out (--allow-missing-assets) [RS5001]" ]]
  is_png out.png
}

@test "robots: a coordinate of the wrong length is RS7040 at the field" {
  write_arm
  write_cell "generalizedCoordinate=0,0"
  run -2 --separate-stderr "$RENDER" cell.rscene -o out.png
  [[ "${stderr_lines[0]}" == "cell.rscene:7:"*": error: generalizedCoordinate has 2 numbers; the model 'arm' has 1 (joints only: fixed base) [RS7040]" ]]
}

@test "robots: ANYmal C from ../shared renders standing, with its meshes and textures" {
  needs_shared corpus/robots/anymal_c/urdf/anymal.urdf
  urdf="$CORPUS/robots/anymal_c/urdf/anymal.urdf"
  bash "$ROOT/bench/render/robots.sh" "$urdf" 1 > anymal.rscene
  # From 1.7 m front-right, 0.8 m up, looking at the robot.
  echo "camera /World/Cam 1.2 -1.2 0.8 0.37947 -0.11947 0.04949 0.91612 50 0.05 100 160 120 rgb true id=cam" >> anymal.rscene
  run --separate-stderr "$RENDER" anymal.rscene -v -o anymal.png
  [ "$status" -eq 0 ]
  [[ "$stderr" == *"1 robots"* ]]
  [[ "$stderr" != *"warning"* && "$stderr" != *"error"* ]]
  sed 's/ true true generalizedCoordinate/ false true generalizedCoordinate/' anymal.rscene > hidden.rscene
  run "$RENDER" hidden.rscene --reference anymal.png --threshold 0.1
  [ "$status" -eq 1 ]  # the robot covers more than a tenth of the picture
}

@test "robots: a pipe from rscene-sim loses the scene's folder; the error says how to give it back" {
  run -2 --separate-stderr bash -c "cd '$ROOT/examples' && '$RSCENE_BIN/rscene-sim' --steps 1 robot_cell.rscene 2>/dev/null | (cd '$BATS_TEST_TMPDIR' && '$RENDER' -o p.png)"
  [[ $stderr == *"<stdin>:"*": error: robot file 'robots/quadruped/quadruped.urdf' does not exist [RS5001]"* ]]
  [[ $stderr == *"hint: standard input has no folder, so relative paths resolve against the current one: name the scene with --stdin-filename PATH or give --base-dir DIR"* ]]
  run -0 --separate-stderr bash -c "cd '$ROOT/examples' && '$RSCENE_BIN/rscene-sim' --steps 1 robot_cell.rscene 2>/dev/null | '$RENDER' --width 64 --height 48 --stdin-filename robot_cell.rscene -o '$BATS_TEST_TMPDIR/p.png'"
  [ -s "$BATS_TEST_TMPDIR/p.png" ]
}

# Issue 13, geometry: foliage, wires, deformables and granular media are
# drawn (no longer listed as skipped), with their errors at the record.
geometry_scene() {
  cat <<SCENE
raisim_engine_scene 1
camera /World/Cam -6 0 2 0.98 0 0.17 0 60 0.05 100 96 64 rgb true id=cam
light /World/Sun 0.2 0.1 -1 3 type=directional
terrain_region /World/T 5 5 4 4 0 0 0 id=terrain
terrain_foliage_layer /World/T id=grass densityPerSquareMeter=50 seed=5 $1
object /World/A box 0 0 2 1 0 0 0 0.2 0.2 0.2 0.5 1 1 default engine_default false true false - static true 1 18446744073709551615 id=a
wire /World/W stiff a - 1 localPositionB=0,0,0
deformable /World/D cloth $DATA/render_assets/crate.obj 0 1 0.5 1 0 0 0 1 1 1
granular /World/S particles 0 -1 0 1 0 0 0 1 1 1 boxMax=0.4,0.4,0.2 radius=0.05 spacing=0.1 $2
SCENE
}

@test "geometry: foliage, wire, deformable and granular are drawn, not skipped" {
  geometry_scene > g.rscene
  run "$RENDER" g.rscene -o g.png
  [ "$status" -eq 0 ]
  [ "$output" = "" ]
  is_png g.png
  # Another seed scatters the grass elsewhere: another image.
  geometry_scene > a.rscene
  sed 's/seed=5/seed=6/' a.rscene > b.rscene
  "$RENDER" a.rscene -o a.png
  "$RENDER" b.rscene -o b.png
  cmp a.png g.png
  ! cmp -s a.png b.png
}

@test "geometry: granular beyond maxParticles is validate's RS7082 at the key, beyond --max-instances RS9070, exit 2" {
  geometry_scene "" "maxParticles=10" > g.rscene
  run -1 "$BIN/rscene-validate" g.rscene
  vline=$(grep -m1 'error:' <<<"$output")
  [[ "$vline" == *"[RS7082]" ]]
  run -2 --separate-stderr "$RENDER" g.rscene -o g.png
  [ "${stderr_lines[0]}" = "$vline" ]
  [[ "${stderr_lines[0]}" == "g.rscene:9:"*"error: granular /World/S has 32 particles, more than its maxParticles 10 [RS7082]" ]]
  [ ! -e g.png ]
  geometry_scene "maxRenderedInstances=1" > g.rscene
  run -2 --separate-stderr "$RENDER" g.rscene --max-instances 20 -o g.png
  [ "${stderr_lines[0]}" = "g.rscene:9:1: error: granular /World/S has 32 particles, more than the limit of 19 [RS9070]" ]
  run "$RENDER" g.rscene --max-instances 33 -o g.png
  [ "$status" -eq 0 ]
}

@test "geometry: a foliage primitive it does not know is drawn as blades with RS9072" {
  geometry_scene "primitive=fern" > g.rscene
  run "$RENDER" g.rscene -o g.png
  [ "$status" -eq 0 ]
  [ "${lines[0]}" = "g.rscene:5:1: warning: terrain_foliage_layer primitive 'fern' is drawn as grass_blade [RS9072]" ]
}

@test "forty shadowed point lights are all drawn, and -v splits out the shadow maps' time" {
  {
    echo "raisim_engine_scene 2"
    echo "camera /World/Cam 0 0 14 0.70710678 0 0.70710678 0 60 0.05 100 160 120 rgb true"
    echo "object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615"
    echo "object /World/Box box 0 0 0.5 1 0 0 0 1 1 1 1 1 1 default - false true false - static true 1 18446744073709551615"
    for i in $(seq 0 39); do
      echo "light /World/L$i 0 0 -1 2 type=point position=$((i % 8 - 4)),$((i / 8 - 2)),1.5 shadows=true"
    done
  } > lights.rscene
  run --separate-stderr "$RENDER" lights.rscene --backend cpu -v -o lights.png
  [ "$status" -eq 0 ]
  [[ "$stderr" != *RS9004* ]]
  [[ "$stderr" =~ shadow\ passes\ [0-9.]+\ s,\ drawing ]]
  [ -s lights.png ]
}

@test "thousands of decals or shadowed lights stay bounded: the nearest 1024 decals, the 64 strongest shadows, each said once" {
  {
    echo "raisim_engine_scene 1"
    echo "camera /Cam -6 0 3 0.9732 0 0.2298 0 45 0.05 100 160 90 rgb true"
    echo "object /Floor ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default engine_default false true true - static true 1 18446744073709551615"
    for i in $(seq 1 1100); do echo "projected_decal /D$i 3 3 0 1 0 0 0 1 1 1 halfExtents=0.01,0.01,0.1 color=0,0,1,1"; done
    for i in $(seq 1 70); do echo "light /L$i 0 0 -1 0.1 type=spot position=$((i % 10)),$((i / 10)),3 shadows=true"; done
  } > many.rscene
  run -0 --separate-stderr timeout 60 "$RENDER" many.rscene --backend cpu -o many.png
  [[ "$stderr" == *"1100 decals in view: the 1024 nearest the camera are drawn [RS9055]"* ]]
  [[ "$stderr" == *"70 lights cast shadows; the 64 strongest do, the others light without shadow [RS9050]"* ]]
  [ "$(grep -c RS9055 <<<"$stderr")" -eq 1 ]
  is_png many.png
}

# Issue 14: deformables and granular beds along a simulation.  A cloth
# (an 8 x 8 OBJ grid, pinned at two corners) and a granular bed of 32
# grains: rscene-sim --trajectory, then rscene-render draws every frame.
particle_scene() {
  awk 'BEGIN { n = 8
    for (j = 0; j < n; j++) for (i = 0; i < n; i++) printf "v %g %g 0\n", i / (n - 1) - 0.5, j / (n - 1) - 0.5
    for (j = 0; j < n - 1; j++) for (i = 0; i < n - 1; i++) { a = j * n + i + 1; printf "f %d %d %d %d\n", a, a + 1, a + n + 1, a + n } }' > cloth.obj
  cat > p.rscene <<SCENE
raisim_engine_scene 1
camera /World/Cam -4 0 2 0.9659 0 0.2588 0 60 0.05 100 160 120 rgb true id=cam
light /World/Sun 0.2 0.1 -1 3 type=directional
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615
deformable /World/Cloth cloth cloth.obj 0 0.8 1.5 1 0 0 0 1 1 1 pinnedVertices=0,7 totalMass=0.2
granular /World/Sand particles 0 -1 0 1 0 0 0 1 1 1 boxMax=0.4,0.4,0.2 radius=0.05 spacing=0.1
SCENE
}

@test "particles: rscene-sim --trajectory of a cloth and a granular bed, then rscene-render --trajectory: one image per frame" {
  [ -x "$BIN/rscene-sim" ] || skip "rscene-sim not built in $BIN"
  particle_scene
  run -0 "$BIN/rscene-sim" p.rscene --duration 0.05 --every 4 --trajectory t.jsonl -o /dev/null
  run -0 "$BIN/rscene-sim" p.rscene --duration 0.05 --every 4 --trajectory t.csv --trajectory-format csv -o /dev/null
  frames=$(grep -c '"path":"/World/Sand","points":\[\[' t.jsonl)
  [ "$frames" -ge 2 ]
  [ "$(grep -c '"path":"/World/Cloth","points":\[\[' t.jsonl)" -eq "$frames" ]
  run -0 --separate-stderr "$RENDER" p.rscene --trajectory t.jsonl -o 'j/{frame}.png'
  [ "$(ls j | wc -l)" -eq "$frames" ]
  is_png j/000000.png
  is_png "j/$(printf %06d $((frames - 1))).png"
  # The CSV trajectory (points column) draws the same frames.
  run -0 --separate-stderr "$RENDER" p.rscene --trajectory t.csv -o 'c/{frame}.png'
  [ "$(ls c | wc -l)" -eq "$frames" ]
  cmp j/000001.png c/000001.png
}

@test "trajectory: bodies named with a newline or a byte that is not UTF-8 go from rscene-sim to rscene-render in both formats" {
  printf 'raisim_engine_scene 1\ntime_step 0.0025\n' > odd.rscene
  printf 'object /World/x%%FF sphere 0 0 1 1 0 0 0 1 1 1 0.2 0 1 default - false true false - dynamic true 1 18446744073709551615\n' >> odd.rscene
  printf 'object /World/nl%%0Aline sphere 2 0 1 1 0 0 0 1 1 1 0.2 0 1 default - false true false - dynamic true 1 18446744073709551615\n' >> odd.rscene
  for format in jsonl csv; do
    run -0 "$BIN/rscene-sim" --steps 2 --trajectory "t.$format" --trajectory-format "$format" -o /dev/null odd.rscene
    [ "$(ls -A | grep -c tmp)" -eq 0 ]
    run -0 "$RENDER" --width 32 --height 24 --trajectory "t.$format" -o "$format/{frame}.png" odd.rscene
    is_png "$format/000002.png"
  done
  # the quoted newline makes the CSV record two lines long
  [ "$(grep -c '^0,' t.csv)" -eq 2 ]
}

@test "particles: a frame with a point too few or a malformed point stops at its line and column" {
  particle_scene
  echo '{"time":0,"path":"/World/Cloth","points":[[0,0,1]]}' > few.jsonl
  run -2 --separate-stderr "$RENDER" p.rscene --trajectory few.jsonl -o 'f/{frame}.png'
  [ "$stderr" = "few.jsonl:1:33: error: '/World/Cloth' has 64 vertices (its OBJ's v lines), the line gives 1 points [RS9047]" ]
  [ -z "$(ls f 2>/dev/null)" ]  # no image written
  printf '%s\n' '{"time":0,"path":"/World/Sand","points":[[0,0,1],[0,nan,1]]}' > nan.jsonl
  run -2 --separate-stderr "$RENDER" p.rscene --trajectory nan.jsonl -o 'f/{frame}.png'
  [[ "$stderr" == "nan.jsonl:1:"*": error: malformed JSON"*"[RS9046]"* ]]
  printf '%s\n' 'time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,points' '0,/World/Sand,,,,,,,,,,,,,,0 0 1;0 1' > two.csv
  run -2 --separate-stderr "$RENDER" p.rscene --trajectory two.csv -o 'f/{frame}.png'
  [ "$stderr" = "two.csv:2:34: error: point 1 '0 1' is not three numbers 'x y z' [RS9046]" ]
}
