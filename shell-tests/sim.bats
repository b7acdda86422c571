#!/usr/bin/env bats
# End-to-end tests of rscene-sim: every flag, exit statuses, exact
# messages for bad physics input, determinism and the batch recipe.

load helpers
SIM="$BIN/rscene-sim"

setup() {
  needs_tools rscene-sim
  in_workdir
  cp "$DATA"/sim_*.rscene .
}

@test "--help lists every option" {
  run -0 "$SIM" --help
  for opt in --output --duration --steps --trajectory --every --trajectory-format --until-rest --report --pd-gains \
             --sensors --imu-format --pcd-encoding --stdin-filename --base-dir --version; do
    [[ $output == *"$opt"* ]] || { echo "missing $opt"; false; }
  done
}

@test "--version prints the tool name" {
  run -0 "$SIM" --version
  [[ $output == "rscene-sim "* ]]
}

@test "dropped bodies settle on the ground and are written back" {
  run -0 --separate-stderr "$SIM" --duration 2 sim_drop.rscene
  [ -z "$stderr" ]
  box=$(zof /World/Box <<<"$output")
  ball=$(zof /World/Ball <<<"$output")
  awk -v z="$box" 'BEGIN { exit !(z > 0.199 && z < 0.201) }'
  awk -v z="$ball" 'BEGIN { exit !(z > 0.099 && z < 0.101) }'
  # the static ground line is unchanged
  grep -qx 'object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615' <<<"$output"
}

@test "zero steps writes what rscene-fmt writes" {
  [ -x "$BIN/rscene-fmt" ] || skip "rscene-fmt not built"
  "$SIM" --steps 0 sim_drop.rscene > a
  "$BIN/rscene-fmt" sim_drop.rscene > b
  cmp a b
}

@test "output is byte-identical run after run" {
  "$SIM" --duration 1 sim_drop.rscene > a
  "$SIM" --duration 1 sim_drop.rscene > b
  cmp a b
}

@test "reads stdin and writes -o atomically" {
  run -0 "$SIM" --steps 100 -o out.rscene --stdin-filename sim_drop.rscene < sim_drop.rscene
  [ -z "$output" ]
  "$SIM" --steps 100 sim_drop.rscene | cmp - out.rscene
}

@test "--trajectory writes JSON Lines every K steps" {
  run -0 "$SIM" --steps 10 --trajectory t.jsonl --every 5 sim_drop.rscene
  [ "$(wc -l < t.jsonl)" -eq 6 ]  # t = 0, 5, 10 for two bodies
  jq -e 'has("time") and has("path") and (.position|length)==3 and (.quaternion|length)==4
         and (.linearVelocity|length)==3 and (.angularVelocity|length)==3' t.jsonl > /dev/null
  [ "$(head -1 t.jsonl | jq -r .path)" = /World/Box ]
}

@test "--trajectory-format csv has a header and one row per body and sample" {
  run -0 "$SIM" --steps 4 --trajectory t.csv --every 2 --trajectory-format csv sim_drop.rscene
  [ "$(head -1 t.csv)" = "time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,points" ]
  [ "$(wc -l < t.csv)" -eq 7 ]
  run -2 "$SIM" --trajectory-format xml sim_drop.rscene
}

@test "--until-rest stops early and --report says so" {
  run -0 --separate-stderr "$SIM" --duration 10 --until-rest --report sim_drop.rscene
  jq -e '.atRest == true and .steps < 10000 and .bodies == 2 and has("realtimeFactor")
         and has("stepsPerSecond") and has("contactsPerStep") and has("wallTime")
         and has("parseTime") and has("buildTime") and has("writeTime")
         and (.stepCpuTime | type == "number" and . >= 0)' <<<"$stderr"
}

@test "--duration and --steps exclude each other" {
  run -2 "$SIM" --duration 1 --steps 3 sim_drop.rscene
  [[ $output == *"--duration excludes --steps"* ]]
}

@test "a dynamic body without mass is refused" {
  run -2 --separate-stderr "$SIM" sim_bad_mass.rscene
  [ -z "$output" ]
  [ "${stderr_lines[0]}" = "sim_bad_mass.rscene:2:49: error: dynamic body '/World/Box' needs a mass > 0 [RS4008]" ]
}

@test "a missing mesh is refused with its resolved path; --base-dir moves it" {
  run -2 --separate-stderr "$SIM" sim_missing_mesh.rscene
  [ "${stderr_lines[0]}" = "sim_missing_mesh.rscene:2:93: error: mesh file 'meshes/rock.obj' does not exist [RS5001]" ]
  run -2 --separate-stderr "$SIM" --base-dir /nowhere sim_missing_mesh.rscene
  [[ ${stderr_lines[0]} == *"mesh file '/nowhere/meshes/rock.obj' does not exist [RS5001]" ]]
}

@test "non-finite numbers are refused, not simulated" {
  run -2 --separate-stderr "$SIM" --stdin-filename nan.rscene <<<$'raisim_engine_scene 1\ngravity 0 0 nan'
  [ "${stderr_lines[0]}" = "nan.rscene:2:13: error: number 'nan' is not finite [RS2002]" ]  # validate's words
}

@test "a sensor and an empty granular bed are kept as written, with no warning" {
  run -0 --separate-stderr "$SIM" --steps 1 sim_unsupported.rscene
  [ "$stderr" = "" ]
  grep -q '^sensor /World/Imu imu /World/Ball 0 0 0 1 0 0 0$' <<<"$output"
  grep -q '^granular /World/Sand sand' <<<"$output"
}

