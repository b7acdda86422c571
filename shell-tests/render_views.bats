#!/usr/bin/env bats
# rscene-render's many views (CPU backend): --all-cameras, a sensor chosen
# by --camera, -o patterns and the records' outputPath, the files each pass
# writes, collisions found before drawing, and --trajectory frames (from
# rscene-sim, and a camera on a robot link that moves between frames).

load helpers
RENDER="$BIN/rscene-render"
SIM="$BIN/rscene-sim"

setup() {
  needs_tools rscene-render
  in_workdir
  cat > s.rscene << 'EOF'
raisim_engine_scene 2
light /World/Sun -0.3 0.4 -1.0 3.5 id=sun type=directional position=0,0,5 color=1,1,1
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615 id=ground
object /World/Box box 1 0 0.5 1 0 0 0 1 1 1 0.5 1 1.0 default - false true false - dynamic true 1 18446744073709551615 id=box
camera /World/Cam -4 0 1 1 0 0 0 60 0.05 100 64 48 rgb_depth true id=cam outputPath=caps/cam.png
camera /World/Off -4 0 1 1 0 0 0 60 0.05 100 64 48 rgb false id=off
sensor /World/Eye depth_camera ground -3 0 0.5 1 0 0 0 id=eye width=40 height=30 segmentation=true outputPath=caps/eye.png
sensor /World/Imu imu box 0 0 0 1 0 0 0 id=imu
EOF
}

# Bit depth and color type of a PNG (IHDR bytes 24 and 25): "16 0" is 16-bit gray.
png_format() {
  od -An -tu1 -j24 -N2 "$1" | awk '{ print $1, $2 }'
}

# The shape in a NumPy .npy header.
npy_shape() {
  head -c 128 "$1" | tr -d '\0' | grep -ao "'shape': ([0-9]*, [0-9]*)"
}

@test "--all-cameras: every enabled camera and camera-like sensor, every pass, named by -o" {
  run "$RENDER" s.rscene --all-cameras -o 'out/{name}.{kind}.png'
  [ "$status" -eq 0 ]
  [ "$(cd out && ls | tr '\n' ' ')" = "World_Cam.depth.npy World_Cam.depth.png World_Cam.rgb.png World_Eye.depth.npy World_Eye.depth.png World_Eye.segmentation.json World_Eye.segmentation.png " ]
  is_png out/World_Cam.rgb.png
  [ "$(png_size out/World_Cam.rgb.png)" = "64x48" ]
  [ "$(png_format out/World_Cam.depth.png)" = "16 0" ]
  [ "$(png_size out/World_Eye.segmentation.png)" = "40x30" ]
  [ "$(npy_shape out/World_Eye.depth.npy)" = "'shape': (30, 40)" ]
  [ "$(head -c 6 out/World_Cam.depth.npy | tail -c 5)" = "NUMPY" ]
  grep -q '"path": "/World/Box"' out/World_Eye.segmentation.json
}

@test "-o fields: {id} {kind} {frame} {time}; an unknown field is a usage error" {
  run "$RENDER" s.rscene --camera eye -o 'o/{id}-{kind}-{frame}-{time}.png'
  [ "$status" -eq 0 ]
  [ -f o/eye-depth-000000-0.png ]
  [ -f o/eye-segmentation-000000-0.json ]
  run -2 --separate-stderr "$RENDER" s.rscene --all-cameras -o 'o/{nme}.png'
  [ "$stderr" = "rscene-render: error: unknown field {nme} in output pattern (fields: {name} {id} {kind} {frame} {time})" ]
}

@test "--camera selects a sensor by path or id; an unknown name is exit 2" {
  run "$RENDER" s.rscene --camera /World/Eye -o 'a/{kind}.png'
  [ "$status" -eq 0 ]
  [ -f a/depth.png ] && [ -f a/segmentation.png ] && [ ! -e a/rgb.png ]
  run "$RENDER" s.rscene --camera World/Eye -o 'b/{kind}.png'
  [ "$status" -eq 0 ]
  [ -f b/depth.png ]
  run -2 --separate-stderr "$RENDER" s.rscene --camera /World/Ey -o x.png
  [[ "$stderr" == "rscene-render: error: no camera or camera-like sensor with path or id '/World/Ey'; did you mean '/World/Eye'?" ]]
}

@test "without -o each record's outputPath is written, .{kind} added for a view of several passes" {
  run "$RENDER" s.rscene --all-cameras
  [ "$status" -eq 0 ]
  [ "$(cd caps && ls | tr '\n' ' ')" = "cam.depth.npy cam.depth.png cam.rgb.png eye.depth.npy eye.depth.png eye.segmentation.json eye.segmentation.png " ]
}

