#!/usr/bin/env bats
# rscene-diff --review DIR (issue 27): before.png and after.png from one
# camera, changes.png marked from the id pass, review.md and index.html.
# Pixel facts come from review_png.py (exact palette colors of changes.png,
# in the picture above its legend band); every image these tests make was
# looked at while writing them.  Small images on the CPU backend.

load helpers
DIFF="$BIN/rscene-diff"
PNG="$BATS_TEST_DIRNAME/review_png.py"
export LP_NUM_THREADS=1
W=160
H=96

setup() {
  needs_tools rscene-diff
  "$DIFF" --help | grep -q -- --review || skip "rscene-diff built without lib/render"
  in_workdir
  cat > old.rscene <<'EOF2'
raisim_engine_scene 2
light /World/Sun 0.3 0.2 -1 3 type=directional shadows=true
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615
object /World/Crates/Box box 0 0 0.5 1 0 0 0 1 1 1 1 1 1 default - false true false - static true 1 18446744073709551615
object /World/Crates/Other box -2 1 0.5 1 0 0 0 1 1 1 1 1 1 default - false true false - static true 1 18446744073709551615
EOF2
}

# facts FILE: review_png.py's lines for the picture of changes.png.
facts() { python3 "$PNG" "$1" "$H"; }
count() { awk -v k="$1" '$1 == k { print $2 }' <<<"$2"; }
cx() { awk -v k="$1" '$1 == k { print $3 }' <<<"$2"; }

review() { "$DIFF" -q --review out --width "$W" --height "$H" "$@"; }

@test "review: the folder holds the five files; exit 1 when the scenes differ" {
  sed 's|Box box 0 0 0.5|Box box 1.5 0 0.5|' old.rscene > new.rscene
  run review old.rscene new.rscene
  [ "$status" -eq 1 ]
  [ -z "$output" ]
  run ls out
  [ "$output" = "$(printf '%s\n' after.png before.png changes.png index.html review.md)" ]
  f=$(facts out/before.png)
  [[ "$f" == *"size $W $H"* ]]
  f=$(facts out/changes.png)
  [ "$(awk '$1 == "size" { print $3 }' <<<"$f")" -gt "$H" ]  # the legend band below the picture
}

@test "review: a moved box is orange at its new place and outlined in dashed blue at its old one" {
  sed 's|Box box 0 0 0.5|Box box 1.5 0 0.5|' old.rscene > new.rscene
  run review old.rscene new.rscene
  [ "$status" -eq 1 ]
  f=$(facts out/changes.png)
  echo "$f"
  [ "$(count changed "$f")" -gt 20 ]
  [ "$(count ghost "$f")" -gt 5 ]
  [ "$(count added "$f")" -eq 0 ]
  [ "$(count removed "$f")" -eq 0 ]
  # +x is to the right in the three-quarter view from -x,-y.
  [ "$(cx changed "$f")" -gt "$(cx ghost "$f")" ]
  grep -q '| object /World/Crates/Box | changed | position | 0,0,0.5 | 1.5,0,0.5 |' out/review.md
}

@test "review: an added sphere is green, and nothing else is marked" {
  { cat old.rscene
    echo 'object /World/Props/Ball sphere 1 -1.5 0.5 1 0 0 0 0.5 0.5 0.5 1 1 1 default - false true false - static true 1 18446744073709551615'
  } > new.rscene
  run review old.rscene new.rscene
  [ "$status" -eq 1 ]
  f=$(facts out/changes.png)
  echo "$f"
  [ "$(count added "$f")" -gt 20 ]
  [ "$(count changed "$f")" -eq 0 ]
  [ "$(count removed "$f")" -eq 0 ]
  [ "$(count ghost "$f")" -eq 0 ]
  grep -q '^#### /World/Props$' out/review.md
  grep -q '| object /World/Props/Ball | added | |  | primitive=sphere, position=1,-1.5,0.5' out/review.md
}

@test "review: a removed box is red where it stood in the old scene" {
  grep -v Other old.rscene > new.rscene
  run review old.rscene new.rscene
  [ "$status" -eq 1 ]
  f=$(facts out/changes.png)
  echo "$f"
  [ "$(count removed "$f")" -gt 20 ]
  [ "$(count added "$f")" -eq 0 ]
  [ "$(count changed "$f")" -eq 0 ]
  # The box at x=-2 stood left of the one that stays (at the image's centre).
  [ "$(cx removed "$f")" -lt $((W / 2)) ]
}