@test "examples/robot_cell simulates, its wire to the articulated robot too" {
  run -0 --separate-stderr "$SIM" --steps 2 "$ROOT/examples/robot_cell.rscene"
  [[ "$stderr" != *"RS7011"* ]]
  grep -q '^wire /World/Tether stiff articulated_quadruped compound_cart 2' <<<"$output"
  # the README's batch recipe no longer halts on it
  if command -v parallel > /dev/null; then
    mkdir out
    run -0 parallel --halt soon,fail=1 "$SIM" --steps 2 -o out/{/} {} ::: "$ROOT"/examples/*.rscene
  fi
}

@test "a zero time step is refused with rscene-validate's code" {
  printf 'raisim_engine_scene 2\ntime_step 0\n' >dt.rscene
  run -2 --separate-stderr "$SIM" dt.rscene
  [ "${stderr_lines[0]}" = "dt.rscene:2:11: error: time step must be positive [RS7008]" ]
}

@test "a failed run leaves no output file" {
  run -2 "$SIM" -o out.rscene sim_bad_mass.rscene
  [ ! -e out.rscene ]
}

@test "batch: GNU parallel runs many scenes, one output each" {
  command -v parallel > /dev/null || skip "GNU parallel not installed"
  mkdir in out
  for i in 1 2 3 4; do cp sim_drop.rscene in/s$i.rscene; done
  run -0 parallel --halt soon,fail=1 "$SIM" --duration 0.5 -o out/{/} {} ::: in/*.rscene
  [ "$(ls out | wc -l)" -eq 4 ]
  cmp out/s1.rscene out/s4.rscene
  # one bad scene fails the batch
  cp sim_bad_mass.rscene in/bad.rscene
  run parallel --halt soon,fail=1 "$SIM" -o out/{/} {} ::: in/*.rscene
  [ "$status" -ne 0 ]
}

# --- missing assets and bodies leaving the world ---

@test "--allow-missing-assets leaves out a body whose mesh is missing and simulates the rest" {
  run -0 "$SIM" --help
  [[ $output == *"--allow-missing-assets"* ]]
  { cat sim_missing_mesh.rscene
    echo 'object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615'
    echo 'object /World/Box box 3 0 1 1 0 0 0 0.4 0.4 0.4 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615'
  } > partial.rscene
  run -2 "$SIM" --steps 10 partial.rscene
  run -0 --separate-stderr "$SIM" --allow-missing-assets --duration 1 partial.rscene
  [ "${stderr_lines[0]}" = "partial.rscene:2:93: warning: mesh file 'meshes/rock.obj' does not exist; body '/World/Rock' is not simulated [RS5001]" ]
  # the left-out body's record is written unchanged; the box fell onto the ground
  grep -qxF "$(sed -n 2p partial.rscene)" <<<"$output"
  box=$(zof /World/Box <<<"$output")
  awk -v z="$box" 'BEGIN { exit !(z > 0.19 && z < 0.21) }'
}

@test "--allow-missing-assets: an unreadable mesh (a device, a non-mesh) is left out too" {
  sed 's|meshes/rock.obj|/dev/zero|' sim_missing_mesh.rscene > dev.rscene
  run -0 --separate-stderr "$SIM" --allow-missing-assets --steps 5 dev.rscene
  [[ ${stderr_lines[0]} == "dev.rscene:2:"*": warning: mesh file '/dev/zero' is not a regular file; body '/World/Rock' is not simulated [RS5001]" ]]
  run -2 --separate-stderr timeout 10 "$SIM" --steps 5 dev.rscene
  [[ $stderr == *"mesh file '/dev/zero' is a device, not a regular file [RS5001]"* ]]
}

@test "--allow-missing-assets leaves out a robot whose file is missing, as rscene-render does" {
  # The robot cell without its robots/ folder: the format's own situation
  # (a scene whose URDF is not shipped).
  cp "$ROOT/examples/robot_cell.rscene" cell.rscene
  run -2 --separate-stderr "$SIM" --steps 5 cell.rscene
  [[ ${stderr_lines[0]} == "cell.rscene:5:51: error: robot file 'robots/quadruped/quadruped.urdf' does not exist [RS5001]" ]]
  run -0 --separate-stderr "$SIM" --allow-missing-assets --steps 5 --sensors sensors cell.rscene
  [ "${stderr_lines[0]}" = "cell.rscene:5:51: warning: robot file 'robots/quadruped/quadruped.urdf' does not exist; articulated system '/World/Robot' is left out (--allow-missing-assets) [RS5001]" ]
  [[ $stderr == *"cell.rscene:13:29: warning: sensor '/World/Robot/Imu' is not used: 'articulated_quadruped' was left out for its missing robot file [RS5001]"* ]]
  [[ $stderr == *"cell.rscene:14:26: warning: wire '/World/Tether' is not attached: 'articulated_quadruped' was left out for its missing robot file [RS5001]"* ]]
  # nothing recorded for the robot's sensors; its record written back as it was
  [ -z "$(ls sensors 2>/dev/null)" ]
  grep -qxF "$("$BIN/rscene-fmt" cell.rscene | grep '^articulated ')" <<<"$output"
  # rscene-render leaves out the same things with the same words
  grep -v '^ ' <<<"$stderr" > sim.err
  run -0 --separate-stderr "$BIN/rscene-render" --allow-missing-assets --width 64 --height 48 -o cell.png cell.rscene
  diff sim.err <(grep -v '^ ' <<<"$stderr" | grep -v '^rscene-render:')
  # a view riding on the robot left out is no view, even when asked for by name
  run -2 --separate-stderr "$BIN/rscene-render" --allow-missing-assets --camera /World/Robot/HeadCam -o cam.png cell.rscene
  [[ $stderr == *"/World/Robot/HeadCam"* ]]
  [ ! -e cam.png ]
}

@test "--allow-missing-assets: a left-out robot's IK targets and --pd-gains joints are warnings, not silence or a usage error" {
  cp "$ROOT/examples/robot_cell.rscene" cell.rscene
  echo 'articulated_ik /World/Robot LF_FOOT 0.3,0.2,0.05' >> cell.rscene
  run -0 --separate-stderr "$SIM" --allow-missing-assets --steps 5 --pd-gains LF_KFE=50,1 cell.rscene
  [[ $stderr == *"cell.rscene:20:29: warning: IK target of frame 'LF_FOOT' is not solved: '/World/Robot' was left out for its missing robot file [RS5001]"* ]]
  [[ $stderr == *"warning: --pd-gains names joint 'LF_KFE', which no articulated system loaded has as a movable joint; its gains are not used (1 left out by --allow-missing-assets) [RS5001]"* ]]
  # without a robot left out, an unknown joint stays a usage error
  run -2 --separate-stderr "$SIM" --steps 5 --pd-gains NO_SUCH=50,1 "$ROOT/examples/robot_cell.rscene"
  [[ $stderr == *"--pd-gains names joint 'NO_SUCH', which no articulated system has as a movable joint"* ]]
}

@test "--allow-missing-assets drops a robot's missing or unreadable collision mesh with a warning" {
  mkdir -p robots/quadruped
  cp "$ROOT/examples/robot_cell.rscene" cell.rscene
  # the base's collision box becomes a mesh file that is not there
  awk '!done && /<box size="0.5 0.22 0.12"\/>/ && seen { sub(/<box size="0.5 0.22 0.12"\/>/, "<mesh filename=\"gone.obj\"/>"); done = 1 }
       /<collision>/ { seen = 1 } { print }' "$ROOT/examples/robots/quadruped/quadruped.urdf" > robots/quadruped/quadruped.urdf
  grep -q 'gone.obj' robots/quadruped/quadruped.urdf
  run -2 --separate-stderr "$SIM" --steps 5 cell.rscene
  [[ $stderr == *"robots/quadruped/quadruped.urdf:41: error: collision mesh 'gone.obj' not found"*"[RS5001]"* ]]
  run -0 --separate-stderr "$SIM" --allow-missing-assets --steps 5 cell.rscene
  [[ ${stderr_lines[0]} == "robots/quadruped/quadruped.urdf:41: warning: collision mesh 'gone.obj' not found"*"; the <collision> is skipped (--allow-missing-assets) [RS5001]" ]]
  run -0 --separate-stderr "$BIN/rscene-render" --allow-missing-assets --width 64 --height 48 -o cell.png cell.rscene
  [[ ${stderr_lines[0]} == "robots/quadruped/quadruped.urdf:41: warning: collision mesh 'gone.obj' not found"*"[RS5001]" ]]
  # a file that is there but no mesh: sim drops it too (render draws no collisions)
  head -c 3000 /dev/urandom > robots/quadruped/gone.obj
  run -2 --separate-stderr "$SIM" --steps 5 cell.rscene
  [[ $stderr == *"cell.rscene:8:26: error: body '/World/Robot': link 'base': cannot read mesh 'robots/quadruped/gone.obj'"*"[RS7007]"* ]]
  # validate --check-files says the same, where sim says it
  first=$(grep -m1 'error:' <<<"$stderr")
  run -1 "$BIN/rscene-validate" --check-files cell.rscene
  [[ $output == *"$first"* ]]
  run -0 --separate-stderr "$SIM" --allow-missing-assets --steps 5 cell.rscene
  [[ ${stderr_lines[0]} == "cell.rscene:8:26: warning: articulated system '/World/Robot': cannot read mesh 'robots/quadruped/gone.obj': "*"; that collision is left out [RS7007]" ]]
}

@test "a wire end names a body by id first, then by path: the scene model's one rule" {
  # /World/A has the id "/World/B"; the wire's "/World/B" is that id, so A
  # hangs from the wire's world end and the body whose path is /World/B falls.
  cat > ends.rscene <<'SCENE'
raisim_engine_scene 1
time_step 0.0025
object /World/A sphere 0 0 0.5 1 0 0 0 1 1 1 0.1 0 1 default - false true false - dynamic true 1 18446744073709551615 id=/World/B
object /World/B sphere 3 0 0.5 1 0 0 0 1 1 1 0.1 0 1 default - false true false - dynamic true 1 18446744073709551615 id=object_b
wire /World/W stiff - /World/B 0.2 id=w localPositionA=0,0,2
SCENE
  run -0 "$SIM" --steps 400 ends.rscene
  a=$(zof /World/A <<<"$output") b=$(zof /World/B <<<"$output")
  awk -v a="$a" -v b="$b" 'BEGIN { exit !(a > 1.79 && a < 1.81 && b < -4) }'
}

@test "a body that falls off the edge leaves the world and --until-rest still finishes" {
  cat > edge.rscene <<'SCENE'
raisim_engine_scene 1
object /World/Platform box 0 0 0 1 0 0 0 2 2 1 0.5 1 1 default engine_default false true false - static true 1 18446744073709551615
object /World/On box 0 0 0.7 1 0 0 0 0.4 0.4 0.4 0.5 1 1 default engine_default false true false - dynamic true 1 18446744073709551615
object /World/Off box 3 0 0.7 1 0 0 0 0.4 0.4 0.4 0.5 1 1 default engine_default false true false - dynamic true 1 18446744073709551615
SCENE
  run -0 --separate-stderr "$SIM" --duration 30 --until-rest --report edge.rscene
  [[ ${stderr_lines[0]} == "edge.rscene:4:1: warning: dynamic body '/World/Off' left the world at step "*" s): fell below z = -10.5 (10 m under the lowest static geometry); no longer simulated, written at its last pose [RS7012]" ]]
  jq -e '.leftWorld == 1 and .atRest == true and .simulatedTime < 5' <<<"${stderr_lines[-1]}"
  # written at the pose it had when it left: about 10 m under the platform
  off=$(zof /World/Off <<<"$output")
  awk -v z="$off" 'BEGIN { exit !(z < -10.5 && z > -10.7) }'
}

@test "corpus: the warehouse and the city simulate with --allow-missing-assets" {
  needs_shared corpus
  for scene in rayrai_warehouse rayrai_city; do
    run -2 "$SIM" --steps 1 "$CORPUS/$scene.rscene"
    run -0 --separate-stderr "$SIM" --allow-missing-assets --duration 1 --report -o out.rscene "$CORPUS/$scene.rscene"
    [[ $stderr == *"does not exist; bodies '"*"' and "*" others are not simulated [RS5001]"* ]]
    jq -e '.steps > 0' <<<"${stderr_lines[-1]}"
    [ -s out.rscene ]
  done
}

@test "--duration 2s says what a duration looks like; counts must be whole numbers" {
  run -2 --separate-stderr "$SIM" --duration 2s sim_drop.rscene
  [ "${stderr_lines[0]}" = "rscene-sim: error: --duration: expected seconds as a plain number >= 0 (e.g. 2 or 0.5), not '2s'" ]
  run -2 --separate-stderr "$SIM" --duration=-1 sim_drop.rscene
  [ "${stderr_lines[0]}" = "rscene-sim: error: --duration: expected seconds as a plain number >= 0 (e.g. 2 or 0.5), not '-1'" ]
  run -2 --separate-stderr "$SIM" --steps 2.5 sim_drop.rscene
  [ "${stderr_lines[0]}" = "rscene-sim: error: --steps: expected a whole number >= 0, not '2.5'" ]
  run -2 --separate-stderr "$SIM" --every 0 sim_drop.rscene
  [ "${stderr_lines[0]}" = "rscene-sim: error: --every: expected a whole number >= 1, not '0'" ]
  run -2 --separate-stderr "$SIM" --duraton 2 sim_drop.rscene
  [ "${stderr_lines[0]}" = "rscene-sim: error: unknown option '--duraton'; did you mean '--duration'?" ]
  # the forms it takes
  run -0 "$SIM" --duration 0.5 sim_drop.rscene
  run -0 "$SIM" --duration 1e-2 sim_drop.rscene
}

@test "trajectory times are the step count times the step as written: 1.4, not 1.4000000000000001" {
  sed 's/^time_step .*/time_step 0.1/' sim_drop.rscene > tenth.rscene
  run -0 "$SIM" --steps 20 --trajectory t.csv --trajectory-format csv tenth.rscene
  [ "$(cut -d, -f1 t.csv | uniq | tr '\n' ' ')" = "time 0 0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9 1 1.1 1.2 1.3 1.4 1.5 1.6 1.7 1.8 1.9 2 " ]
  run -0 "$SIM" --steps 3 --trajectory t.jsonl tenth.rscene
  grep -q '^{"time":0.3,' t.jsonl
}