@test "a single camera record with -o FILE still writes its color image (--reference works as before)" {
  run "$RENDER" s.rscene --camera cam -o one.png
  [ "$status" -eq 0 ]
  [ "$(png_size one.png)" = "64x48" ]
  [ "$(png_format one.png)" = "8 6" ]
  [ ! -e caps ]
  # The same pixels by the many-view path, round shapes included.
  printf 'object /World/Ball sphere -1 0.5 0.6 1 0 0 0 1 1 1 0.3 1 1 default - false true false - dynamic true 1 18446744073709551615\n' >> s.rscene
  "$RENDER" s.rscene --camera cam -o one.png
  "$RENDER" s.rscene --camera cam -o 'p/{kind}.png'
  cmp one.png p/rgb.png
}

@test "a depth camera drawn alone (-o FILE, --camera NAME) writes what --all-cameras writes for it, not a color PNG" {
  grep -v -e '^camera' -e '^sensor' s.rscene > d.rscene
  echo 'camera /World/Depth -4 0 1 1 0 0 0 60 0.05 100 64 48 depth true id=dcam outputPath=caps/d.png' >> d.rscene
  run "$RENDER" d.rscene --all-cameras
  [ "$status" -eq 0 ]
  [ "$(cd caps && ls | tr '\n' ' ')" = "d.npy d.png " ]
  run --separate-stderr "$RENDER" d.rscene -o plain.png  # the first enabled camera
  [ "$status" -eq 0 ]
  [ "$stderr" = "" ]
  run "$RENDER" d.rscene --camera dcam -o named.png
  [ "$status" -eq 0 ]
  for f in plain named; do
    cmp $f.png caps/d.png
    cmp $f.npy caps/d.npy
    # IHDR: 16-bit grayscale (bit depth 16, colour type 0), not 8-bit RGBA ("8 6").
    [ "$(png_format $f.png)" = "16 0" ]
    [ "$(python3 -c 'import sys; h = open(sys.argv[1], "rb").read(26); print(h[12:16].decode(), h[24], h[25])' $f.png)" = "IHDR 16 0" ]
  done
  [ "$(png_size plain.png)" = "64x48" ]
  [ "$(npy_shape plain.npy)" = "'shape': (48, 64)" ]
  # A segmentation camera likewise: its image and legend.
  sed 's/ depth true id=dcam/ segmentation true id=dcam/' d.rscene > g.rscene
  "$RENDER" g.rscene --all-cameras -o 'all/{name}.{kind}.png'
  "$RENDER" g.rscene -o seg.png
  cmp seg.png all/World_Depth.segmentation.png
  cmp seg.json all/World_Depth.segmentation.json
  # --reference compares a color image, which a depth camera does not make;
  # -o - writes one color image.
  run -2 --separate-stderr "$RENDER" d.rscene --reference ref.png
  [ "$stderr" = "rscene-render: error: --reference compares a color image; camera '/World/Depth' has renderMode depth, which makes none: write its images with -o and compare those files" ]
  [ ! -e ref.png ]
  run -2 --separate-stderr "$RENDER" d.rscene -o -
  [ "$stderr" = "rscene-render: error: -o - writes one color image; '/World/Depth' makes a depth image and its .npy beside it: give -o FILE or -o PATTERN" ]
}

@test "an outputPath outside the current folder is refused; nothing is written" {
  sed 's#outputPath=caps/cam.png#outputPath=../cam.png#' s.rscene > up.rscene
  run -2 --separate-stderr "$RENDER" up.rscene --all-cameras
  [[ "$stderr" == *"up.rscene:5:"*"error: "*"outputPath"*"'..'"* ]]
  [ ! -e caps ] && [ ! -e ../cam.png ]
  sed 's#outputPath=caps/cam.png#outputPath=/tmp/cam.png#' s.rscene > abs.rscene
  run -2 --separate-stderr "$RENDER" abs.rscene --camera cam
  [[ "$stderr" == *"abs.rscene:5:"*"error: "*"outputPath"* ]]
  [ ! -e caps ]
}

@test "two views writing one file are refused before anything is drawn" {
  run -2 --separate-stderr "$RENDER" s.rscene --all-cameras -o 'same/{kind}.png'
  [ "$stderr" = "rscene-render: error: two images would go to 'same/depth.png': '/World/Cam' (depth) and '/World/Eye' (depth); use {name} and {kind} in -o, or give the records different outputPath [RS9048]" ]
  [ ! -e same/rgb.png ]
  # One view of several passes is one view, not two: put {kind} in -o.
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam -o 'one/{name}.png'
  [ "$stderr" = "rscene-render: error: two images would go to 'one/World_Cam.png': view '/World/Cam' makes several images (rgb, depth); put {kind} in -o, such as 'one/{name}.{kind}.png' [RS9048]" ]
  run -2 --separate-stderr "$RENDER" s.rscene --camera eye -o one.png
  [ "$stderr" = "rscene-render: error: two images would go to 'one.png': view '/World/Eye' makes several images (depth, segmentation); put {kind} in -o, such as 'one.{kind}.png' [RS9048]" ]
  [ ! -e one.png ]
}

