#!/bin/bash
# A single-node Slurm cluster on this machine, for trying and testing the
# job-array recipe of examples/slurm/ (shell-tests/slurm.bats runs it).
# Debian's packages: slurm-wlm (slurmctld, slurmd, sbatch...) and munge.
#
#   eval "$(scripts/slurm-cluster.sh start [DIR])"   # exports SLURM_CONF
#   sbatch --wait ...; sinfo; squeue
#   scripts/slurm-cluster.sh stop DIR
#
# start: makes DIR (default: a new folder under ${TMPDIR:-/tmp}) and puts
# everything there: a munge key, the sockets, slurm.conf (one node with
# this machine's CPUs, one default partition, free TCP ports), the state,
# spool, logs and pid files.  It starts munged, slurmctld and slurmd,
# waits (at most SLURM_START_TIMEOUT seconds, default 60) until `sinfo`
# shows the node idle, and prints `export SLURM_CONF=DIR/slurm.conf` (and
# RSCENE_SLURM_DIR=DIR) on standard output.  Nothing outside DIR is
# written and no system service is used: it runs in a container without
# systemd.  When it cannot finish it stops what it started, removes DIR,
# and exits 1, showing the daemons' log tails.  It exits 77 (nothing
# started) where a cluster cannot start here: not root (the daemons run
# as root, SlurmUser=root) or a package missing.
#
# DIR must be short (munged's socket path has at most 108 bytes) and in
# folders everyone may enter (munged checks).
#
# stop: cancels the jobs left on the cluster, stops exactly the daemons
# whose pid files are in DIR (TERM, then KILL after 10 s), ends a job
# step that outlived slurmd (its slurmstepd, found by this SLURM_CONF,
# and every process under it), and removes DIR.  A process that has
# ended but is not yet reaped (a zombie) counts as ended.  It refuses a
# DIR that start did not make, and is safe to run twice, or after a
# start that failed.
#
# No slurmdbd: `sacct` has no accounting storage here, so the recipe
# keeps its own per-task status files.
set -Eeuo pipefail

die() { echo "slurm-cluster: $*" >&2; exit 1; }
usage() { echo "usage: $0 start [DIR] | stop DIR" >&2; exit 2; }

# The daemons it starts, each with its pid file DIR/NAME.pid.
DAEMONS="munged slurmctld slurmd"

# running PID: whether PID is a live process; an ended one that its
# parent has not reaped yet (a zombie: a container's pid 1 may take its
# time) is not.
running() {
  local stat=""
  read -r stat 2>/dev/null < "/proc/$1/stat" || return 1
  stat=${stat##*) }
  case ${stat%% *} in Z | X | x) return 1 ;; esac
  return 0
}

# pid_of DIR NAME: the pid in DIR/NAME.pid when that process still runs
# the program NAME (a reused pid is left alone), else nothing.
pid_of() {
  local f="$1/$2.pid" pid comm=""
  [ -s "$f" ] || return 0
  pid=$(tr -dc 0-9 < "$f")
  [ -n "$pid" ] && running "$pid" || return 0
  read -r comm 2>/dev/null < "/proc/$pid/comm" || return 0
  [ "$comm" != "$2" ] || echo "$pid"
}