@test "review: an unchanged scene, and one respelled only, mark nothing and exit 0" {
  cp old.rscene same.rscene
  sed -e 's|Box box 0 0 0.5 1|Box   box 0.0 0 0.50 1.0|' -e 's|^light /World/Sun 0.3|light  /World/Sun 0.30|' old.rscene > respelled.rscene
  ! cmp -s old.rscene respelled.rscene
  for new in same.rscene respelled.rscene; do
    rm -rf out
    run review old.rscene "$new"
    [ "$status" -eq 0 ]
    f=$(facts out/changes.png)
    echo "$f"
    for k in added removed changed ghost; do [ "$(count "$k" "$f")" -eq 0 ]; done
    cmp out/before.png out/after.png
    grep -q '^\*\*no change\*\*' out/review.md
  done
}

@test "review: a side that does not parse gives the line diff in review.md, no images, exit 2" {
  sed 's|Box box 0 0 0.5 .*|Box box 0 0 0.5|' old.rscene > bad.rscene  # a truncated record
  mkdir out && touch out/before.png  # an earlier review's image does not stay
  run --separate-stderr "$DIFF" --review out old.rscene bad.rscene
  [ "$status" -eq 2 ]
  [[ "$stderr" == *"bad.rscene:4:"*"showing a line diff"* ]]
  [[ "$output" == *"+object /World/Crates/Box box 0 0 0.5"$'\n'* ]]
  run ls out
  [ "$output" = "$(printf '%s\n' index.html review.md)" ]
  grep -q '^```diff$' out/review.md
  grep -qF -- '-object /World/Crates/Box box 0 0 0.5' out/review.md
}

@test "review: DIR is made with its parents; a file or a symbolic link there is refused" {
  cp old.rscene new.rscene
  run "$DIFF" -q --review a/b/c --width 32 --height 24 old.rscene new.rscene
  [ "$status" -eq 0 ]
  [ -f a/b/c/review.md ]
  touch file
  run --separate-stderr "$DIFF" --review file old.rscene new.rscene
  [ "$status" -eq 2 ]
  [ "$stderr" = "rscene-diff: error: --review: 'file' exists and is not a folder" ]
  mkdir real && ln -s real link
  run --separate-stderr "$DIFF" --review link old.rscene new.rscene
  [ "$status" -eq 2 ]
  [[ "$stderr" == "rscene-diff: error: --review: 'link' is a symbolic link"* ]]
  [ -z "$(ls real)" ]
}

@test "review: --camera, --width and --height need --review; --review takes no git arguments" {
  cp old.rscene new.rscene
  run --separate-stderr "$DIFF" --width 10 old.rscene new.rscene
  [ "$status" -eq 2 ]
  [ "$stderr" = "rscene-diff: error: --camera, --width and --height go with --review DIR" ]
  h=0123456789012345678901234567890123456789
  run --separate-stderr "$DIFF" --review out x.rscene old.rscene "$h" 100644 new.rscene "$h" 100644
  [ "$status" -eq 2 ]
  [ "$stderr" = "rscene-diff: error: --review takes OLD NEW, not git's external-diff arguments" ]
  [ ! -e out ]
  run --separate-stderr "$DIFF" --review "" old.rscene new.rscene
  [ "$status" -eq 2 ]
  [ "$stderr" = "rscene-diff: error: --review: give a folder, not an empty string" ]
}

@test "review: the scenes' shared camera is used; --camera names another or auto" {
  cam='camera /World/Cam -6 0 2 0.9848 0 0.1736 0 50 0.1 100 160 96 rgb true'
  { cat old.rscene; echo "$cam"; } > a.rscene
  sed 's|Box box 0 0 0.5|Box box 0 1 0.5|' a.rscene > b.rscene
  run review a.rscene b.rscene
  [ "$status" -eq 1 ]
  grep -q 'Drawn from camera /World/Cam, the scenes'"'"' own' out/review.md
  run review --camera auto a.rscene b.rscene
  [ "$status" -eq 1 ]
  grep -q 'Drawn from the automatic view of both scenes' out/review.md
  run review --camera /World/Cam old.rscene b.rscene
  [ "$status" -eq 1 ]
  grep -q 'Drawn from camera /World/Cam' out/review.md
  run --separate-stderr review --camera /World/Nope a.rscene b.rscene
  [ "$status" -eq 2 ]
  [[ "$stderr" == "rscene-diff: error: --camera: no camera with path or id '/World/Nope'"* ]]
}