@test "an output that cannot be written stops the run before any file is replaced" {
  mkdir -p out/World_Eye.depth.png
  run -2 "$RENDER" s.rscene --all-cameras -o 'out/{name}.{kind}.png'
  [ ! -e out/World_Cam.rgb.png ]
}

@test "-o - writes one color image to standard output, and refuses more" {
  printf 'raisim_engine_scene 2\nobject /World/Box box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 1.0 default - false true false - dynamic true 1 18446744073709551615 id=box\nsensor /World/C rgb - -3 0 0.5 1 0 0 0 width=32 height=24\n' > c.rscene
  "$RENDER" c.rscene --camera /World/C -o - > c.png
  [ "$(png_size c.png)" = "32x24" ]
  run -2 --separate-stderr "$RENDER" s.rscene --camera eye -o -
  [[ "$stderr" == "rscene-render: error: -o - writes one color image"* ]]
}

@test "a renderMode rscene-render does not know warns and draws color" {
  sed 's/ rgb_depth true id=cam/ thermal true id=cam/' s.rscene > th.rscene
  run --separate-stderr "$RENDER" th.rscene --camera cam -o 't/{kind}.png'
  [ "$status" -eq 0 ]
  [[ "$stderr" == "th.rscene:5:"*"warning: renderMode 'thermal' is not one rscene-render draws; the color image is drawn [RS9045]"* ]]
  [ -f t/rgb.png ]
}

@test "flags that do not go together are usage errors" {
  run -2 --separate-stderr "$RENDER" s.rscene --all-cameras --camera cam -o 'x/{name}.png'
  [ "$stderr" = "rscene-render: error: --all-cameras and --camera: give one of them" ]
  run -2 --separate-stderr "$RENDER" s.rscene --every 2 -o x.png
  [ "$stderr" = "rscene-render: error: --every needs --trajectory" ]
  run -2 --separate-stderr "$RENDER" --trajectory - -o 'x/{frame}.png' < s.rscene
  [ "$stderr" = "rscene-render: error: --trajectory - reads standard input, which the scene is read from: name the scene file" ]
  run -2 --separate-stderr "$RENDER" s.rscene --all-cameras --reference r.png
  [ "$stderr" = "rscene-render: error: --reference compares one image: not with --all-cameras or --trajectory" ]
  printf '{"time":0,"path":"/World/Box","position":[0,0,1],"quaternion":[1,0,0,0]}\n' > t.jsonl
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory t.jsonl -o 'x/{kind}.png'
  [ "$stderr" = "rscene-render: error: -o 'x/{kind}.png' has no {frame} or {time}: every frame of --trajectory would write the same file" ]
  run -2 --separate-stderr "$RENDER" s.rscene --all-cameras --every 0 --trajectory t.jsonl -o 'x/{frame}.png'
  [ "$status" -eq 2 ]
  [ ! -e x ]
}

@test "--trajectory: rscene-sim writes, rscene-render reads, one image per frame; --every K" {
  [ -x "$SIM" ] || skip "rscene-sim not built"
  sed 's/box 1 0 0.5 1 0 0 0/box 1 0 3 1 0 0 0/' s.rscene > drop.rscene
  "$SIM" drop.rscene --duration 1 --every 100 --trajectory t.jsonl -o /dev/null
  [ "$(cut -d, -f1 t.jsonl | sort -u | wc -l)" -eq 5 ]
  run "$RENDER" drop.rscene --camera cam --trajectory t.jsonl -o 'f/{name}.{kind}.{frame}.png'
  [ "$status" -eq 0 ]
  [ "$(ls f/*.rgb.*.png | wc -l)" -eq 5 ]
  ! cmp -s f/World_Cam.rgb.000000.png f/World_Cam.rgb.000004.png  # the box fell
  "$SIM" drop.rscene --duration 1 --every 100 --trajectory t.csv --trajectory-format csv -o /dev/null
  run "$RENDER" drop.rscene --camera cam --trajectory t.csv --every 2 -o 'c/{frame}.{kind}.png'
  [ "$status" -eq 0 ]
  [ "$(ls c/*.rgb.png | tr '\n' ' ')" = "c/000000.rgb.png c/000001.rgb.png c/000002.rgb.png " ]
  cmp c/000001.rgb.png f/World_Cam.rgb.000002.png  # CSV frame 2 is JSON Lines frame 2
  # Standard input, when the scene is a file; outputPath gains .{frame}.
  "$RENDER" drop.rscene --camera eye --trajectory - < t.jsonl
  [ -f caps/eye.depth.000004.png ] && [ -f caps/eye.segmentation.000004.json ]
}