# The daemons' log tails, for a start that failed.
show_logs() {
  local f
  for f in "$1"/log/*.log; do
    [ -s "$f" ] || continue
    echo "--- $f" >&2
    tail -n 15 "$f" >&2
  done
}

stop_cluster() {
  local dir=$1 name pid
  [ -d "$dir" ] || return 0
  # Only a folder this script made: its marker file says so.
  [ -e "$dir/.rscene-slurm" ] || die "$dir was not made by slurm-cluster.sh start; not touching it"
  # Jobs still queued or running: end them while slurmctld and slurmd
  # are up, so that no slurmstepd or job process outlives the cluster.
  if [ -n "$(pid_of "$dir" slurmctld)" ] && [ -n "$(pid_of "$dir" slurmd)" ]; then
    SLURM_CONF="$dir/slurm.conf" timeout 10 scancel --quiet --full --user=root >/dev/null 2>&1 || true
    for _ in $(seq 1 50); do
      [ -z "$(SLURM_CONF="$dir/slurm.conf" timeout 5 squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.2
    done
  fi
  # TERM to all three at once (each takes a second or two to end), KILL
  # to what is left after 10 s.
  local pids=""
  for name in $DAEMONS; do
    pid=$(pid_of "$dir" "$name")
    [ -z "$pid" ] || { kill -TERM "$pid" 2>/dev/null || true; pids="$pids $pid"; }
  done
  for _ in $(seq 1 100); do
    local alive=""
    for pid in $pids; do
      ! running "$pid" || alive="$alive $pid"
    done
    pids=$alive
    [ -n "$pids" ] || break
    sleep 0.1
  done
  for pid in $pids; do kill -KILL "$pid" 2>/dev/null || true; done
  # A job that slurmd could not end (slurmctld or slurmd gone before the
  # scancel): its slurmstepd, found by the SLURM_CONF this cluster's
  # slurmd passed it, and every process under it.
  local p comm stat ppid steps="" kids
  local -A children=()
  for p in /proc/[0-9]*; do
    stat="" comm=""
    read -r stat 2>/dev/null < "$p/stat" || continue
    stat=${stat##*) }  # after "pid (comm) ": state ppid ...
    ppid=${stat#* }
    ppid=${ppid%% *}
    children[$ppid]+=" ${p#/proc/}"
    read -r comm 2>/dev/null < "$p/comm" || continue
    [ "$comm" = slurmstepd ] || continue
    if running "${p#/proc/}" && tr '\0' '\n' < "$p/environ" 2>/dev/null | grep -qx "SLURM_CONF=$dir/slurm.conf"; then
      steps="$steps ${p#/proc/}"
    fi
  done
  while [ -n "$steps" ]; do
    kids=""
    for pid in $steps; do
      kill -KILL "$pid" 2>/dev/null || true
      kids="$kids ${children[$pid]:-}"
    done
    steps=$kids
  done
  rm -rf "$dir"
}

# free_ports N: N distinct TCP ports that nothing listens on now.
free_ports() {
  python3 - "$1" <<'EOF'
import socket, sys
socks = []
for _ in range(int(sys.argv[1])):
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    socks.append(s)
print(" ".join(str(s.getsockname()[1]) for s in socks))
EOF
}

start_cluster() {
  local dir=${1:-} p
  if [ "$(id -u)" -ne 0 ]; then
    echo "slurm-cluster: needs root (the test cluster runs its daemons as root)" >&2
    exit 77
  fi
  for p in munged mungekey slurmctld slurmd sbatch sinfo scancel squeue python3; do
    command -v "$p" >/dev/null 2>&1 || PATH="$PATH:/usr/sbin:/sbin" command -v "$p" >/dev/null 2>&1 || {
      echo "slurm-cluster: $p not found (sh scripts/install-deps.sh installs slurm-wlm and munge)" >&2
      exit 77
    }
  done
  export PATH="$PATH:/usr/sbin:/sbin"

  if [ -z "$dir" ]; then
    dir=$(mktemp -d "${TMPDIR:-/tmp}/rscene-slurm.XXXXXX")
  else
    [ ! -e "$dir" ] || [ -z "$(ls -A "$dir")" ] || die "$dir exists and is not empty"
    mkdir -p "$dir"
  fi
  dir=$(cd "$dir" && pwd -P)
  # munged's socket path has at most 108 bytes.
  [ "${#dir}" -le 80 ] || { rmdir "$dir" 2>/dev/null || true; die "$dir: too long a path for munge's socket (keep it under 80 bytes)"; }
  : > "$dir/.rscene-slurm"
  # munged refuses a key that others can read, and a socket in a folder
  # that others can write to or cannot enter.
  chmod 755 "$dir"
  mkdir -m 700 "$dir/munge" "$dir/log" "$dir/state" "$dir/spool"
  mkdir -m 755 "$dir/socket"
  trap 'echo "slurm-cluster: start failed; the logs:" >&2; show_logs "$dir"; stop_cluster "$dir"; exit 1' ERR
  trap 'stop_cluster "$dir"; exit 1' INT TERM

  mungekey --create --keyfile="$dir/munge/munge.key" --bits=1024 >/dev/null 2>&1 ||
    dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
  chmod 400 "$dir/munge/munge.key"
  munged --socket="$dir/socket/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munged.pid" --log-file="$dir/log/munged.log" \
    --seed-file="$dir/munge/munged.seed" --num-threads=2 </dev/null >"$dir/log/munged.start.log" 2>&1

  local host ports ctld_port d_port cpus mem
  host=$(hostname -s)
  ports=$(free_ports 2)
  ctld_port=${ports% *}
  d_port=${ports#* }
  cpus=$(nproc)
  # This machine's memory in MiB (jobs ask for some: --mem-per-cpu).
  mem=$(awk '$1 == "MemTotal:" { print int($2 / 1024) }' /proc/meminfo)
  cat > "$dir/slurm.conf" <<EOF
# Written by scripts/slurm-cluster.sh: one node, this machine, for tests.
ClusterName=rscene
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/socket/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
# Each finished job and array task, one line: JobState=COMPLETED|FAILED...
# (no slurmdbd, so sacct has nothing to read).
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/log/jobcomp.log
MpiDefault=none
MailProg=/bin/true
SwitchType=switch/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU_Memory
ReturnToService=2
SlurmdParameters=config_overrides
# A finished job's record stays 4 s: long enough for sbatch --wait, which
# then polls every 2 s instead of backing off to 8 or 32 s.
MinJobAge=4
KillWait=5
InactiveLimit=0
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=batch Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$dir/slurm.conf"

  # -c: a fresh start, no state from an earlier cluster; -i: ignore any.
  slurmctld -c -i </dev/null >"$dir/log/slurmctld.start.log" 2>&1
  slurmd -N "$host" </dev/null >"$dir/log/slurmd.start.log" 2>&1

  local timeout=${SLURM_START_TIMEOUT:-60} waited=0 state=""
  while :; do
    state=$(timeout 5 sinfo -h -N -o %t 2>/dev/null || true)
    [ "$state" = idle ] && break
    if [ -z "$(pid_of "$dir" munged)" ] || [ -z "$(pid_of "$dir" slurmctld)" ] || [ -z "$(pid_of "$dir" slurmd)" ]; then
      # A daemon may still be forking when its pid file is absent.
      [ "$waited" -lt 3 ] || { echo "slurm-cluster: a daemon exited" >&2; false; }
    fi
    [ "$waited" -lt "$timeout" ] || { echo "slurm-cluster: the node is not idle after ${timeout}s (state: ${state:-none})" >&2; false; }
    sleep 1
    waited=$((waited + 1))
  done
  trap - ERR INT TERM
  echo "export SLURM_CONF=$dir/slurm.conf RSCENE_SLURM_DIR=$dir"
}

case ${1:-} in
  start) [ $# -le 2 ] || usage; start_cluster "${2:-}" ;;
  stop) [ $# -eq 2 ] || usage; stop_cluster "$2" ;;
  *) usage ;;
esac
