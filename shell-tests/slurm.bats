#!/usr/bin/env bats
# The README's Slurm job-array recipe (examples/slurm/) on a one-node
# cluster that scripts/slurm-cluster.sh starts on this machine for the
# file (setup_file) and stops after it (teardown_file).  Tests that need
# the cluster skip, with the reason, where it cannot start: not root, or
# slurm-wlm and munge not installed (scripts/install-deps.sh installs
# them; `make test` runs as root).  Any other failure to start fails
# them.  The recipe's scripts that need no cluster (one task run by hand,
# the summary) are tested everywhere.

load helpers

CLUSTER="$ROOT/scripts/slurm-cluster.sh"
RECIPE="$ROOT/examples/slurm"

setup_file() {
  export SLURM_SKIP="" SLURM_CONF="" RSCENE_SLURM_DIR=""
  local out rc=0
  out=$("$CLUSTER" start 2>"$BATS_FILE_TMPDIR/start.err") || rc=$?
  if [ "$rc" -eq 77 ]; then
    SLURM_SKIP=$(head -n 1 "$BATS_FILE_TMPDIR/start.err")
    return 0
  fi
  [ "$rc" -eq 0 ] || { cat "$BATS_FILE_TMPDIR/start.err" >&2; return 1; }
  eval "$out"
  export SLURM_CONF RSCENE_SLURM_DIR
}

teardown_file() {
  [ -z "${RSCENE_SLURM_DIR:-}" ] || "$CLUSTER" stop "$RSCENE_SLURM_DIR"
}

setup() {
  in_workdir
  export RSCENE_SIM="$BIN/rscene-sim" DURATION=0.2
}

needs_cluster() {
  [ -z "$SLURM_SKIP" ] || skip "$SLURM_SKIP"
  [ -n "$SLURM_CONF" ] || { echo "no cluster"; return 1; }
}

# scenes N BAD...: N copies of sim_drop as in/s1..sN.rscene, the numbers
# BAD... a syntax error instead, and their paths in scenes.txt.
scenes() {
  local n=$1 i
  shift
  mkdir -p in
  for ((i = 1; i <= n; i++)); do cp "$DATA/sim_drop.rscene" "in/s$i.rscene"; done
  for i in "$@"; do printf 'raisim_engine_scene 2\nobject {\n' > "in/s$i.rscene"; done
  for ((i = 1; i <= n; i++)); do echo "$PWD/in/s$i.rscene"; done > scenes.txt
}

@test "the cluster: one node with this machine's CPUs, idle, its daemons from pid files" {
  needs_cluster
  run -0 sinfo -h -N -o '%t %c'
  [ "$output" = "idle $(nproc)" ]
  local d pid
  for d in munged slurmctld slurmd; do
    pid=$(cat "$RSCENE_SLURM_DIR/$d.pid")
    [ "$(cat "/proc/$pid/comm")" = "$d" ]
  done
  [[ $SLURM_CONF == "$RSCENE_SLURM_DIR/slurm.conf" ]]
}