# --- Resource limits (README "Resource limits", rscene-sim(1) LIMITS) ---
# Each reproducer runs under a time and address-space bound (bounded,
# helpers.bash), so a regression fails here instead of hanging or swapping
# the test machine.

# A scene of: header, time_step $1, then object lines from stdin.
scene() { printf 'raisim_engine_scene 1\ntime_step %s\n' "$1"; cat; }
# An object line: path, position, orientation, scale, mass, body mode.
obj() {
  echo "object $1 box $2 $3 $4 0.5 1 $5 default engine_default false true false - $6 true 1 18446744073709551615"
}
GROUND='object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615'

@test "limits: a dynamic mass of 4.9e-324 is refused up front (RS7020), nothing written" {
  { echo "$GROUND"; obj /World/Box "0 0 1" "1 0 0 0" "0.4 0.4 0.4" 4.9e-324 dynamic; } | scene 0.001 > tiny.rscene
  run -2 --separate-stderr bounded 500000 10 "$SIM" -o out.rscene tiny.rscene
  [ "${stderr_lines[0]}" = "tiny.rscene:4:55: error: dynamic body '/World/Box' has mass 4.94066e-324, which cannot be simulated [RS7020]" ]
  [ ! -e out.rscene ]
  # A light body simulates ...
  { echo "$GROUND"; obj /World/Box "0 0 1" "1 0 0 0" "0.4 0.4 0.4" 1e-300 dynamic; } | scene 0.001 > light.rscene
  run -0 bounded 500000 10 "$SIM" --steps 100 light.rscene
  [[ $output != *nan* ]]
  # ... and one whose inertia underflows passes the up-front check but is
  # stopped at its first step by the state check, with nothing written.
  { echo "$GROUND"; obj /World/Box "0 0 1" "1 0 0 0" "0.4 0.4 0.4" 2.2250738585072014e-308 dynamic; } | scene 0.001 > normal.rscene
  run -2 --separate-stderr bounded 500000 10 "$SIM" --steps 10 normal.rscene
  [[ ${stderr_lines[0]} == "normal.rscene:4:1: error: the angular velocity of body '/World/Box' is no longer finite at step 1 "*"[RS7024]" ]]
  [ -z "$output" ]
}

@test "limits: orientation 1e308 1e308 0 0 is refused (RS7021), even with --steps 0" {
  { echo "$GROUND"; obj /World/Box "0 0 1" "1e308 1e308 0 0" "0.4 0.4 0.4" 2 dynamic; } | scene 0.001 > q.rscene
  run -2 --separate-stderr bounded 500000 10 "$SIM" --steps 0 q.rscene
  [ "${stderr_lines[0]}" = "q.rscene:4:29: error: body '/World/Box': orientation does not normalise to a unit quaternion [RS7021]" ]
  [ -z "$output" ]
}

@test "limits: time_step 1e-12 and 5e-324 are refused at the time_step (RS7022)" {
  echo "$GROUND" | scene 1e-12 > fine.rscene
  run -2 --separate-stderr bounded 500000 10 "$SIM" fine.rscene
  [ "${stderr_lines[0]}" = "fine.rscene:2:11: error: time_step 1e-12 is below the smallest simulated step, 1e-09 s [RS7022]" ]
  echo "$GROUND" | scene 5e-324 > denormal.rscene
  run -2 --separate-stderr bounded 500000 10 "$SIM" denormal.rscene
  [ "${stderr_lines[0]}" = "denormal.rscene:2:11: error: time_step 4.94066e-324 is below the smallest simulated step, 1e-09 s [RS7022]" ]
}

@test "limits: numbers that would overflow are refused by sim and validate alike (RS7020 RS7022 RS7026 RS7021)" {
  # Issue 10: each of these used to pass validate and stop sim with RS7024.
  VALIDATE=$RSCENE_BIN/rscene-validate
  { echo "$GROUND"; obj /World/Box "0 0 1" "1 0 0 0" "0.4 0.4 0.4" 1e300 dynamic; } | scene 0.001 > heavy.rscene
  echo "$GROUND" | scene 1e300 > longstep.rscene
  { echo "$GROUND"; obj /World/A "0 0 1" "1 0 0 0" "0.4 0.4 0.4" 1 dynamic; obj /World/B "0 0 3" "1 0 0 0" "0.4 0.4 0.4" 1 dynamic
    echo 'wire /World/W stiff /World/A /World/B 1 localPositionA=1e308,0,0'; } | scene 0.001 > wire.rscene
  { echo 'scene_graph inheritedTransforms=true'; echo 'compound /World/C 1e308 0 0 1 0 0 0 1 1 1 1 dynamic true true id=c'
    echo 'compound_child /World/C box 0 0 0 1 0 0 0 1 1 1'
    echo 'object /World/A box 1e308 0 1 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic true 1 1 parentGroupId=c'
  } | scene 0.001 > chain.rscene
  for f in heavy longstep wire chain; do
    run -2 --separate-stderr bounded 500000 10 "$SIM" --steps 10 -o out.rscene $f.rscene
    sim=${stderr_lines[0]}
    [ ! -e out.rscene ]
    run -1 --separate-stderr "$VALIDATE" $f.rscene
    [ "${lines[0]}" = "$sim" ]
  done
  [[ $sim == "chain.rscene:4:19: error: compound '/World/C': position is more than 1e+12 m from its frame's origin [RS7021]" ]]
  run -1 --separate-stderr "$VALIDATE" heavy.rscene
  [[ ${lines[0]} == *"has mass 1e+300, which cannot be simulated [RS7020]" ]]
  run -1 --separate-stderr "$VALIDATE" longstep.rscene
  [[ ${lines[0]} == *"time_step 1e+300 is above the longest simulated step, 1 s [RS7022]" ]]
  run -1 --separate-stderr "$VALIDATE" wire.rscene
  [[ ${lines[0]} == *"localPositionA of wire '/World/W' is larger than 1e+12 in magnitude [RS7026]" ]]
}