@test "--trajectory naming a body the scene does not have: exit 2 at its line and column" {
  { printf '{"time":0,"path":"/World/Box","position":[0,0,1],"quaternion":[1,0,0,0]}\n'
    printf '{"time":0,"path":"/World/Ghost","position":[0,0,1],"quaternion":[1,0,0,0]}\n'; } > t.jsonl
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory t.jsonl -o 'x/{frame}.{kind}.png'
  [ "$stderr" = "t.jsonl:2:18: error: '/World/Ghost' is no object, compound or articulated system of the scene [RS9047]" ]
  [ ! -e x/000000.rgb.png ]
}

@test "--trajectory: malformed lines and missing files are exit 2" {
  printf '{"time":0,"path":"/World/Box","position":[0,0],"quaternion":[1,0,0,0]}\n' > bad.jsonl
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory bad.jsonl -o 'x/{frame}.{kind}.png'
  [ "$stderr" = "bad.jsonl:1:31: error: position is not an array of 3 numbers [RS9046]" ]
  : > empty.jsonl
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory empty.jsonl -o 'x/{frame}.{kind}.png'
  [ "$stderr" = "empty.jsonl: error: empty trajectory: no line to render [RS9046]" ]
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory nope.jsonl -o 'x/{frame}.{kind}.png'
  [ "$stderr" = "rscene-render: error: cannot open trajectory 'nope.jsonl': No such file or directory" ]
}

@test "a camera on a robot link moves with the link between two trajectory frames" {
  cat > arm.urdf << 'EOF'
<robot name="arm">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"><visual><geometry><box size="0.3 0.3 0.3"/></geometry></visual></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 1"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <link name="arm"><visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual></link>
</robot>
EOF
  cat > r.rscene << 'EOF'
raisim_engine_scene 2
light /World/Sun -0.3 0.4 -1.0 3.5 id=sun type=directional position=0,0,5 color=1,1,1
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615 id=ground
object /World/Box box 3 0 0.5 1 0 0 0 1 1 1 0.5 1 1.0 default - false true false - dynamic true 1 18446744073709551615 id=box
articulated_resource arm_res Arm arm.urdf
articulated /World/Arm arm_res 0 0 0 1 0 0 0 true true id=arm
sensor /World/Arm/Eye rgb arm 0 0 0 1 0 0 0 id=eye parentLink=arm width=48 height=32
EOF
  { printf '{"time":0,"path":"/World/Arm","position":[0,0,0],"quaternion":[1,0,0,0],"jointPositions":{"j1":0}}\n'
    printf '{"time":1,"path":"/World/Arm","position":[0,0,0],"quaternion":[1,0,0,0],"jointPositions":{"j1":1.2}}\n'
    printf '{"time":2,"path":"/World/Arm","position":[0,0,0],"quaternion":[1,0,0,0],"jointPositions":{"j1":0}}\n'; } > t.jsonl
  run "$RENDER" r.rscene --camera eye --trajectory t.jsonl -o 'f/{frame}.png'
  [ "$status" -eq 0 ]
  ! cmp -s f/000000.png f/000001.png  # turned away from the box
  cmp f/000000.png f/000002.png       # and back
  printf '{"time":0,"path":"/World/Arm","position":[0,0,0],"quaternion":[1,0,0,0],"jointPositions":{"elbow":1}}\n' > j.jsonl
  run -2 --separate-stderr "$RENDER" r.rscene --camera eye --trajectory j.jsonl -o 'g/{frame}.png'
  [[ "$stderr" == "j.jsonl:1:"*": error: joint 'elbow' is no movable joint of robot '/World/Arm' (model 'arm') [RS9047]" ]]
  # A line that leaves a joint out is an error naming it, not a joint at zero.
  printf '{"time":0,"path":"/World/Arm","position":[0,0,0],"quaternion":[1,0,0,0],"jointPositions":{}}\n' > m.jsonl
  run -2 --separate-stderr "$RENDER" r.rscene --camera eye --trajectory m.jsonl -o 'h/{frame}.png'
  [ "$stderr" = "m.jsonl:1:18: error: robot '/World/Arm' (model 'arm'): the line leaves out joint 'j1' (every movable joint needs a position) [RS9047]" ]
  [ ! -e h/000000.png ]
}