@test "the recipe end to end: a broken scene fails only its task; the rerun of the failed task; one summary" {
  needs_tools rscene-sim
  needs_cluster
  scenes 7 5
  # 7 scenes in chunks of 3: tasks 0 (s1-s3), 1 (s4-s6), 2 (s7); task 1
  # fails for its broken s5, and submit.sh --wait says so
  CHUNK=3 run -1 "$RECIPE/submit.sh" scenes.txt out --wait
  [[ $output == *"submit: 7 scenes, 3 tasks of 3"* ]]
  [[ $output == *"batch $PWD/out: 1 of 3 tasks failed or did not run (task numbers 1); rerun them with: "*"/rerun-failed.sh $PWD/out"* ]]
  # Slurm's own record of the tasks (jobcomp/filetxt; no sacct here)
  local job state
  job=$(grep -o 'Submitted batch job [0-9]*' <<<"$output" | grep -o '[0-9]*$')
  for t in 0 1 2; do
    state=$(grep "ArrayJobId=$job ArrayTaskId=$t " "$RSCENE_SLURM_DIR/log/jobcomp.log" | grep -o 'JobState=[A-Z]*')
    [ "$state" = "JobState=$([ "$t" = 1 ] && echo FAILED || echo COMPLETED)" ]
  done
  [ "$(cat out/status/0)" = "ok 3" ]
  [ "$(cat out/status/1)" = "failed 1 of 3" ]
  [ "$(cat out/status/2)" = "ok 1" ]
  # every other scene's result and report stand
  for i in 1 2 3 4 6 7; do
    [ -s "out/scenes/s$i.rscene" ]
    run -0 jq -e --arg s "$PWD/in/s$i.rscene" '.scene == $s and .exit == 0 and .error == null and .report.steps > 0' "out/reports/s$i.json"
  done
  cmp out/scenes/s1.rscene out/scenes/s7.rscene
  "$RSCENE_SIM" --duration 0.2 -o direct.rscene in/s1.rscene
  cmp direct.rscene out/scenes/s1.rscene
  [ ! -e out/scenes/s5.rscene ]
  run -0 jq -r '[.exit, .task, .report, .output] | @tsv' out/reports/s5.json
  [ "$output" = $'2\t1\t\t' ]
  run -0 jq -r .error out/reports/s5.json
  [[ $output == "$PWD/in/s5.rscene:"*": error: "*"[RS"*"]" ]]
  grep -q "s5.rscene:.*error:" out/logs/*_1.out
  # no temporary file is left beside the results
  [ -z "$(find out -name '.*' -type f)" ]

  # mend s5 and rerun the failed task only: task 1, once; its good scenes
  # s4 and s6 are not simulated again, tasks 0 and 2 not touched
  cp "$DATA/sim_drop.rscene" in/s5.rscene
  # (every result is written by a rename: a new inode)
  local kept logs_before
  kept=$(stat -c '%i %n' out/status/[02] out/scenes/* out/reports/s[1234679].json)
  logs_before=$(ls out/logs | wc -l)
  run -0 "$RECIPE/rerun-failed.sh" out --wait
  [[ $output == *"rerun-failed: resubmitting task numbers 1 (--array=1)"* ]]
  [[ $output == *"batch $PWD/out: all 3 tasks ok"* ]]
  [ "$(ls out/logs | wc -l)" -eq $((logs_before + 1)) ]
  [ "$(cat out/status/1)" = "ok 3" ]
  [ "$(stat -c '%i %n' out/status/[02] out/scenes/s[1234679].rscene out/reports/s[1234679].json)" = "$kept" ]
  cmp out/scenes/s1.rscene out/scenes/s5.rscene
  run -0 jq -e '.exit == 0 and .report.steps > 0' out/reports/s5.json
  # nothing is left to rerun
  run -0 "$RECIPE/rerun-failed.sh" out --wait
  [[ $output == *"all 3 tasks ok"* ]]
  # a rerun simulates as the batch did: its DURATION is recorded, and
  # another one in the environment is refused
  grep -qx 'DURATION=0.2' out/batch
  rm out/status/2
  DURATION=1 run -2 "$RECIPE/rerun-failed.sh" out --wait
  [[ $output == *"the batch ran with DURATION=0.2, the environment says 1: unset it, or submit a new batch"* ]]
  unset DURATION
  rm out/reports/s7.json
  run -0 "$RECIPE/rerun-failed.sh" out --wait
  run -0 jq -e '.report.simulatedTime > 0.19 and .report.simulatedTime < 0.21' out/reports/s7.json
  export DURATION=0.2

  # one summary of every report, in the list's order: JSON Lines and CSV
  run -0 "$RECIPE/summarize.sh" out summary.jsonl
  [ "$(wc -l < summary.jsonl)" -eq 7 ]
  run -0 jq -sr 'map(.scene | sub(".*/"; "")) | join(" ")' summary.jsonl
  [ "$output" = "s1.rscene s2.rscene s3.rscene s4.rscene s5.rscene s6.rscene s7.rscene" ]
  run -0 jq -se 'all(.exit == 0 and (.report.simulatedTime | . > 0.19 and . < 0.21))' summary.jsonl
  run -0 "$RECIPE/summarize.sh" out summary.csv
  [ "$(wc -l < summary.csv)" -eq 8 ]
  [[ $(head -n 1 summary.csv) == '"scene","output","task","job","exit","error",'*'"report.steps"'* ]]
  [ "$(grep -c "^\"$PWD/in/s[1-7].rscene\",\"$PWD/out/scenes/s[1-7].rscene\",[012],\"[0-9]*_[012]\",0,," summary.csv)" -eq 7 ]
}

@test "100,000 scenes fit within MaxArraySize in chunks of 100; chunks too small are refused" {
  needs_cluster
  mkdir in
  (cd in && seq -f 's%06g.rscene' 1 100000 | xargs touch)
  seq -f "$PWD/in/s%06g.rscene" 1 100000 > big.txt
  run -0 "$RECIPE/submit.sh" big.txt out --test-only
  [[ $output == *"submit: 100000 scenes, 1000 tasks of 100"* ]]
  [[ $output == *"to start at"* ]]
  [ ! -e out/batch ]
  CHUNK=50 run -2 "$RECIPE/submit.sh" big.txt out --test-only
  [[ $output == *"2000 tasks, over the cluster's MaxArraySize (1001): raise CHUNK"* ]]
}