@test "limits: a body Bullet drops has left the world (RS7012), even with no static geometry" {
  # Bullet silently freezes a dynamic body whose swept bounds pass 10^6 m.
  { echo 'gravity 0 0 -1e12'; obj /World/Box "0 0 1" "1 0 0 0" "0.4 0.4 0.4" 1 dynamic; } | scene 1 > away.rscene
  run -0 --separate-stderr bounded 500000 10 "$SIM" --steps 5 -o out.rscene away.rscene
  [[ ${stderr_lines[0]} == "away.rscene:4:1: warning: dynamic body '/World/Box' left the world at step "*": moved more than 1e+06 m in one step (Bullet drops such a body); "*"[RS7012]" ]]
  grep -q '^object /World/Box box 0 0 -' out.rscene
  ! grep -qi 'nan\|inf' out.rscene
}

@test "limits: a parent cycle is refused by sim and render as validate refuses it (RS3017)" {
  { echo 'object /World/A box 0 0 1 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic true 1 1 id=a parentGroupId=b'
    echo 'object /World/B box 0 0 3 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic true 1 1 id=b parentGroupId=a'
  } | scene 0.001 > cycle.rscene
  # A scene with errors gets validate's list (its RS3007 warnings too).
  run -2 --separate-stderr bounded 500000 10 "$SIM" -o out.rscene cycle.rscene
  sim=$(grep -m1 ': error: ' <<<"$stderr")
  [[ $sim == "cycle.rscene:3:"*": error: node '/World/A' is its own ancestor [RS3017]" ]]
  [ ! -e out.rscene ]
  run -1 --separate-stderr "$RSCENE_BIN/rscene-validate" cycle.rscene
  [[ $output == *"$sim"* ]]
  run -2 --separate-stderr "$RSCENE_BIN/rscene-render" -o out.png cycle.rscene
  [ "$(grep -m1 ': error: ' <<<"$stderr")" = "$sim" ]
  [ ! -e out.png ]
}

@test "limits: --duration 1e300 and --steps past --max-steps are refused (RS7023); --max-steps raises the cap" {
  run -2 --separate-stderr bounded 500000 10 "$SIM" --duration 1e300 sim_drop.rscene
  [ "${stderr_lines[0]}" = "sim_drop.rscene:2:11: error: --duration 1e+300 at time_step 0.001 is 1e+303 steps, more than the limit of 10000000 steps [RS7023]" ]
  [ "${stderr_lines[3]}" = "  hint: raise the limit with --max-steps N, or simulate less time" ]
  run -2 --separate-stderr bounded 500000 10 "$SIM" --steps 10000001 sim_drop.rscene
  [[ ${stderr_lines[0]} == *"--steps 10000001, more than the limit of 10000000 steps [RS7023]" ]]
  run -2 --separate-stderr bounded 500000 10 "$SIM" --max-steps 99 --duration 0.1 sim_drop.rscene
  [[ ${stderr_lines[0]} == *"--duration 0.1 at time_step 0.001 is 100 steps, more than the limit of 99 steps [RS7023]" ]]
  run -0 --separate-stderr bounded 500000 10 "$SIM" --max-steps 100 --duration 0.1 --report sim_drop.rscene
  jq -e '.steps == 100' <<<"${stderr_lines[-1]}"
}

@test "limits: a state that stops being finite stops the run naming the body (RS7024); no scene, no trajectory" {
  # The smallest normal mass passes the up-front checks (its inverse is
  # finite); its inertia's inverse is not, which only stepping finds.
  { echo "$GROUND"; obj /World/Heavy "0 0 1" "1 0 0 0" "0.4 0.4 0.4" 2.2250738585072014e-308 dynamic; } | scene 0.001 > heavy.rscene
  echo old > t.jsonl
  run -2 --separate-stderr bounded 500000 10 "$SIM" --steps 2000 --trajectory t.jsonl -o out.rscene heavy.rscene
  [[ ${stderr_lines[0]} == "heavy.rscene:4:1: error: the "*" of body '/World/Heavy' is no longer finite at step "*"; the simulation stopped and nothing was written [RS7024]" ]]
  [[ $stderr != *"write cancelled"* ]]  # the failure is the one line about it (its hint follows)
  [ "${stderr_lines[-1]}" = "  hint: look for extreme masses, sizes, speeds or time steps" ]
  [ "$(cat t.jsonl)" = old ]
  [ ! -e out.rscene ]
  [ -z "$output" ]
  # Written through a pipe: the lines before the failure, none of them NaN or infinite.
  run -2 --separate-stderr bounded 500000 10 "$SIM" --steps 2000 --trajectory - heavy.rscene
  [[ $output != *nan* && $output != *inf* ]]
}

@test "limits: 12,000 co-located static boxes finish in bounded time and memory (no static pairs)" {
  for i in $(seq 12000); do obj "/World/S$i" "0 0 0" "1 0 0 0" "1 1 1" 1 static; done | scene 0.001 > statics.rscene
  # Before: the pair cache held 72 million static-static pairs (segfault, or
  # still running after 60 s at 1.8 GB).  Now about 4 s and 60 MB.
  run -0 --separate-stderr bounded 2000000 60 "$SIM" --steps 1 --report -o out.rscene statics.rscene
  jq -e '.steps == 1 and .contactsPerStep == 0' <<<"${stderr_lines[-1]}"
  [ -s out.rscene ]
}

@test "limits: --max-pairs stops co-located dynamic bodies (RS7025); 0 lifts the cap" {
  for i in $(seq 100); do obj "/World/D$i" "0 0 0" "1 0 0 0" "0.4 0.4 0.4" 1 dynamic; done | scene 0.001 > pile.rscene
  run -2 --separate-stderr bounded 1000000 30 "$SIM" --steps 1 --max-pairs 1000 -o out.rscene pile.rscene
  # After the scene model's RS7013, one per body (99: each but the first
  # starts inside an earlier one), four lines each.
  [ "$(grep -c 'warning: .*\[RS7013\]$' <<<"$stderr")" -eq 99 ]
  [[ ${stderr_lines[396]} =~ ^pile\.rscene:[0-9]+:1:\ error:\ more\ than\ 1000\ overlapping\ body\ pairs\ at\ step\ 0,\ this\ body\ in\ one\ of\ them\;\ the\ simulation\ stopped\ and\ nothing\ was\ written\ \[RS7025\]$ ]]
  [[ ${stderr_lines[397]} == "  object /World/D"* ]]
  [ ! -e out.rscene ]
  run -0 bounded 1000000 30 "$SIM" --steps 1 --max-pairs 4950 pile.rscene
  run -0 bounded 1000000 30 "$SIM" --steps 1 --max-pairs 0 pile.rscene
  # 500 in one spot are 124,750 pairs, past the default cap: refused before
  # they cost 1 GB (before: 2,000 of them segfaulted at 3.8 GB).
  for i in $(seq 500); do obj "/World/D$i" "0 0 0" "1 0 0 0" "0.4 0.4 0.4" 1 dynamic; done | scene 0.001 > crowd.rscene
  run -2 --separate-stderr bounded 1000000 30 "$SIM" --steps 1 crowd.rscene
  [[ $stderr == *"more than 100000 overlapping body pairs at step 0"*"[RS7025]"* ]]
}

