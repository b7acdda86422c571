#!/usr/bin/env bats
# End-to-end tests of rscene-sim --sensors (with --imu-format and
# --pcd-encoding): the files, their formats, closed-form readings in a box
# room, refused outputPath values, the output rules, determinism.

load helpers
SIM="$BIN/rscene-sim"

# A closed room (inside x -4..4, y -3..3, z 0..2), a crate resting on its
# floor carrying an IMU, and a 1 x 4 LiDAR at its centre, 1 m up.
room() {
  cat <<'EOF2'
raisim_engine_scene 1
time_step 0.01
gravity 0 0 -9.81
object /World/Floor box 0 0 -0.1 1 0 0 0 8.4 6.4 0.2 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/East box 4.1 0 1 1 0 0 0 0.2 6 2 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/West box -4.1 0 1 1 0 0 0 0.2 6 2 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/North box 0 3.1 1 1 0 0 0 8.4 0.2 2 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/South box 0 -3.1 1 1 0 0 0 8.4 0.2 2 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/Crate box 1 1 0.25 1 0 0 0 0.5 0.5 0.5 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615 id=crate
EOF2
  echo "sensor /World/Imu imu crate 0 0 0.25 1 0 0 0 updateRate=10 ${IMU_EXTRA:-}"
  echo "sensor /World/Lidar lidar - 0 0 1 1 0 0 0 updateRate=5 lidarChannels=1 lidarSamples=4 lidarVerticalFov=0 ${LIDAR_EXTRA:-}"
}

setup() {
  needs_tools rscene-sim
  in_workdir
  room > room.rscene
}

@test "--sensors writes an IMU file and LiDAR scans with an index, named by sensor path" {
  run -0 --separate-stderr "$SIM" --duration 1 --sensors out -o /dev/null room.rscene
  [ -z "$stderr" ]
  [ -f out/World+Imu.csv ]
  [ -f out/World+Lidar/scans.csv ]
  # 5 Hz over 1 s: at 0, 0.2 ... 1.
  run -0 cat out/World+Lidar/scans.csv
  [ "${lines[0]}" = "index,time,points,file" ]
  [ "${lines[1]}" = "0,0,4,scan_000000.pcd" ]
  [ "${lines[6]}" = "5,1,4,scan_000005.pcd" ]
  [ "${#lines[@]}" -eq 7 ]
  for i in 0 1 2 3 4 5; do [ -f "out/World+Lidar/scan_00000$i.pcd" ]; done
  # 10 Hz IMU: 0.1 ... 1, after a header.
  run -0 cat out/World+Imu.csv
  [ "${lines[0]}" = "time,ax,ay,az,wx,wy,wz" ]
  [ "${#lines[@]}" -eq 11 ]
  [[ ${lines[1]} == 0.1,* ]]
  [[ ${lines[10]} == 1,* ]]
}

@test "the IMU of a crate at rest reads +9.81 up and no rotation" {
  run -0 "$SIM" --duration 1 --sensors out -o /dev/null room.rscene
  tail -n 1 out/World+Imu.csv | awk -F, '{
    ok = ($2 * $2 + $3 * $3 < 1e-4) && ($4 > 9.80 && $4 < 9.82) && ($5 * $5 + $6 * $6 + $7 * $7 < 1e-6)
    if (!ok) print "bad reading: " $0
    exit !ok }'
}

@test "--pcd-encoding ascii: the LiDAR sees the room's walls 4 m and 3 m away, in its own frame" {
  run -0 "$SIM" --steps 0 --sensors out --pcd-encoding ascii -o /dev/null room.rscene
  run -0 cat out/World+Lidar/scan_000000.pcd
  [ "${lines[0]}" = "# .PCD v0.7 - Point Cloud Data file format" ]
  [ "${lines[1]}" = "# time 0" ]
  [ "${lines[3]}" = "FIELDS x y z" ]
  [ "${lines[5]}" = "TYPE F F F" ]
  [ "${lines[7]}" = "WIDTH 4" ]
  [ "${lines[9]}" = "VIEWPOINT 0 0 1 1 0 0 0" ]
  [ "${lines[10]}" = "POINTS 4" ]
  [ "${lines[11]}" = "DATA ascii" ]
  # yaw 0, 90, 180, 270 (counter-clockwise): east 4, north 3, west 4, south 3.
  sed -n '13,16p' out/World+Lidar/scan_000000.pcd | awk '
    BEGIN { split("4 0 -4 0", ex); split("0 3 0 -3", ey) }
    { n++; d = ($1 - ex[n]) ^ 2 + ($2 - ey[n]) ^ 2 + $3 ^ 2; if (d > 1e-6) { print "point " n ": " $0; bad = 1 } }
    END { exit bad || n != 4 }'
}