# start_second: a second cluster beside the file's, in a folder of its
# own making (munge wants a short socket path in folders all may enter),
# running a job that sleeps; sets dir, and pids to the daemons', the
# job shell's (then sleep's) and its slurmstepd's.
start_second() {
  run -0 --separate-stderr "$CLUSTER" start
  dir=$(sed -n 's/.* RSCENE_SLURM_DIR=//p' <<<"$output")
  [ -e "$dir/.rscene-slurm" ]
  pids=$(cat "$dir"/*.pid)
  SLURM_CONF="$dir/slurm.conf" run -0 sbatch --output=/dev/null --wrap 'echo $$ $PPID > '"$PWD"'/job.pid; exec sleep 300'
  for _ in $(seq 1 300); do [ -s job.pid ] && break; sleep 0.1; done
  [ -s job.pid ]
  [ "$(cat "/proc/$(cut -d' ' -f2 job.pid)/comm")" = slurmstepd ]
  pids="$pids $(cat job.pid)"
}

# ended PID...: each is gone, or a zombie that its parent (pid 1, for a
# daemon) has not reaped yet.
ended() {
  local p
  for p in "$@"; do
    [ ! -e "/proc/$p/stat" ] || [[ $(cat "/proc/$p/stat" 2>/dev/null) == *") Z "* ]] ||
      [ ! -e "/proc/$p/stat" ] || { echo "process $p still runs: $(cat "/proc/$p/stat")"; return 1; }
  done
}

@test "stop ends every process the cluster started, a running job's too, and removes its folder" {
  needs_cluster
  local dir pids
  start_second
  run -0 "$CLUSTER" stop "$dir"
  [ ! -e "$dir" ]
  # shellcheck disable=SC2086
  ended $pids
  # the file's own cluster still answers
  run -0 sinfo -h -N -o %t
  [ "$output" = idle ]
}

@test "stop ends a job's processes even when slurmctld and slurmd have died" {
  needs_cluster
  local dir pids
  start_second
  kill -KILL "$(cat "$dir/slurmctld.pid")" "$(cat "$dir/slurmd.pid")"
  run -0 "$CLUSTER" stop "$dir"
  [ ! -e "$dir" ]
  # shellcheck disable=SC2086
  ended $pids
}

@test "submit refuses a list with carriage returns or scenes that cannot be read, before using the cluster" {
  scenes 3
  sed 's/$/\r/' scenes.txt > crlf.txt
  run -2 "$RECIPE/submit.sh" crlf.txt out
  [[ $output == "submit: $PWD/crlf.txt has carriage returns (Windows line ends): convert it first"* ]]
  echo "$PWD/in/nothere.rscene" >> scenes.txt
  run -2 "$RECIPE/submit.sh" scenes.txt out
  [ "$output" = "submit: $PWD/scenes.txt names 1 scene(s) that cannot be read, such as: $PWD/in/nothere.rscene " ]
  [ ! -e out ]
}

@test "stop leaves alone a folder it did not make" {
  mkdir keep
  touch keep/slurmd.pid
  run -1 "$CLUSTER" stop keep
  [[ $output == *"was not made by slurm-cluster.sh start; not touching it"* ]]
  [ -e keep/slurmd.pid ]
}

@test "one task run by hand: its chunk only, a status file, exit 1 when a scene fails" {
  needs_tools rscene-sim
  scenes 5 4
  SLURM_ARRAY_TASK_ID=1 CHUNK=2 run -1 "$RECIPE/sim-array.sh" scenes.txt out
  [ "$(ls out/scenes)" = "s3.rscene" ]
  [ "$(ls out/reports | tr '\n' ' ')" = "s3.json s4.json " ]
  [ "$(cat out/status/1)" = "failed 1 of 2" ]
  SLURM_ARRAY_TASK_ID=2 CHUNK=2 run -0 "$RECIPE/sim-array.sh" scenes.txt out
  [ "$(cat out/status/2)" = "ok 1" ]
  # a task past the list's end is a usage error
  SLURM_ARRAY_TASK_ID=3 CHUNK=2 run -2 "$RECIPE/sim-array.sh" scenes.txt out
}

@test "the summary lists a scene whose task did not run, and exits 1" {
  needs_tools rscene-sim
  scenes 4
  mkdir out
  printf 'LIST=%q\nCHUNK=2\nTASKS=2\n' "$PWD/scenes.txt" > out/batch
  SLURM_ARRAY_TASK_ID=0 CHUNK=2 run -0 "$RECIPE/sim-array.sh" scenes.txt out
  run -1 "$RECIPE/summarize.sh" out sum.jsonl
  [[ $output == *"summarize: 4 scenes, 2 ok, 2 failed or not run"* ]]
  run -0 jq -sc 'map([.exit, .error, .task])' sum.jsonl
  [ "$output" = '[[0,null,0],[0,null,0],[null,"not run",1],[null,"not run",1]]' ]
  run -1 "$RECIPE/summarize.sh" out sum.csv
  [ "$(wc -l < sum.csv)" -eq 5 ]
  [[ $(tail -n 1 sum.csv) == "\"$PWD/in/s4.rscene\",,1,,,\"not run\","* ]]
  [ "$(tail -n 1 sum.csv | tr -cd , | wc -c)" -eq "$(head -n 1 sum.csv | tr -cd , | wc -c)" ]
  # a scene list naming two scenes of one file name is refused
  mkdir other && cp in/s1.rscene other/
  echo "$PWD/other/s1.rscene" >> scenes.txt
  run -2 "$RECIPE/submit.sh" scenes.txt out2
  [[ $output == *"names more than one scene called: s1"* ]]
}