@test "limits: --trajectory is streamed: 200 bodies x 5,000 steps in 150 MB of address space" {
  for i in $(seq 200); do obj "/World/B$i" "$((2 * i)) 0 1" "1 0 0 0" "0.4 0.4 0.4" 1 dynamic; done | scene 0.001 > many.rscene
  # Held in memory, this trajectory (250 MB) did not fit.
  bounded 150000 60 "$SIM" --steps 5000 --trajectory /dev/stdout -o out.rscene many.rscene | wc -l > lines
  [ "$(cat lines)" = $((200 * 5001)) ]
  [ -s out.rscene ]
}

@test "limits: SIGINT while a trajectory streams: exit 130, the old trajectory kept, no temporary file" {
  command -v env > /dev/null && env --default-signal=INT true || skip "env --default-signal unsupported"
  echo keep > t.jsonl
  env --default-signal=INT "$SIM" --steps 5000000 --trajectory t.jsonl -o out.rscene sim_drop.rscene &
  pid=$!
  # Wait until the temporary trajectory file exists, so the signal lands mid-write.
  for _ in $(seq 100); do compgen -G '.t.jsonl.tmp*' > /dev/null && break; sleep 0.05; done
  compgen -G '.t.jsonl.tmp*' > /dev/null
  kill -INT "$pid"
  status=0
  wait "$pid" || status=$?
  [ "$status" -eq 130 ]
  [ "$(cat t.jsonl)" = keep ]
  [ ! -e out.rscene ]
  ! compgen -G '.t.jsonl.tmp*'
}

@test "a mesh that cannot be read is RS7007 at the record's field" {
  mkdir -p g
  echo "garbage, not a mesh" > g/bad.obj
  printf 'raisim_engine_scene 1\nobject /World/B mesh 0 0 1 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false g/bad.obj dynamic true 1 18446744073709551615\n' > mg.rscene
  run -2 --separate-stderr "$SIM" --steps 1 mg.rscene
  [[ ${stderr_lines[0]} == "mg.rscene:2:90: error: body '/World/B': cannot read mesh 'g/bad.obj': "*" [RS7007]" ]]
}

@test "50 000 findings print in linear time (each finding's source line is not searched from the top)" {
  { echo 'raisim_engine_scene 1'
    for i in $(seq 1 50000); do
      echo "object /World/b$i box 0 0 1 1 0 0 0 0 1 1 0.5 1 1 default engine_default false true false - dynamic true 1 18446744073709551615"
    done
  } > zero.rscene
  run -2 --separate-stderr bounded 1000000 20 "$SIM" --steps 1 zero.rscene
  [ "$(grep -c 'RS7003' <<<"$stderr")" -eq 50000 ]
  [[ ${stderr_lines[-4]} == "zero.rscene:50001:40: error: box with a zero or negative side "*"[RS7003]" ]]
}

@test "limits: validate, sim and render give one verdict on hostile values (code, line and column)" {
  # Each of these once passed one tool and failed another (issue 10 review).
  base='object /World/Box box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - dynamic true 1 18446744073709551615 id=object_box'
  b2='object /World/B2 sphere 0 0 3 1 0 0 0 1 1 1 0.2 0 1 default engine_default false true false - dynamic true 1 18446744073709551615 id=object_b2'
  cases=(
    "solver 2147483647 0 0.2 accurate|RS7027"
    "solver -2147483649 0 0.2 accurate|RS2003"
    "$b2
wire /World/W stiff object_box object_b2 -1|RS4011"
    "$b2
wire /World/W compliant object_box object_b2 1 stiffness=1e308|RS7027"
    "camera /World/C -8 -8 5 1 0 0 0 45 0.05 200 -1 10 rgb true|RS7028"
    "camera /World/C -8 -8 5 1 0 0 0 45 0.05 200 16385 10 rgb true|RS7028"
    "terrain_region /World/T 4294967297 2 100 100 0 0 0|RS2003"
    "terrain_region /World/T 3 3 10 10 0 0 0 heights=0,0,0,0,1e308,0,0,0,0|RS7026"
    "contact_material default default -1e308 0 0 0 0 0 0|RS7027"
  )
  for c in "${cases[@]}"; do
    { echo "$GROUND"; echo "$base"; echo "${c%|*}"; } | scene 0.001 > h.rscene
    run -2 --separate-stderr bounded 2000000 20 "$SIM" --steps 1 -o out.rscene h.rscene
    sim=${stderr_lines[0]}
    [[ $sim == *"error: "*"[${c##*|}]" ]]
    run -1 --separate-stderr "$RSCENE_BIN/rscene-validate" h.rscene
    [ "${sim%%: error*}" = "${lines[0]%%: error*}" ]  # same file:line:col
    [[ ${lines[0]} == *"[${c##*|}]" ]]
    run -2 --separate-stderr timeout 20 "$RSCENE_BIN/rscene-render" --width 32 --height 32 -o out.png h.rscene
    [ "${stderr_lines[0]}" = "$sim" ]
  done
  # An object parented to itself, and an orientation too short to have a direction.
  { echo "$GROUND"; echo "$base parentGroupId=object_box"; } | scene 0.001 > self.rscene
  { echo "$GROUND"; echo "${base/0.5 1 0 0 0/0.5 1e-13 1e-13 1e-13 1e-13}"; } | scene 0.001 > tiny.rscene
  for f in self tiny; do
    run -2 --separate-stderr bounded 2000000 20 "$SIM" --steps 1 -o out.rscene $f.rscene
    sim=$(grep -m1 ': error: ' <<<"$stderr")  # validate's list: its warnings may come first
    run -1 --separate-stderr "$RSCENE_BIN/rscene-validate" $f.rscene
    v=$(printf '%s\n' "${lines[@]}" | grep -m1 ': error: ')
    [ "${sim%%: error*}" = "${v%%: error*}" ]
    [ "${sim##*[}" = "${v##*[}" ]
  done
}

# generalizedCoordinate entry N (0-based) of the articulated record at PATH
# in scene text on stdin.
qof() {
  awk -v p="$1" -v n="$2" '$1 == "articulated" && $2 == p {
    for (i = 1; i <= NF; ++i) if ($i ~ /^generalizedCoordinate=/) { split(substr($i, 23), q, ","); print q[n + 1] } }'
}

@test "robots: without --pd-gains the quadruped of robot_cell collapses; with it, it stands" {
  run -0 --separate-stderr "$SIM" --duration 2 "$ROOT/examples/robot_cell.rscene"
  z=$(qof /World/Robot 2 <<<"$output")
  awk -v z="$z" 'BEGIN { exit !(z < 0.25) }'
  run -0 --separate-stderr "$SIM" --duration 2 --pd-gains 100,2 "$ROOT/examples/robot_cell.rscene"
  z=$(qof /World/Robot 2 <<<"$output")
  awk -v z="$z" 'BEGIN { exit !(z > 0.3582 && z < 0.4182) }'  # within 3 cm of 0.3882
  # the positional pose is q's base
  grep -q "^articulated /World/Robot quadruped_resource [^ ]* [^ ]* $z " <<<"$output"
}

@test "robots: --pd-gains per joint wins over the default; bad gains and unknown joints are usage errors" {
  # LF_KFE (entry 9, held at -1.2 against the load) sags less when stiffer
  run -0 --separate-stderr "$SIM" --duration 1 --pd-gains 100,2 "$ROOT/examples/robot_cell.rscene"
  a=$(qof /World/Robot 9 <<<"$output")
  run -0 --separate-stderr "$SIM" --duration 1 --pd-gains 100,2 --pd-gains LF_KFE=2000,40 "$ROOT/examples/robot_cell.rscene"
  b=$(qof /World/Robot 9 <<<"$output")
  awk -v a="$a" -v b="$b" 'function abs(x) { return x < 0 ? -x : x } BEGIN { exit !(abs(b + 1.2) < abs(a + 1.2) / 2) }'
  run -2 --separate-stderr "$SIM" --pd-gains 100 "$ROOT/examples/robot_cell.rscene"
  [ "$stderr" = "rscene-sim: error: --pd-gains '100': expected KP,KD or JOINT=KP,KD with finite gains >= 0" ]
  run -2 --separate-stderr "$SIM" --pd-gains=-1,2 "$ROOT/examples/robot_cell.rscene"
  [[ "$stderr" == *"--pd-gains '-1,2': expected KP,KD"* ]]
  run -2 --separate-stderr "$SIM" --pd-gains LF_KNEE=1,2 "$ROOT/examples/robot_cell.rscene"
  [[ "$stderr" == *"--pd-gains names joint 'LF_KNEE', which no articulated system has as a movable joint"* ]]
  [ -z "$output" ]
  run -2 --separate-stderr "$SIM" --pd-gains LF_KFF=1,2 "$ROOT/examples/robot_cell.rscene"
  [[ "$stderr" == *"'LF_KFF', which no articulated system has as a movable joint; did you mean 'LF_KFE'?" ]]
}