@test "binary PCD (the default) holds 12 bytes a point after the header" {
  run -0 "$SIM" --steps 0 --sensors out -o /dev/null room.rscene
  f=out/World+Lidar/scan_000000.pcd
  header=$(head -n 12 "$f" | wc -c)
  [ "$(sed -n 12p "$f")" = "DATA binary" ]
  [ "$(stat -c %s "$f")" -eq $((header + 4 * 12)) ]
  # The first point, float32 little-endian: (4, 0, 0).
  [ "$(tail -c 48 "$f" | od -An -f -N 12 | xargs)" = "4 0 0" ]
}

@test "--imu-format jsonl writes JSON Lines; an outputPath ending in .csv keeps CSV" {
  run -0 "$SIM" --duration 0.2 --sensors out --imu-format jsonl -o /dev/null room.rscene
  [ -f out/World+Imu.jsonl ]
  [ ! -e out/World+Imu.csv ]
  run -0 head -n 1 out/World+Imu.jsonl
  [[ $output == '{"time":0.1,"acceleration":['*'],"angularVelocity":['*']}' ]]
  IMU_EXTRA="outputPath=streams/imu.csv" room > named.rscene
  run -0 "$SIM" --duration 0.2 --sensors out2 --imu-format jsonl -o /dev/null named.rscene
  run -0 head -n 1 out2/streams/imu.csv
  [ "$output" = "time,ax,ay,az,wx,wy,wz" ]
  LIDAR_EXTRA="outputPath=scans/front" room > lidar.rscene
  run -0 "$SIM" --steps 0 --sensors out3 -o /dev/null lidar.rscene
  [ -f out3/scans/front/scan_000000.pcd ]
}

@test "an absolute or '..' outputPath is refused before anything runs, as validate refuses it" {
  IMU_EXTRA="outputPath=/tmp/imu.csv" room > abs.rscene
  run -2 --separate-stderr "$SIM" --sensors out -o /dev/null abs.rscene
  [ "${stderr_lines[0]}" = "abs.rscene:10:71: error: sensor outputPath '/tmp/imu.csv' is absolute [RS7069]" ]
  [ ! -e out ]
  IMU_EXTRA="outputPath=a/../../imu.csv" room > up.rscene
  run -2 --separate-stderr "$SIM" --sensors out -o /dev/null up.rscene
  [[ ${stderr_lines[0]} == "up.rscene:10:71: error: "*"[RS7069]" ]]
  [ ! -e out ]
}

@test "two sensors writing one path are refused; force_torque is skipped with a warning" {
  LIDAR_EXTRA="outputPath=World+Imu.csv" room > same.rscene
  run -2 --separate-stderr "$SIM" --sensors out -o /dev/null same.rscene
  [[ ${stderr_lines[0]} == "same.rscene:11:"*": error: sensor '/World/Lidar' and sensor '/World/Imu' would both write 'World+Imu.csv' [RS7070]" ]]
  { room; echo "sensor /World/Ft force_torque crate 0 0 0 1 0 0 0"; } > ft.rscene
  run -0 --separate-stderr "$SIM" --steps 1 --sensors out -o /dev/null ft.rscene
  [ "${stderr_lines[0]}" = "ft.rscene:12:18: warning: sensor '/World/Ft' of kind 'force_torque' is not recorded (rscene-sim records lidar and imu) [RS7071]" ]
  { room; echo "sensor /World/Big lidar - 0 0 1 1 0 0 0 lidarChannels=4096 lidarSamples=4096"; } > big.rscene
  run -2 --separate-stderr "$SIM" --sensors out -o /dev/null big.rscene
  [ "${stderr_lines[0]}" = "big.rscene:12:73: error: lidar scan of 4096 x 4096 rays is more than 4194304 rays [RS7066]" ]
}

@test "without --sensors, sensors are not recorded and nothing is written" {
  run -0 --separate-stderr "$SIM" --steps 5 -o /dev/null room.rscene
  [ -z "$stderr" ]
  [ -z "$(ls)" ] || [ "$(ls)" = "room.rscene" ]
}