@test "ANYmal C's URDF sensor sets are views: --all-cameras and --camera ROBOT/SET/SENSOR" {
  needs_shared corpus/robots/anymal_c/urdf/anymal_sensored.urdf
  urdf="$CORPUS/robots/anymal_c/urdf/anymal_sensored.urdf"
  urdf=$(cd "$(dirname "$urdf")" && pwd)/anymal_sensored.urdf
  { printf 'raisim_engine_scene 2\n'
    printf 'object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615 id=ground\n'
    printf 'object /World/Crate box 1.5 0 0.3 1 0 0 0 0.6 0.6 0.6 5 1 1.0 default - false true false - dynamic true 1 18446744073709551615 id=crate\n'
    printf 'articulated_resource anymal_res ANYmal %s\n' "$urdf"
    printf 'articulated /World/Anymal anymal_res 0 0 0.54 1 0 0 0 true true id=anymal generalizedCoordinate=0,0,0.54,1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8\n'; } > a.rscene
  run "$RENDER" a.rscene --all-cameras -o 'a/{name}.{kind}.png'
  [ "$status" -eq 0 ]
  [ "$(ls a/*.png | wc -l)" -eq 4 ]  # two RealSense sets: color and depth each (the IMUs and the LiDAR are no views)
  [ "$(png_size a/World_Anymal_depth_camera_front_camera_parent_color.rgb.png)" = "640x480" ]
  [ "$(png_format a/World_Anymal_depth_camera_rear_camera_parent_depth.depth.png)" = "16 0" ]
  run "$RENDER" a.rscene --camera World/Anymal/depth_camera_front_camera_parent/color -o front.png
  [ "$status" -eq 0 ]
  cmp front.png a/World_Anymal_depth_camera_front_camera_parent_color.rgb.png
}

@test "a write that fails in the middle of a trajectory stops the run with exit 2" {
  { printf '{"time":0,"path":"/World/Box","position":[1,0,0.5],"quaternion":[1,0,0,0]}\n'
    printf '{"time":1,"path":"/World/Box","position":[1,0,0.7],"quaternion":[1,0,0,0]}\n'
    printf '{"time":2,"path":"/World/Box","position":[1,0,0.9],"quaternion":[1,0,0,0]}\n'; } > t.jsonl
  mkdir f && : > f/000001  # frame 1's folder cannot be made
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory t.jsonl -o 'f/{frame}/{kind}.png'
  [[ "$stderr" == "rscene-render: error: f/000001/"* ]]
  [ -f f/000000/rgb.png ]  # taken by a writer before frame 1 failed
}

@test "a camera record whose parentGroupId is a body rides on it along a trajectory" {
  printf 'camera /World/Box/Cam 0 0 1 1 0 0 0 60 0.05 100 48 32 rgb true id=boxcam parentGroupId=box\n' >> s.rscene
  { printf '{"time":0,"path":"/World/Box","position":[1,0,0.5],"quaternion":[1,0,0,0]}\n'
    printf '{"time":1,"path":"/World/Box","position":[1,0,0.5],"quaternion":[0.7071068,0,0,0.7071068]}\n'
    printf '{"time":2,"path":"/World/Box","position":[1,0,0.5],"quaternion":[1,0,0,0]}\n'; } > t.jsonl
  run --separate-stderr "$RENDER" s.rscene --camera boxcam --trajectory t.jsonl -o 'b/{frame}.png'
  [ "$status" -eq 0 ]
  [ "$stderr" = "" ]  # riding on a body is meant: no RS3007 warning, here or in rscene-validate
  run "$BIN/rscene-validate" s.rscene
  [[ "$output" != *RS3007* ]]
  # A cube turned a quarter looks the same from a fixed camera: only a camera turning with it sees frame 1 differ.
  ! cmp -s b/000000.png b/000001.png
  cmp b/000000.png b/000002.png
}

@test "--trajectory naming a directory is exit 2 with a message, not an abort" {
  mkdir d
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory d -o 'q/{frame}.{kind}.png'
  [ "$stderr" = "rscene-render: error: d: is a directory" ]
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory - -o 'q/{frame}.{kind}.png' < d
  [ "$stderr" = "rscene-render: error: --trajectory -: standard input is a directory" ]
  [ -d /proc/self ] || skip "no /proc"
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory /proc/self -o 'q/{frame}.{kind}.png'
  [ "$stderr" = "rscene-render: error: /proc/self: is a directory" ]
  [ ! -e q ]
}