@test "robots: --steps 0 writes the record's state back as written" {
  run -0 --separate-stderr "$SIM" --steps 0 "$ROOT/examples/robot_cell.rscene"
  grep -q 'generalizedCoordinate=0,0,0.3882,1,0,0,0,0,0.6,-1.2,0,0.6,-1.2,0,-0.6,1.2,0,-0.6,1.2 generalizedVelocity=0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0$' <<<"$output"
}

@test "robots: the trajectory has the base and the joints by name (CSV columns q.NAME, u.NAME; JSON Lines objects)" {
  run -0 --separate-stderr "$SIM" --steps 3 --trajectory t.csv --trajectory-format csv --pd-gains 100,2 "$ROOT/examples/robot_cell.rscene"
  head -1 t.csv | grep -q '^time,path,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,q.LF_HAA,q.LF_HFE,q.LF_KFE,.*,q.RH_KFE,u.LF_HAA,.*,u.RH_KFE,points$'
  [ "$(head -1 t.csv | tr ',' '\n' | wc -l)" -eq $((15 + 24 + 1)) ]
  grep -q '^0,/World/Robot,0,0,0.3882,1,0,0,0,0,0,0,0,0,0,0,0.6,-1.2,0,0.6,-1.2,0,-0.6,1.2,0,-0.6,1.2,0,0,0,0,0,0,0,0,0,0,0,0,$' t.csv
  grep -q '^0,/World/Cart,.*,,,,$' t.csv  # a body row leaves the joint columns empty
  [ "$(grep -c '/World/Robot' t.csv)" -eq 4 ]
  run -0 --separate-stderr "$SIM" --steps 1 --trajectory t.jsonl "$ROOT/examples/robot_cell.rscene"
  command -v jq >/dev/null || skip "jq not installed"
  [ "$(jq -s 'map(select(.path == "/World/Robot"))[0].jointPositions.LF_KFE' t.jsonl)" = "-1.2" ]
  [ "$(jq -s 'map(select(.path == "/World/Robot"))[0].position[2]' t.jsonl)" = "0.3882" ]
  [ "$(jq -s 'map(select(.path == "/World/Robot"))[1].jointVelocities | length' t.jsonl)" = "12" ]
}

@test "robots: two runs are byte-identical" {
  "$SIM" --duration 1 --pd-gains 100,2 -o a.rscene --trajectory a.jsonl "$ROOT/examples/robot_cell.rscene"
  "$SIM" --duration 1 --pd-gains 100,2 -o b.rscene --trajectory b.jsonl "$ROOT/examples/robot_cell.rscene"
  cmp a.rscene b.rscene
  cmp a.jsonl b.jsonl
}

@test "robots: a wire's localIndexB past the robot's bodies is RS7046 at the wire, as validate says" {
  sed 's|^wire /World/Tether stiff articulated_quadruped compound_cart 2.0|wire /World/Tether stiff compound_cart articulated_quadruped 2.0 localIndexB=13|' \
    "$ROOT/examples/robot_cell.rscene" > w.rscene
  sed -i "s|robots/quadruped|$ROOT/examples/robots/quadruped|g" w.rscene
  run -2 --separate-stderr "$SIM" --steps 1 w.rscene
  [[ "$stderr" == *"w.rscene:14:"*": error: wire '/World/Tether': localIndexB 13 is not a body of articulated system 'articulated_quadruped' (it has 13, 0 to 12) [RS7046]"* ]]
  # at the localIndexB key, the column validate gives
  at=$(grep -o 'w.rscene:14:[0-9]*' <<<"$stderr" | head -1)
  run "$BIN/rscene-validate" --check-files w.rscene
  [[ $output == *"$at: error: "*"[RS7046]"* ]]
}

@test "robots: a mesh collision is a convex hull; convexifyCollisionMeshes=false says so (RS7051)" {
  cp "$DATA/render_assets/crate.obj" .
  cat > arm.urdf <<'URDF'
<robot name="arm">
  <link name="world"/>
  <link name="box">
    <inertial><origin xyz="0 0 -0.3"/><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename="crate.obj" scale="0.1 0.1 0.1"/></geometry></collision>
  </link>
  <joint name="hinge" type="revolute">
    <parent link="world"/><child link="box"/><origin xyz="0 0 1"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="10"/>
  </joint>
</robot>
URDF
  printf 'raisim_engine_scene 1\narticulated_resource arm_res Arm arm.urdf\narticulated /World/Arm arm_res 0 0 0 1 0 0 0 true true convexifyCollisionMeshes=false generalizedCoordinate=0.5\n' > arm.rscene
  run -0 --separate-stderr "$SIM" --steps 10 arm.rscene
  [[ "$stderr" == "arm.rscene:3:"*": warning: articulated system '/World/Arm': convexifyCollisionMeshes=false, but its mesh collisions are simulated as convex hulls (Bullet collides no triangle mesh on a moving body) [RS7051]"* ]]
  q=$(qof /World/Arm 0 <<<"$output")
  awk -v q="$q" 'BEGIN { exit !(q < 0.5) }'  # it swings down
  sed -i 's/ convexifyCollisionMeshes=false//' arm.rscene
  run -0 --separate-stderr "$SIM" --steps 10 arm.rscene
  [ -z "$stderr" ]
}

@test "robots: enabled articulated_ik targets are solved before stepping; --steps 0 writes the solved pose" {
  mkdir -p cell && cp -r "$ROOT/examples/robots" cell/
  grep -v '^wire\|^sensor' "$ROOT/examples/robot_cell.rscene" > cell/ik.rscene
  echo 'articulated_ik /World/Robot LF_FOOT 0.35,0.25,0.05 enabled=true' >> cell/ik.rscene
  run -0 --separate-stderr "$SIM" --steps 0 cell/ik.rscene
  # The left front leg moved (its three joints, entries 7..9); the others did not.
  [ "$(qof /World/Robot 7 <<<"$output")" != 0 ]
  [ "$(qof /World/Robot 10 <<<"$output")" = 0 ]
  [ "$(qof /World/Robot 11 <<<"$output")" = 0.6 ]
  # Unreachable: a warning naming the residual, the best pose kept, exit 0.
  sed 's/LF_FOOT 0.35,0.25,0.05/LF_FOOT 3,0,0/' cell/ik.rscene > cell/far.rscene
  run -0 --separate-stderr "$SIM" --steps 0 -o /dev/null cell/far.rscene
  ik=$(grep -n '^articulated_ik' cell/far.rscene | cut -d: -f1)
  [[ $stderr == *"far.rscene:$ik:"*": warning: IK target of frame 'LF_FOOT' not reached after 80 iterations: position residual "*" m (tolerance 0.001); the best pose found is used [RS7047]"* ]]
  # A frame the robot lacks: an error with a suggestion, as validate gives it.
  sed 's/LF_FOOT 0.35/LF_FOTO 0.35/' cell/ik.rscene > cell/bad.rscene
  run -2 --separate-stderr "$SIM" --steps 0 -o /dev/null cell/bad.rscene
  [[ $stderr == *"bad.rscene:$ik:29: error: frame 'LF_FOTO' is no joint or link of the model 'quadruped' [RS7044]"* ]]
  [[ $stderr == *"did you mean 'LF_FOOT'?"* ]]
  run -1 --separate-stderr "$RSCENE_BIN/rscene-validate" cell/bad.rscene
  [[ $output == *"bad.rscene:$ik:29: error: "*"[RS7044]"* ]]
}