@test "--sensors refuses a file in the way and an output that is also --trajectory" {
  touch afile
  run -2 --separate-stderr "$SIM" --steps 1 --sensors afile -o /dev/null room.rscene
  [ "$stderr" = "rscene-sim: error: afile: cannot create the folder: not a directory" ]
  mkdir out
  run -2 --separate-stderr "$SIM" --steps 1 --sensors out --trajectory out/World+Imu.csv -o /dev/null room.rscene
  [ "$stderr" = "rscene-sim: error: --trajectory 'out/World+Imu.csv' and --sensors 'out/World+Imu.csv' are the same file; one would overwrite the other" ]
}

@test "a symlink at a sensor's file stays a link; its target gets the stream" {
  mkdir out
  echo old > target.csv
  ln -s ../target.csv out/World+Imu.csv
  run -0 "$SIM" --duration 0.2 --sensors out -o /dev/null room.rscene
  [ -L out/World+Imu.csv ]
  run -0 head -n 1 target.csv
  [ "$output" = "time,ax,ay,az,wx,wy,wz" ]
}

@test "the same noiseSeed gives the same noisy streams; another seed does not" {
  IMU_EXTRA="noiseStddev=0.1 noiseSeed=3" LIDAR_EXTRA="noiseStddev=0.01 noiseSeed=3" room > noisy.rscene
  IMU_EXTRA="noiseStddev=0.1 noiseSeed=4" LIDAR_EXTRA="noiseStddev=0.01 noiseSeed=4" room > other.rscene
  "$SIM" --duration 0.5 --sensors a -o /dev/null noisy.rscene
  "$SIM" --duration 0.5 --sensors b -o /dev/null noisy.rscene
  "$SIM" --duration 0.5 --sensors c -o /dev/null other.rscene
  diff -r a b
  ! cmp -s a/World+Imu.csv c/World+Imu.csv
  ! cmp -s a/World+Lidar/scan_000001.pcd c/World+Lidar/scan_000001.pcd
}

@test "--report counts sensors and scans" {
  run -0 --separate-stderr "$SIM" --duration 1 --sensors out --report -o /dev/null room.rscene
  [[ $stderr == *'"lidarScans":6'* ]]
  [[ $stderr == *'"sensors":2'* ]]
}

@test "a bad --imu-format or --pcd-encoding is a usage error" {
  run -2 "$SIM" --sensors out --imu-format xml room.rscene
  run -2 "$SIM" --sensors out --pcd-encoding zip room.rscene
}

@test "ANYmal C's URDF sensor sets (corpus): its IMUs and Ouster LiDAR are recorded under the robot's path" {
  needs_shared corpus/robots/anymal_c/urdf/anymal_sensored.urdf
  urdf="$CORPUS/robots/anymal_c/urdf/anymal_sensored.urdf"
  cat > anymal.rscene <<EOF2
raisim_engine_scene 1
time_step 0.002
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
articulated_resource anymal_res ANYmal $urdf
articulated /World/Anymal anymal_res 0 0 0.54 1 0 0 0 true true id=anymal generalizedCoordinate=0,0,0.54,1,0,0,0,0.03,0.4,-0.8,-0.03,0.4,-0.8,0.03,-0.4,0.8,-0.03,-0.4,0.8
EOF2
  run -0 "$SIM" --duration 0.1 --pd-gains 200,4 --sensors out -o /dev/null anymal.rscene
  [ -f out/World+Anymal+lidar_link+imu.csv ]
  [ -f out/World+Anymal+depth_camera_front_camera_parent+imu.csv ]
  # The Ouster: update_rate 100 over 0.1 s is 11 scans (0 to 0.1) of 64 x 512 rays; the ground ahead returns.
  run -0 cat out/World+Anymal+lidar_link+lidar/scans.csv
  [ "${#lines[@]}" -eq 12 ]
  points=$(echo "${lines[1]}" | cut -d, -f3)
  [ "$points" -gt 1000 ] && [ "$points" -le 32768 ]
  # Its IMU (update_rate 10 in ouster1-64.xml) reads once, at 0.1 s, about +g up.
  run -0 cat out/World+Anymal+lidar_link+imu.csv
  [ "${#lines[@]}" -eq 2 ]
  [[ ${lines[1]} == 0.1,* ]]
}