@test "--trajectory: a duplicate key and a line cut off mid-JSON are errors at their column" {
  printf '{"time":0,"path":"/World/Box","position":[1,0,0.5],"quaternion":[1,0,0,0],"time":5}\n' > dup.jsonl
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory dup.jsonl -o 'x/{frame}.{kind}.png'
  [ "$stderr" = 'dup.jsonl:1:75: error: "time" twice in one object (which one is meant?) [RS9046]' ]
  [ ! -e x/000000.rgb.png ]
  printf '{"time":0,"path":"/World/Box","position":[1,0,0.5],"quaternion":[1,0,0,0]}\n{"time":1,"path":"/World/Box","posi' > cut.jsonl
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory cut.jsonl -o 'x/{frame}.{kind}.png'
  [[ "$stderr" == "cut.jsonl:2:36: error: malformed JSON: "*"missing closing quote"*"[RS9046]" ]]
}

# A robot whose URDF sensor set has a camera, '/World/Arm/head/color', and a
# sensor record of the same path.
two_of_one_name() {
  cat > arm.urdf << 'XML'
<robot name="arm">
  <link name="base"><visual><geometry><box size="0.3 0.3 0.3"/></geometry></visual></link>
  <joint name="j" type="fixed"><parent link="base"/><child link="head"/><origin xyz="0 0 1"/></joint>
  <link name="head" sensor="cam.xml"/>
</robot>
XML
  cat > cam.xml << 'XML'
<?xml version="1.0"?>
<sensor_set name="cam">
  <sensor name="color" type="rgb">
    <origin rpy="0 0 0" xyz="0.3 0 0"/>
    <camera horizontal_fov="1.0"><image width="32" height="24"/><clip near="0.1" far="50"/></camera>
  </sensor>
</sensor_set>
XML
  { printf 'raisim_engine_scene 2\n'
    printf 'object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 1 0 0 default - false true true - static true 1 18446744073709551615 id=ground\n'
    printf 'articulated_resource arm_res Arm arm.urdf\n'
    printf 'articulated /World/Arm arm_res 0 0 0.15 1 0 0 0 true true id=arm\n'
    printf '%s\n' "$1"; } > r.rscene
}

@test "two views of one name: --all-cameras says where each is declared, --camera is ambiguous" {
  two_of_one_name 'sensor /World/Arm/head/color rgb - 3 0 0.5 1 0 0 0 id=dup width=16 height=12'
  run -2 --separate-stderr "$RENDER" r.rscene --all-cameras -o '{name}.png'
  [ "$stderr" = "rscene-render: error: two images would go to 'World_Arm_head_color.png': two views are named '/World/Arm/head/color': the sensor record at r.rscene:5 and a URDF sensor of robot '/World/Arm' (cam.xml:3); rename the record, or use {id} in -o [RS9048]" ]
  run "$RENDER" r.rscene --all-cameras -o '{id}.png'
  [ "$status" -eq 0 ]
  [ "$(png_size dup.png)" = "16x12" ] && [ "$(png_size World_Arm_head_color.png)" = "32x24" ]
  run -2 --separate-stderr "$RENDER" r.rscene --camera World/Arm/head/color -o x.png
  [ "$stderr" = "rscene-render: error: --camera 'World/Arm/head/color' names 2 views: '/World/Arm/head/color' (id dup), the sensor record at r.rscene:5; '/World/Arm/head/color', a URDF sensor of robot '/World/Arm' (cam.xml:3); select one by its record's id, or rename the record" ]
  # A camera record of that path: the single-image path does not pick it silently either.
  two_of_one_name 'camera /World/Arm/head/color 3 0 0.5 1 0 0 0 60 0.05 100 16 12 rgb true id=dup'
  run -2 --separate-stderr "$RENDER" r.rscene --camera /World/Arm/head/color -o x.png
  [[ "$stderr" == "rscene-render: error: --camera '/World/Arm/head/color' names 2 views: "*"the camera record at r.rscene:5; "* ]]
  [ ! -e x.png ]
  "$RENDER" r.rscene --camera dup -o x.png
  [ "$(png_size x.png)" = "16x12" ]
}

@test "--camera: a LiDAR or IMU is no view; unknown names list the sensor views too" {
  run -2 --separate-stderr "$RENDER" s.rscene --camera /World/Imu -o x.png
  [ "$stderr" = "rscene-render: error: '/World/Imu' is a sensor of kind imu, not a view (rscene-render draws cameras and camera-like sensors; rscene-sim --sensors records it); the views of the scene: /World/Cam, /World/Off, /World/Eye" ]
  grep -v '^camera' s.rscene > nocam.rscene
  run -2 --separate-stderr "$RENDER" nocam.rscene --camera nosuch -o x.png
  [ "$stderr" = "rscene-render: error: no camera or camera-like sensor with path or id 'nosuch'; the views of the scene: /World/Eye" ]
  grep -v '^sensor /World/Eye' nocam.rscene > none.rscene
  run -2 --separate-stderr "$RENDER" none.rscene --camera nosuch -o x.png
  [ "$stderr" = "rscene-render: error: no camera or camera-like sensor with path or id 'nosuch'; the scene has no view (leave out --camera, or use --camera auto)" ]
}