@test "robots: hostile values stop the run with one verdict (diverged RS7024, too large RS7052, RS7035, RS7049, missing file at the scene)" {
  # Gains far too stiff for the step: diverged, nothing written (it used to
  # write the base 90 km up, exit 0).
  run -2 --separate-stderr "$SIM" --duration 2 --pd-gains 1e4,100 -o out.rscene "$ROOT/examples/robot_cell.rscene"
  [[ $stderr == *"error: the state of articulated system '/World/Robot' diverged at step "*"[RS7024]"* ]]
  [ ! -e out.rscene ]
  # 1,100 movable joints: refused up front (20,000 took 8 GB and crashed).
  awk 'BEGIN { print "<robot name=\"deep\"><link name=\"world\"/>"; p = "world"
    for (i = 0; i < 1100; ++i) { printf "<link name=\"l%d\"><inertial><mass value=\"0.1\"/><inertia ixx=\"0.001\" iyy=\"0.001\" izz=\"0.001\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n", i
      printf "<joint name=\"j%d\" type=\"revolute\"><origin xyz=\"0 0 0.05\"/><parent link=\"%s\"/><child link=\"l%d\"/><axis xyz=\"1 0 0\"/></joint>\n", i, p, i; p = "l" i }
    print "</robot>" }' > deep.urdf
  printf 'raisim_engine_scene 1\ntime_step 0.001\narticulated_resource res R deep.urdf\narticulated /World/R res 0 0 1 1 0 0 0 true true id=r\n' > deep.rscene
  run -2 --separate-stderr bounded 2000000 20 "$SIM" --steps 1 -o out.rscene deep.rscene
  [[ $stderr == *"deep.rscene:4:22: error: articulated system '/World/R' has 1101 bodies; rscene-sim simulates at most 1000 per robot [RS7052]"* ]]
  # An inertia of 1e308: validate --check-files and sim both refuse it, in the URDF.
  printf '<robot name="b"><link name="world"/><link name="l1"><inertial><mass value="1"/>\n<inertia ixx="1e308" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>\n<joint name="j1" type="revolute"><parent link="world"/><child link="l1"/><axis xyz="1 0 0"/></joint></robot>\n' > big.urdf
  sed 's/deep.urdf/big.urdf/' deep.rscene > big.rscene
  run -2 --separate-stderr "$SIM" --steps 1 -o out.rscene big.rscene
  [[ $stderr == *"big.urdf:1: error: link 'l1' has an inertia that is not finite, has a negative diagonal entry or is beyond 1e21 kg m^2 [RS7035]"* ]]
  run -1 --separate-stderr "$RSCENE_BIN/rscene-validate" --check-files big.rscene
  [[ $output == *"[RS7035]"* ]]
  # A coordinate of 1e308: refused, not written back.
  sed 's/true true id=r/true true id=r generalizedCoordinate=1e308/; s/big.urdf/big1.urdf/' big.rscene > q.rscene
  sed 's/ixx="1e308"/ixx="1"/' big.urdf > big1.urdf
  run -2 --separate-stderr "$SIM" --steps 1 -o out.rscene q.rscene
  [[ $stderr == *"q.rscene:4:"*": error: generalizedCoordinate holds a number beyond 1e12 in magnitude [RS7049]"* ]]
  # A robot file that is not there: at the scene's field, as render and validate say.
  sed 's/big.urdf/nope.urdf/' big.rscene > nope.rscene
  run -2 --separate-stderr "$SIM" --steps 1 -o out.rscene nope.rscene
  [ "${stderr_lines[0]}" = "nope.rscene:3:28: error: robot file 'nope.urdf' does not exist [RS5001]" ]
}

@test "a dynamic object's custom inertia changes how it tumbles; a zero moment is refused by sim and validate alike (RS7090)" {
  # A box dropped on an edge (tilted 30 degrees about x) tips over at a rate
  # set by its inertia: ten times the shape's Ixx lands it at another angle.
  base='object /World/Box box 0 0 0.6 0.9659258 0.2588190 0 0 0.5 0.5 0.5 0 0 1 default - false true false - dynamic true 1 18446744073709551615'
  { head -4 sim_drop.rscene; echo "$base"; } > shape.rscene
  { head -4 sim_drop.rscene; echo "$base customInertia=true inertiaDiagonal=0.4,0.4,0.4"; } > custom.rscene
  { head -4 sim_drop.rscene; echo "$base customInertia=true inertiaDiagonal=0.041666666666666664,0.041666666666666664,0.041666666666666664"; } > same.rscene
  pose() { "$SIM" --steps 300 "$1" | awk '$2 == "/World/Box" { print $4, $5, $6, $7, $8, $9, $10 }'; }
  shape=$(pose shape.rscene)
  [ -n "$shape" ]
  [ "$(pose custom.rscene)" != "$shape" ]
  # The shape's own inertia (m (y^2 + z^2) / 12 for a 0.5 m cube of 1 kg) written out: the same motion.
  [ "$(pose same.rscene)" = "$shape" ]
  { head -4 sim_drop.rscene; echo "$base customInertia=true inertiaDiagonal=0.4,0,0.4"; } > zero.rscene
  run -2 --separate-stderr "$SIM" --steps 1 zero.rscene
  [[ ${stderr_lines[0]} == "zero.rscene:5:"*": error: inertia diagonal of body '/World/Box' has 0, which cannot be simulated [RS7090]" ]]
  run -1 "$BIN/rscene-validate" zero.rscene
  [[ $output == *"[RS7090]"* ]]
}

@test "bodies that start inside the ground are warned about, pushed out before they may sleep, and --until-rest waits for it" {
  cat > sink.rscene <<'SCENE'
raisim_engine_scene 1
time_step 0.0025
gravity 0 0 -9.81
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/Cube box 0 0 0.2 1 0 0 0 1 1 1 0.5 1 10 default engine_default false true false - dynamic true 1 18446744073709551615
object /World/Crate box 3 0 0.2 1 0 0 0 0.5 0.5 0.5 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615
object /World/Deep box -3 0 -5 1 0 0 0 0.5 0.5 0.5 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615
object /World/Resting box 6 0 0.25 1 0 0 0 0.5 0.5 0.5 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615
SCENE
  run -0 --separate-stderr "$SIM" --duration 5 --until-rest -o out.rscene sink.rscene
  [ "${stderr_lines[0]}" = "sink.rscene:5:24: warning: dynamic body '/World/Cube' starts 0.3 m inside '/World/Ground'; the solver pushes it out over the first steps, which moves it and what it touches [RS7013]" ]
  [[ $stderr == *"sink.rscene:7:24: warning: dynamic body '/World/Deep' starts 5.25 m inside '/World/Ground'"* ]]
  [[ $stderr == *"sink.rscene:6:25: warning: dynamic body '/World/Crate' starts 0.05 m inside '/World/Ground'"* ]]
  [[ $stderr != *"/World/Resting' starts"* ]]  # resting contact is no overlap
  [[ $stderr != *RS7002* ]]  # it came to rest
  # each rests on the ground (half its height up, within 2 mm)
  awk '$1 == "object" && $2 != "/World/Ground" {
         h = $2 == "/World/Cube" ? 0.5 : 0.25; d = $6 - h; if (d < 0) d = -d
         if (d > 0.002) { print $2, $6; bad = 1 } } END { exit bad }' out.rscene
}