@test "review: an added scene (/dev/null before) marks everything added" {
  run review /dev/null old.rscene
  [ "$status" -eq 1 ]
  f=$(facts out/changes.png)
  [ "$(count added "$f")" -gt 20 ]
  grep -q '^\*\*5 records: 5 added\*\* (/dev/null &rarr; old.rscene)' out/review.md
}

@test "review: a scene that parses but does not build gives the table without images, exit 2" {
  sed 's|Box box 0 0 0.5|Box box 0 0 oops|' old.rscene > bad.rscene
  run --separate-stderr "$DIFF" --review out old.rscene bad.rscene
  [ "$status" -eq 2 ]
  [[ "$stderr" == "bad.rscene:4:34: error: expected a number, found 'oops' [RS2001]"* ]]
  run ls out
  [ "$output" = "$(printf '%s\n' index.html review.md)" ]
  grep -q 'A scene does not build (bad.rscene; rscene-validate says why): no images are drawn' out/review.md
  grep -q '| object /World/Crates/Box | changed | position | 0,0,0.5 | 0,0,oops |' out/review.md
}

@test "review: review.md escapes | and Markdown in values" {
  sed 's|^object /World/Crates/Other box -2 1 0.5 1 0 0 0 1 1 1 1 1 1 default - false true false -|object /World/Crates/Other mesh -2 1 0.5 1 0 0 0 1 1 1 1 1 1 default - false true false a_b.obj|' old.rscene > a.rscene
  sed 's|a_b.obj|a\|*b*.obj|' a.rscene > b.rscene
  run --separate-stderr review a.rscene b.rscene
  [ "$status" -eq 1 ]
  grep -qF '| meshPath | a\_b.obj | a\|\*b\*.obj |' out/review.md
}

# chrome ARGS...: Debian's chromium, headless, with every host name
# unresolvable (a request to the network fails instead of leaving).
chrome() {
  timeout 120 chromium --headless=new --no-sandbox --disable-gpu --hide-scrollbars --force-color-profile=srgb \
    --host-resolver-rules='MAP * ~NOTFOUND' --user-data-dir="$BATS_TEST_TMPDIR/chrome" "$@"
}

@test "review: index.html in a real headless browser: no console errors, no requests, the buttons switch the image, the screenshot shows it pixel for pixel" {
  command -v chromium >/dev/null || skip "chromium not installed (scripts/install-deps.sh)"
  sed 's|Box box 0 0 0.5|Box box 1.5 0 0.5|' old.rscene > new.rscene
  run review old.rscene new.rscene
  [ "$status" -eq 1 ]
  # grep: the page has no <img src> or <link> outside data: URIs.
  ! grep -qE '(src|href)="(https?:|//|file:)' out/index.html
  page="file://$PWD/out/index.html"
  # The page's own check, run on load, is read back from the DOM; the
  # browser's log holds every console message (CONSOLE lines).
  chrome --enable-logging=stderr --v=0 --virtual-time-budget=5000 --dump-dom "$page" > dom.html 2> log.txt
  grep -o 'data-selfcheck="[^"]*"' dom.html
  grep -q 'data-selfcheck="requests 0; images 2 decoded 2; before true; changes true; after true; slider true"' dom.html
  ! grep -i 'CONSOLE' log.txt
  # A screenshot of each view holds its image unscaled, pixel for pixel.
  for view in after before changes; do
    chrome --window-size=800,600 --screenshot="$PWD/shot-$view.png" "$page#$view" 2>/dev/null
    run python3 "$PNG" --find "shot-$view.png" "out/$view.png"
    echo "$view: $output"
    [[ "$output" == "at "* ]]
  done
  # and not another view's image.
  run python3 "$PNG" --find shot-before.png out/after.png
  [ "$output" = absent ]
}