@test "a sensor view: --reference is refused with a reason, --width/--height warn and keep its size" {
  run -2 --separate-stderr "$RENDER" s.rscene --camera /World/Eye --reference ref.png
  [ "$stderr" = "rscene-render: error: --reference compares a camera record's color image; '/World/Eye' is a sensor: write its images with -o and compare those files" ]
  [ ! -e ref.png ]
  run --separate-stderr "$RENDER" s.rscene --camera eye --width 100 --height 80 -o 'w/{kind}.png'
  [ "$status" -eq 0 ]
  [ "$stderr" = "rscene-render: warning: --width/--height: sensor '/World/Eye' keeps its own size, 40x30 (its intrinsics are written for it)" ]
  [ "$(png_size w/segmentation.png)" = "40x30" ]
}

@test "an outputPath without an extension gains .png when the view writes several images" {
  sed 's#outputPath=caps/eye.png#outputPath=caps/noext#' s.rscene > n.rscene
  run "$RENDER" n.rscene --camera eye
  [ "$status" -eq 0 ]
  [ "$(cd caps && ls | tr '\n' ' ')" = "noext.depth.npy noext.depth.png noext.segmentation.json noext.segmentation.png " ]
  is_png caps/noext.depth.png
}

@test "images are PNG: an image name with another extension is refused, .PNG and none are fine" {
  run -2 --separate-stderr "$RENDER" s.rscene --all-cameras -o 'pc/{name}.{kind}.npy'
  [ "$stderr" = "rscene-render: error: -o 'pc/{name}.{kind}.npy': 'pc/World_Cam.rgb.npy' ends in .npy, but rscene-render writes PNG images only (a depth image's float .npy and a segmentation's .json legend are written beside the image, under its name with .npy or .json); end -o with .png" ]
  [ ! -e pc ]
  run -2 --separate-stderr "$RENDER" s.rscene --all-cameras -o 'x/{name}.{kind}.jpg'
  [[ "$stderr" == "rscene-render: error: -o 'x/{name}.{kind}.jpg': 'x/World_Cam.rgb.jpg' ends in .jpg, but "* ]]
  [ ! -e x ]
  run -2 --separate-stderr "$RENDER" s.rscene -o cam.JPG
  [[ "$stderr" == "rscene-render: error: -o: 'cam.JPG' ends in .JPG, but rscene-render writes PNG images only "*"; end -o with .png" ]]
  [ ! -e cam.JPG ]
  run -2 --separate-stderr "$RENDER" s.rscene --reference ref.png --diff-output d.jpg
  [[ "$stderr" == "rscene-render: error: --diff-output: 'd.jpg' ends in .jpg, "* ]]
  [ ! -e ref.png ]
  sed 's#outputPath=caps/eye.png#outputPath=caps/eye.jpg#' s.rscene > j.rscene
  # The record's own outputPath is the scene model's rule: RS7069 at the
  # key, as validate and sim say it.
  run -2 --separate-stderr "$RENDER" j.rscene --camera eye
  [[ "$stderr" == "j.rscene:7:"*": error: sensor outputPath 'caps/eye.jpg' ends in .jpg, but "*" [RS7069]"* ]]
  [ ! -e caps ]
  run -1 "$BIN/rscene-validate" j.rscene
  [[ "$output" == "j.rscene:7:"*": error: sensor outputPath 'caps/eye.jpg' ends in .jpg, but "*" [RS7069]"* ]]
  run "$RENDER" s.rscene --camera eye -o 'u/{kind}.PNG'
  [ "$status" -eq 0 ]
  is_png u/depth.PNG && [ -f u/depth.npy ] && [ -f u/segmentation.json ]
  run "$RENDER" s.rscene --camera cam -o 'n/{kind}'
  [ "$status" -eq 0 ]
  is_png n/rgb && is_png n/depth && [ -f n/depth.npy ]
}