@test "a run that fails leaves no sensor files: no IMU file, no index, no scans, no folder it made" {
  # The smallest normal mass passes the checks; stepping it does not stay finite (RS7024).
  { room; echo "object /World/Heavy box 0 0 1 1 0 0 0 0.4 0.4 0.4 0.5 1 2.2250738585072014e-308 default engine_default false true false - dynamic true 1 18446744073709551615 id=heavy"
    echo "sensor /World/HeavyImu imu heavy 0 0 0 1 0 0 0"; } > heavy.rscene
  run -2 --separate-stderr "$SIM" --steps 2000 --sensors out -o /dev/null heavy.rscene
  [[ ${stderr_lines[0]} == *"[RS7024]" ]]
  [ ! -e out/World+Imu.csv ]
  [ ! -e out/World+HeavyImu.csv ]
  [ ! -e out/World+Lidar/scans.csv ]
  [ ! -e out ]  # the scans taken before the failure are removed, and the folders the run made
}

@test "an interrupted run (SIGINT) exits 130 and leaves no sensor files; a folder that was there stays" {
  mkdir kept
  run -130 timeout --preserve-status -s INT 1 "$SIM" --duration 100000 --sensors kept/out --trajectory t.jsonl \
    -o scene.out room.rscene
  [ -z "$output" ]  # no 'write cancelled' errors: 130 says it
  [ -d kept ]
  [ ! -e kept/out ]
  [ ! -e t.jsonl ]
  [ ! -e scene.out ]
}

@test "every signal that ends a run (TERM, HUP, PIPE, ALRM, QUIT, USR1, USR2) leaves nothing, and ends the tool by that signal" {
  for sig in TERM HUP PIPE ALRM QUIT USR1 USR2; do
    mkdir "k_$sig"
    run timeout --preserve-status -s "$sig" 1 "$SIM" --duration 100000 --sensors "k_$sig/out" \
      --trajectory "k_$sig/t.jsonl" -o "k_$sig/scene.out" room.rscene
    [ "$status" -eq $((128 + $(kill -l "$sig"))) ] || { echo "$sig: status $status"; false; }
    [ -z "$(ls -A "k_$sig")" ] || { echo "$sig left: $(ls -A "k_$sig")"; false; }
  done
}

@test "--sensors '' is a usage error" {
  run -2 "$SIM" --sensors '' -o /dev/null room.rscene
  [[ $output == *"--sensors"* ]]
  [ ! -e out ]
}

@test "outputPath values sim cannot use are refused at the record, as validate refuses them, before any folder is made" {
  IMU_EXTRA="outputPath=." room > dot.rscene
  run -2 --separate-stderr "$SIM" --sensors out -o /dev/null dot.rscene
  [[ ${stderr_lines[0]} == "dot.rscene:10:71: error: sensor outputPath '.' names the --sensors folder itself [RS7069]" ]]
  [ ! -e out ]
  run -1 "$BIN/rscene-validate" dot.rscene
  [[ $output == *"dot.rscene:10:71: error:"*"[RS7069]"* ]]
  # An IMU inside a LiDAR's folder: the same code and place in both tools.
  IMU_EXTRA="outputPath=x/scans.csv" LIDAR_EXTRA="outputPath=x" room > nest.rscene
  run -2 --separate-stderr "$SIM" --sensors out -o /dev/null nest.rscene
  [ "${stderr_lines[0]}" = "nest.rscene:11:117: error: sensor '/World/Lidar' would write 'x', and sensor '/World/Imu' 'x/scans.csv' inside it [RS7070]" ]
  [ ! -e out ]
  run -1 "$BIN/rscene-validate" nest.rscene
  [[ ${lines[0]} == "nest.rscene:11:117: error: "*"[RS7070]" ]]
  # A LiDAR's outputPath with a final '/' is its folder.
  LIDAR_EXTRA="outputPath=scans/" room > slash.rscene
  run -0 "$SIM" --steps 1 --sensors out -o /dev/null slash.rscene
  [ -f out/scans/scans.csv ]
}