@test "review: a robot whose knee turned marks the links that moved, not the whole robot" {
  robots="$DATA/robots/check"
  walker() {  # $1: the left knee; $2: the base's x
    printf '%s\n' "raisim_engine_scene 1" "light /World/Sun 0.3 0.2 -1 3 type=directional shadows=true" \
      "object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615" \
      "articulated_resource walker_res Walker $robots/walker.urdf" \
      "articulated /World/W walker_res 0 0 0.5 1 0 0 0 true true id=walker generalizedCoordinate=$2,0,0.5,1,0,0,0,0.3,$1,0.3,-0.6 generalizedVelocity=0,0,0,0,0,0,0,0,0,0"
  }
  walker -0.6 0 > a.rscene
  walker -1.4 0 > knee.rscene
  walker -0.6 0.05 > base.rscene
  # One camera for both runs: the robot's whole body, seen from the front left.
  cam='camera /World/Cam -1.2 -1.2 0.8 0.9188 -0.0400 0.0966 0.3806 50 0.05 50 160 96 rgb true'
  for f in a knee base; do echo "$cam" >> $f.rscene; done
  run review a.rscene knee.rscene
  [ "$status" -eq 1 ]
  grep -qF '| articulated /World/W | changed | generalizedCoordinate\[L\_KNEE\] | -0.6 | -1.4 |' out/review.md
  knee=$(facts out/changes.png)
  echo "knee: $knee"
  run review a.rscene base.rscene
  [ "$status" -eq 1 ]
  base=$(facts out/changes.png)
  echo "base: $base"
  [ "$(count changed "$knee")" -gt 5 ]
  [ "$(count ghost "$knee")" -gt 0 ]
  # Every link moved with the base: far more marked than for one shin.
  [ "$(count changed "$base")" -gt $(( 2 * $(count changed "$knee") )) ]
}

@test "review: a robot file changed marks the robots that use it" {
  robots="$DATA/robots/check"
  sed 's|<box size="0.4 0.3 0.1"/></geometry></visual>|<box size="0.6 0.3 0.2"/></geometry></visual>|' "$robots/walker.urdf" > wide.urdf
  walker() {  # $1: the robot file
    printf '%s\n' "raisim_engine_scene 1" "light /World/Sun 0.3 0.2 -1 3 type=directional shadows=true" \
      "object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615" \
      "articulated_resource walker_res Walker $1" \
      "articulated /World/W walker_res 0 0 0.5 1 0 0 0 true true id=walker" \
      'camera /World/Cam -1.2 -1.2 0.8 0.9188 -0.0400 0.0966 0.3806 50 0.05 50 160 96 rgb true'
  }
  walker "$robots/walker.urdf" > a.rscene
  walker "$PWD/wide.urdf" > b.rscene
  run review a.rscene b.rscene
  [ "$status" -eq 1 ]
  f=$(facts out/changes.png)
  echo "$f"
  [ "$(count changed "$f")" -gt 20 ]
  grep -qF '| articulated\_resource walker\_res | changed | path |' out/review.md
}

@test "review: a missing mesh is drawn as a placeholder, warned once for both scenes" {
  sed 's|^object /World/Crates/Other box -2 1 0.5 1 0 0 0 1 1 1 1 1 1 default - false true false -|object /World/Crates/Other mesh -2 1 0.5 1 0 0 0 1 1 1 1 1 1 default - false true false missing.obj|' old.rscene > a.rscene
  sed 's|Box box 0 0 0.5|Box box 1.5 0 0.5|' a.rscene > b.rscene
  run --separate-stderr review a.rscene b.rscene
  [ "$status" -eq 1 ]
  echo "$stderr"
  [ "$(grep -c "warning: mesh file 'missing.obj' does not exist" <<<"$stderr")" -eq 1 ]
  [[ "$stderr" == "b.rscene:5:"* ]]
}

@test "review: a change out of the shared camera's view is said, on stderr and in review.md" {
  # The camera looks away from the boxes (along -x, from x=-6).
  cam='camera /World/Cam -6 0 2 0 0 0 1 50 0.1 100 160 96 rgb true'
  { cat old.rscene; echo "$cam"; } > a.rscene
  sed 's|Box box 0 0 0.5|Box box 0 1 0.5|' a.rscene > b.rscene
  run --separate-stderr review a.rscene b.rscene
  [ "$status" -eq 1 ]
  [[ "$stderr" == *"rscene-diff: warning: --review: what changed is out of the view of camera /World/Cam, the scenes' own"* ]]
  grep -q 'Note: what changed is out of the view of camera /World/Cam' out/review.md
  [[ "$stderr" == *": --camera changes frames it" ]]
  run --separate-stderr review --camera changes a.rscene b.rscene
  [ "$status" -eq 1 ]
  [ -z "$stderr" ]
  grep -q 'Drawn from the automatic view of what changed' out/review.md
  f=$(facts out/changes.png)
  [ "$(count changed "$f")" -gt 20 ]
}