@test "--trajectory: {time} names each frame, as {frame} does; times in messages as the file wrote them" {
  { printf '{"time":0,"path":"/World/Box","position":[1,0,0.5],"quaternion":[1,0,0,0]}\n'
    printf '{"time":0.25,"path":"/World/Box","position":[1,0,1.5],"quaternion":[1,0,0,0]}\n'; } > t.jsonl
  run "$RENDER" s.rscene --camera cam --trajectory t.jsonl -o 'tm/{time}.{kind}.png'
  [ "$status" -eq 0 ]
  [ "$(cd tm && ls *.png | tr '\n' ' ')" = "0.25.depth.png 0.25.rgb.png 0.depth.png 0.rgb.png " ]
  ! cmp -s tm/0.rgb.png tm/0.25.rgb.png
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory t.jsonl -o 'tm/{kind}.png'
  [ "$stderr" = "rscene-render: error: -o 'tm/{kind}.png' has no {frame} or {time}: every frame of --trajectory would write the same file" ]
  printf '{"time":-1,"path":"/World/Box","position":[1,0,0.5],"quaternion":[1,0,0,0]}\n' >> t.jsonl
  run -2 --separate-stderr "$RENDER" s.rscene --camera cam --trajectory t.jsonl -o 'tb/{frame}.{kind}.png'
  [ "$stderr" = "t.jsonl:3:1: error: time -1 is before the previous frame's 0.25 (times must not decrease) [RS9046]" ]
}

@test "--trajectory: sensor depth noise is drawn anew each frame; frame 0 is the record's seed, runs repeat" {
  [ -x "$SIM" ] || skip "rscene-sim not built"
  # The eye sees only the static ground; the box falls out of its view.
  sed 's/box 1 0 0.5 1 0 0 0/box 9 9 3 1 0 0 0/; s/segmentation=true/noiseStddev=0.01 noiseSeed=5 segmentation=false/' \
    s.rscene > noisy.rscene
  "$SIM" noisy.rscene --steps 4 --every 2 --trajectory t.jsonl -o /dev/null
  "$RENDER" noisy.rscene --camera eye --trajectory t.jsonl -o 'n/{frame}.{kind}.png'
  "$RENDER" noisy.rscene --camera eye --trajectory t.jsonl -o 'm/{frame}.{kind}.png'
  "$RENDER" noisy.rscene --camera eye -o 'one.{kind}.png'
  ! cmp -s n/000000.depth.npy n/000001.depth.npy  # a new draw of noise on the same view
  cmp n/000001.depth.npy m/000001.depth.npy        # the same sequence on every run
  cmp n/000000.depth.npy one.depth.npy             # frame 0: the record's seed, as a single render
}

@test "a robot's sensor-set camera past --max-pixels is an error at its <sensor> element, with a code" {
  cat > r.urdf <<'XML'
<?xml version="1.0"?>
<robot name="r">
<link name="base" sensor="cam.set.xml"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
</robot>
XML
  cat > cam.set.xml <<'XML'
<?xml version="1.0"?>
<sensor_set name="s1">
  <link>
    <sensor name="c" type="rgb"><camera horizontal_fov="1.5"><image width="4096" height="4096"/></camera></sensor>
  </link>
</sensor_set>
XML
  printf 'raisim_engine_scene 1\narticulated_resource res R r.urdf resourceDirectory=.\narticulated /World/Robot res 0 0 1 1 0 0 0 true true id=art1\n' > s.rscene
  run -2 --separate-stderr "$RENDER" --all-cameras --max-pixels 1000000 -o 'out/{name}.{kind}.png' s.rscene
  [[ $stderr == *"cam.set.xml:4: error: sensor '/World/Robot/base/c': image 4096x4096 is 16777216 pixels, more than --max-pixels 1000000 [RS9013]"* ]]
  [ ! -e out ]
}

@test "a signal that stops a --trajectory render leaves every frame whole (an image with its .json) and ends the tool by that signal" {
  needs_tools rscene-sim
  cat > drop.rscene <<'SCENE'
raisim_engine_scene 1
time_step 0.0025
gravity 0 0 -9.81
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/Box box 0 0 2 1 0 0 0 0.5 0.5 0.5 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615
camera /World/Seg -4 0 1 1 0 0 0 60 0.05 100 32 24 segmentation true id=seg
SCENE
  "$BIN/rscene-sim" --duration 20 --trajectory t.jsonl -o /dev/null drop.rscene
  # The signal comes once some frames are written (a loaded machine may
  # take seconds to start drawing), long before the 8001 frames are done.
  "$RENDER" --all-cameras --trajectory t.jsonl -o 'f/{name}.{kind}.{frame}.png' drop.rscene &
  pid=$!
  for _ in $(seq 600); do compgen -G 'f/*.png' > /dev/null && break; sleep 0.1; done
  kill -TERM "$pid"
  rc=0
  wait "$pid" || rc=$?
  [ "$rc" -eq 143 ]
  ls f/*.png > /dev/null  # some frames were written before the signal
  for png in f/*.png; do [ -s "${png%.png}.json" ] || { echo "no legend for $png"; false; }; done
  [ -z "$(find f -name '.*tmp*')" ]
}