@test "a run that ends with a body still deep inside another says so (RS7002); resting contacts do not" {
  cat > deep.rscene <<'SCENE'
raisim_engine_scene 1
time_step 0.0025
gravity 0 0 -9.81
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/Cube box 0 0 0.2 1 0 0 0 1 1 1 0.5 1 10 default engine_default false true false - dynamic true 1 18446744073709551615
object /World/Resting box 6 0 0.25 1 0 0 0 0.5 0.5 0.5 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615
SCENE
  # --until-rest whose duration runs out first: not at rest, and why.
  run -0 --separate-stderr "$SIM" --duration 0.01 --until-rest --report -o out.rscene deep.rscene
  [[ $stderr == *"deep.rscene:5:24: warning: --until-rest reached the end of the duration (t = 0.01 s) before the scene came to rest: dynamic body '/World/Cube' 0."*" m inside '/World/Ground' (more than 5 mm deep: a longer run may push it out, unless it is trapped); the scene written is not at rest [RS7002]"* ]]
  [ "$(grep -c RS7002 <<<"$stderr")" -eq 1 ]
  jq -e '.atRest == false' <<<"${stderr_lines[-1]}"
  [ -s out.rscene ]
  # A plain run that ends as early: the same code, without --until-rest.
  run -0 --separate-stderr "$SIM" --duration 0.01 -o out.rscene deep.rscene
  [[ $stderr == *"deep.rscene:5:24: warning: the run ended (t = 0.01 s) with dynamic body '/World/Cube' 0."*" m inside '/World/Ground' (more than 5 mm deep: a longer run may push it out, unless it is trapped): the scene written is not at rest [RS7002]"* ]]
  # Long enough to push it out: no warning, with or without --until-rest.
  run -0 --separate-stderr "$SIM" --duration 3 -o out.rscene deep.rscene
  [[ $stderr != *RS7002* ]]
  run -0 --separate-stderr "$SIM" --duration 5 --until-rest -o out.rscene deep.rscene
  [[ $stderr != *RS7002* ]]
  # A body resting on the ground from the start: nothing, however short the run.
  grep -v /World/Cube deep.rscene > resting.rscene
  run -0 --separate-stderr "$SIM" --duration 0.01 -o out.rscene resting.rscene
  [[ $stderr != *RS7002* ]]
  run -0 --separate-stderr "$SIM" --duration 0.01 --until-rest -o out.rscene resting.rscene
  [[ $stderr != *RS7002* ]]
}

@test "start warnings (RS7013) come before the end-of-run warning (RS7002), each group in line order" {
  # /World/Trapped (line 6) stays inside a static cage to the end; /World/Late
  # (line 8) starts 2 cm inside a static shelf (sim's RS7013) and is pushed out.
  cat > order.rscene <<'SCENE'
raisim_engine_scene 1
time_step 0.0025
gravity 0 0 -9.81
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/Cage box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - static true 1 18446744073709551615
object /World/Trapped box 0 0 0.5 1 0 0 0 0.4 0.4 0.4 0.5 1 1 default engine_default false true false - dynamic true 1 18446744073709551615
object /World/Shelf box 3 0 0.5 1 0 0 0 1 1 1 0.5 1 1 default engine_default false true false - static true 1 18446744073709551615
object /World/Late box 3 0 1.23 1 0 0 0 0.5 0.5 0.5 0.5 1 1 default engine_default false true false - dynamic true 1 18446744073709551615
SCENE
  run -0 --separate-stderr "$SIM" --steps 20 -o out.rscene order.rscene
  codes=$(grep -o 'order.rscene:[0-9]*:[0-9]*: warning: .*\[RS70[01][0-9]\]' <<<"$stderr" | sed 's/^order.rscene:\([0-9]*\):.*\[\(RS[0-9]*\)\]$/\1 \2/' | tr '\n' ' ')
  [ "$codes" = "6 RS7013 8 RS7013 6 RS7002 " ]
}

@test "a body resting on a still kinematic body comes to rest: --until-rest stops" {
  # Bullet keeps a body touching a kinematic one awake; the run never stopped.
  cat > table.rscene <<'SCENE'
raisim_engine_scene 1
time_step 0.0025
gravity 0 0 -9.81
object /World/Table box 0 0 0.25 1 0 0 0 2 2 0.5 0.5 1 1 default engine_default false true false - kinematic true 1 18446744073709551615
object /World/Crate box 0 0 0.75 1 0 0 0 0.5 0.5 0.5 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615
object /World/Top box 0 0 1.25 1 0 0 0 0.5 0.5 0.5 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615
SCENE
  run -0 --separate-stderr "$SIM" --duration 10 --until-rest --report -o out.rscene table.rscene
  jq -e '.atRest == true and .simulatedTime < 2' <<<"${stderr_lines[-1]}"
  # where they started, on the table
  awk '$2 == "/World/Crate" { d = $6 - 0.75 } $2 == "/World/Top" { e = $6 - 1.25 }
       END { exit !(d * d < 1e-5 && e * e < 1e-5) }' out.rscene
  # with sleeping off nothing rests: the duration is the cap
  sed -i 's/^gravity.*/&\nsolver 80 1e-07 0.2 accurate sleepingEnabled=false/' table.rscene
  run -0 --separate-stderr "$SIM" --duration 1 --until-rest --report -o out.rscene table.rscene
  jq -e '.atRest == false' <<<"${stderr_lines[-1]}"
}

@test "a dynamic body starting 100 m under the ground is refused by validate and sim at its position (RS7015), not a fall" {
  cat > under.rscene <<'SCENE'
raisim_engine_scene 1
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/Deep box 0 0 -100 1 0 0 0 0.5 0.5 0.5 0.5 1 2 default engine_default false true false - dynamic true 1 18446744073709551615
SCENE
  msg="under.rscene:3:24: error: dynamic body '/World/Deep' starts at z = -100, below the world's lower bound z = -10 (10 m under the lowest ground, '/World/Ground'): rscene-sim would take it out of the world at its first step [RS7015]"
  run -2 --separate-stderr "$SIM" --steps 10 -o out.rscene under.rscene
  [ "${stderr_lines[0]}" = "$msg" ]
  [[ $stderr != *RS7012* && $stderr != *RS7013* ]]
  [ ! -e out.rscene ]
  run -1 "$BIN/rscene-validate" under.rscene
  [[ $output == *"$msg"* ]]
  # Under other static geometry (no ground): sim's, before the first step, the same code.
  sed -i 's/ ground 0 0 0 1 0 0 0 20 20 1 / box 0 0 0 1 0 0 0 20 20 1 /' under.rscene
  run -2 --separate-stderr "$SIM" --steps 10 -o out.rscene under.rscene
  [ "${stderr_lines[0]}" = "under.rscene:3:24: error: dynamic body '/World/Deep' starts at z = -100, below the world's lower bound z = -10.5 (10 m under the lowest static geometry): rscene-sim would take it out of the world at its first step [RS7015]" ]
}

@test "a 1000 kg crate on a 1 kg crate: validate and sim warn at the heavy one's mass (RS7014); 100:1 does not" {
  cat > crates.rscene <<'SCENE'
raisim_engine_scene 1
object /World/Ground ground 0 0 0 1 0 0 0 20 20 1 0.5 1 0 default engine_default false true false - static true 1 18446744073709551615
object /World/Light box 0 0 0.25 1 0 0 0 0.5 0.5 0.5 0.5 1 1 default engine_default false true false - dynamic true 1 18446744073709551615
object /World/Heavy box 0 0 0.75 1 0 0 0 0.5 0.5 0.5 0.5 1 1000 default engine_default false true false - dynamic true 1 18446744073709551615
SCENE
  msg="crates.rscene:4:60: warning: dynamic body '/World/Heavy' (1000 kg) starts touching '/World/Light' (1 kg), 1e+03 times lighter (more than 100): the contact solver cannot hold such a pair, and the heavy body sinks through the light one [RS7014]"
  run -0 --separate-stderr "$SIM" --steps 10 -o out.rscene crates.rscene
  [ "${stderr_lines[0]}" = "$msg" ]
  run -0 "$BIN/rscene-validate" crates.rscene
  [[ $output == *"$msg"* ]]
  sed -i 's/ 0.5 1 1000 default/ 0.5 1 100 default/' crates.rscene
  run -0 --separate-stderr "$SIM" --steps 10 -o out.rscene crates.rscene
  [[ $stderr != *RS7014* ]]
}

@test "what rscene-sim writes, rscene-sim reads: examples and corpus settle, are written, validate clean, and settle again" {
  local scenes=("$ROOT"/examples/*.rscene)
  [ -d "$CORPUS" ] && scenes+=("$CORPUS"/*.rscene)
  for f in "${scenes[@]}"; do
    n=$(basename "$f" .rscene)
    d=$(dirname "$f")
    run -0 "$SIM" --allow-missing-assets --base-dir "$d" --duration 1 -o "$n.1.rscene" "$f"
    run -0 "$BIN/rscene-validate" --base-dir "$d" "$n.1.rscene"
    run -0 "$SIM" --allow-missing-assets --base-dir "$d" --duration 1 -o "$n.2.rscene" "$n.1.rscene" ||
      { echo "$n: its own output refused"; false; }
  done
}