@test "a sensor position past 1e12 m is refused at the field by validate and sim alike; no file holds inf or NaN" {
  sed 's|^sensor /World/Imu imu crate 0 0 0.25|sensor /World/Imu imu crate 1.5e308 1.5e308 0.25|' room.rscene > far.rscene
  run -1 --separate-stderr "$BIN/rscene-validate" far.rscene
  [[ ${lines[0]} == "far.rscene:10:29: error: sensor '/World/Imu': position is more than 1e+12 m from its frame's origin [RS7021]" ]]
  run -2 --separate-stderr "$SIM" --duration 1 --sensors out -o /dev/null far.rscene
  [[ ${stderr_lines[0]} == "far.rscene:10:29: error: sensor '/World/Imu': position is more than 1e+12 m from its frame's origin [RS7021]" ]]
  [ ! -e out ]
}

@test "--trajectory or -o inside a LiDAR's scan folder is refused before any work; no scan replaced" {
  mkdir -p out/World+Lidar
  run -2 --separate-stderr "$SIM" --duration 1 --sensors out --trajectory out/World+Lidar/scan_000000.pcd -o /dev/null room.rscene
  [[ $stderr == *"rscene-sim: error: --trajectory 'out/World+Lidar/scan_000000.pcd' is inside the scan folder 'out/World+Lidar' of LiDAR '/World/Lidar', which holds its scans and is replaced as a whole"* ]]
  [ -z "$(ls out/World+Lidar)" ]
  run -2 --separate-stderr "$SIM" --duration 1 --sensors out -o out/World+Lidar/x.rscene room.rscene
  [[ $stderr == *"-o 'out/World+Lidar/x.rscene' is inside the scan folder"* ]]
  [ -z "$(ls out/World+Lidar)" ]
  # beside the folder is fine
  run -0 "$SIM" --duration 1 --sensors out --trajectory out/traj.jsonl -o /dev/null room.rscene
  [ -s out/traj.jsonl ]
}

@test "-o or --trajectory inside a LiDAR folder --sensors has not made yet: refused as that, nothing left" {
  run -2 --separate-stderr "$SIM" --duration 1 --sensors out -o out/World+Lidar/x.rscene room.rscene
  [ "$stderr" = "rscene-sim: error: -o 'out/World+Lidar/x.rscene' is inside the scan folder 'out/World+Lidar' of LiDAR '/World/Lidar', which holds its scans and is replaced as a whole: give a path outside --sensors' LiDAR folders" ]
  [ ! -e out ]
  run -2 --separate-stderr "$SIM" --duration 1 --sensors out --trajectory ./out/World+Lidar -o /dev/null room.rscene
  [[ $stderr == "rscene-sim: error: --trajectory './out/World+Lidar' names the scan folder 'out/World+Lidar' of LiDAR"* ]]
  [ ! -e out ]
}

# The LiDAR's files: name, size and checksum, for comparing two states.
scans_state() { (cd "$1" && ls -A | while read -r f; do echo "$f $(cksum < "$f")"; done) }

@test "a re-run stopped by a signal leaves the earlier run's scans byte for byte, and no temporary folder" {
  run -0 "$SIM" --duration 1 --sensors out -o /dev/null room.rscene
  before=$(scans_state out/World+Lidar)
  [ "$(ls out/World+Lidar | grep -c '^scan_')" -eq 6 ]
  for sig in TERM INT; do
    run timeout --preserve-status -s "$sig" 1 "$SIM" --duration 100000 --sensors out -o /dev/null room.rscene
    [ "$status" -eq $((128 + $(kill -l "$sig"))) ]
    [ "$(scans_state out/World+Lidar)" = "$before" ]
    [ -z "$(ls -A out | grep tmp)" ]
  done
}

@test "a shorter re-run replaces the whole scan folder: no scan of the earlier run stays" {
  run -0 "$SIM" --duration 1 --sensors out -o /dev/null room.rscene
  [ -f out/World+Lidar/scan_000005.pcd ]
  chmod 0750 out/World+Lidar
  run -0 "$SIM" --duration 0.2 --sensors out -o /dev/null room.rscene
  [ "$(ls -A out/World+Lidar)" = "$(printf '%s\n' scan_000000.pcd scan_000001.pcd scans.csv)" ]
  [ "$(wc -l < out/World+Lidar/scans.csv)" -eq 3 ]
  [ "$(stat -c %a out/World+Lidar)" = 750 ]  # the folder's mode is kept
  [ "$(ls -A out)" = "$(printf '%s\n' World+Imu.csv World+Lidar)" ]  # no temporary folder
}

