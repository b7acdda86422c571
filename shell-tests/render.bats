#!/usr/bin/env bats
# End-to-end tests of rscene-render on the CPU backend: every flag, exit
# statuses, exact messages for bad input, and baseline comparison.

BIN="${RSCENE_BIN:-$BATS_TEST_DIRNAME/../build/bin}"
ROOT="$BATS_TEST_DIRNAME/.."
DATA="$ROOT/tests/data"
RENDER="$BIN/rscene-render"

bats_require_minimum_version 1.5.0

setup() {
  [ -x "$RENDER" ] || skip "rscene-render not built in $BIN"
  mkdir "$BATS_TEST_TMPDIR/w"
  cd "$BATS_TEST_TMPDIR/w"
}

# Width and height from a PNG's IHDR.
png_size() {
  od -An -tu1 -j16 -N8 "$1" | awk '{ printf "%dx%d\n", $1*16777216+$2*65536+$3*256+$4, $5*16777216+$6*65536+$7*256+$8 }'
}

is_png() {
  [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]
}

@test "--help lists every flag" {
  run "$RENDER" --help
  [ "$status" -eq 0 ]
  for f in --output --width --height --samples --transparent --backend --camera --stdin-filename \
           --base-dir --allow-missing-assets --reference --threshold --diff-output --verbose --version; do
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
  [ "$output" = "rscene-render: error: no camera with path or id '/World/Nope'; its cameras: /World/Cam" ]
  [ ! -e c.png ]
  run -2 "$RENDER" "$DATA/render_mesh.rscene" --camera cam_mian -o c.png
  [ "$output" = "rscene-render: error: no camera with path or id 'cam_mian'; did you mean 'cam_main'?" ]
}

@test "missing mesh: exit 2 naming the resolved path; --allow-missing-assets draws a placeholder" {
  cp "$DATA/render_mesh.rscene" scene.rscene
  run "$RENDER" scene.rscene -o out.png
  [ "$status" -eq 2 ]
  [[ "${lines[0]}" == "scene.rscene:5:1: error: mesh file not found: render_assets/crate.obj [RS5001]" ]]
  [ ! -e out.png ]
  run "$RENDER" scene.rscene --allow-missing-assets -o out.png
  [ "$status" -eq 0 ]
  [[ "${lines[0]}" == "scene.rscene:5:1: warning: mesh file not found: render_assets/crate.obj [RS5001]" ]]
  is_png out.png
}

@test "--base-dir and --stdin-filename resolve assets" {
  run "$RENDER" --base-dir "$DATA" -o a.png < "$DATA/render_mesh.rscene"
  [ "$status" -eq 0 ]
  run "$RENDER" --stdin-filename "$DATA/render_mesh.rscene" -o b.png < "$DATA/render_mesh.rscene"
  [ "$status" -eq 0 ]
  cmp a.png b.png
}

@test "skipped record kinds are listed in one warning" {
  run "$RENDER" "$DATA/render_skipped.rscene" -o out.png
  [ "$status" -eq 0 ]
  [ "$output" = "rscene-render: warning: skipped records it does not draw yet: local_fog (2), sensor (1)" ]
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
  [[ "$output" == "difference 0.000000 (pixels off by more than 16/255), threshold 0, mean error 0.000000, max 0/255" ]]
}

@test "--reference/--threshold/--diff-output: a different render exits 1 and writes the diff" {
  "$RENDER" "$DATA/render_minimal.rscene" --camera auto --width 64 --height 36 -o base.png
  run "$RENDER" "$DATA/render_minimal.rscene" --width 64 --height 36 --reference base.png --threshold 0.001 \
      --diff-output diff.png
  [ "$status" -eq 1 ]
  [[ "$output" == "difference 0."* ]]
  is_png diff.png
  run "$RENDER" "$DATA/render_minimal.rscene" --width 64 --height 36 --reference base.png --threshold 1
  [ "$status" -eq 0 ]
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
  [ "$output" = "rscene-render: error: nothing to write: give -o FILE (-o - for standard output) or --reference FILE" ]
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
  SHARED="$ROOT/../shared/corpus"
  [ -f "$SHARED/rayrai_warehouse.rscene" ] || skip "no corpus in ../shared"
  run "$RENDER" "$SHARED/rayrai_warehouse.rscene" --allow-missing-assets --width 160 --height 100 -o out.png
  [ "$status" -eq 0 ]
  is_png out.png
}