@test "a re-run that fails leaves the earlier scans as they were and no temporary folder" {
  run -0 "$SIM" --duration 1 --sensors out -o /dev/null room.rscene
  before=$(scans_state out/World+Lidar)
  { room; echo "object /World/Heavy box 0 0 1 1 0 0 0 0.4 0.4 0.4 0.5 1 2.2250738585072014e-308 default engine_default false true false - dynamic true 1 18446744073709551615"; } > heavy.rscene
  run -2 --separate-stderr "$SIM" --steps 2000 --sensors out -o /dev/null heavy.rscene
  [[ $stderr == *"[RS7024]"* ]]
  [[ $stderr != *"write cancelled"* ]]  # the failure is the one line about it
  [ "$(scans_state out/World+Lidar)" = "$before" ]
  [ "$(ls -A out)" = "$(printf '%s\n' World+Imu.csv World+Lidar)" ]
}

@test "a link, a file or a folder of other files where a LiDAR's scan folder goes is refused before any work" {
  mkdir -p out elsewhere
  ln -s ../elsewhere out/World+Lidar
  run -2 --separate-stderr "$SIM" --duration 1 --sensors out -o /dev/null room.rscene
  [[ $stderr == "rscene-sim: error: out/World+Lidar: is a symbolic link; a LiDAR's scan folder is replaced as a whole"* ]]
  [ -z "$(ls -A elsewhere)" ] && [ -L out/World+Lidar ] && [ "$(ls -A out)" = World+Lidar ]
  rm out/World+Lidar && echo keep > out/World+Lidar
  run -2 --separate-stderr "$SIM" --duration 1 --sensors out -o /dev/null room.rscene
  [[ $stderr == "rscene-sim: error: out/World+Lidar: is in the way of the LiDAR's scan folder and is not a folder"* ]]
  [ "$(cat out/World+Lidar)" = keep ]
  rm out/World+Lidar && mkdir out/World+Lidar && echo mine > out/World+Lidar/notes.txt
  run -2 --separate-stderr "$SIM" --duration 1 --sensors out -o /dev/null room.rscene
  [[ $stderr == "rscene-sim: error: out/World+Lidar: holds 'notes.txt', which is not a scan rscene-sim wrote"* ]]
  [ "$(ls -A out/World+Lidar)" = notes.txt ] && [ "$(ls -A out)" = World+Lidar ]
}

@test "LiDAR scans estimated past 1 GiB: a warning with the size before the first step, at lidarSamples (RS7094)" {
  # 64 x 2048 rays, 5 Hz over 200 s: 1001 scans of up to 1.5 MiB.  The
  # heavy body stops the run at its first step, so little is written.
  sed 's|lidarChannels=1 lidarSamples=4 lidarVerticalFov=0|lidarChannels=64 lidarSamples=2048 lidarVerticalFov=30|' room.rscene > big.rscene
  echo "object /World/Heavy box 0 0 1 1 0 0 0 0.4 0.4 0.4 0.5 1 2.2250738585072014e-308 default engine_default false true false - dynamic true 1 18446744073709551615" >> big.rscene
  run -2 --separate-stderr "$SIM" --duration 200 --sensors out -o /dev/null big.rscene
  [[ ${stderr_lines[0]} == "big.rscene:11:"*": warning: the LiDAR scans of this run would write up to 1.47 GiB, more than 1 GiB: LiDAR '/World/Lidar' takes 131072 points a scan x 12 bytes (binary PCD) = 1.5 MiB a scan, x 1001 scans = 1.47 GiB (every ray a return) [RS7094]" ]]
  [[ $stderr == *"[RS7024]"* ]]
  [ ! -e out ]
  # As text, about 32 bytes a point; the hint names the binary encoding.
  run -2 --separate-stderr "$SIM" --duration 200 --sensors out --pcd-encoding ascii -o /dev/null big.rscene
  [[ ${stderr_lines[0]} == *"would write up to 3.91 GiB"*"about 32 bytes (ascii PCD)"*"[RS7094]" ]]
  [[ $stderr == *"hint: "*"--pcd-encoding binary writes 12 bytes a point"* ]]
  # 10 s: 51 scans, 77 MiB: no warning.
  run -2 --separate-stderr "$SIM" --duration 10 --sensors out -o /dev/null big.rscene
  [[ $stderr != *RS7094* ]]
}
