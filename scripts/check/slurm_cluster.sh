#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for trying and testing the scale-out recipes
# (docs/commands/bake.md, "Sharding") without a real cluster and without systemd: munged, slurmctld and
# slurmd run as plain background processes whose configuration, key, state, logs and pid files all live
# in STATE_DIR.
#
#   scripts/check/slurm_cluster.sh start STATE_DIR    install slurm-wlm and munge when missing, start the three
#                                               daemons, wait until the node is idle and print the
#                                               `export SLURM_CONF=...` line that sbatch, squeue etc. need
#   scripts/check/slurm_cluster.sh status STATE_DIR   which daemons run, and sinfo's view of the node
#   scripts/check/slurm_cluster.sh stop STATE_DIR     cancel every job, stop the daemons; nothing is left running
#
# Exit status: 0 done; 2 usage; 77 the cluster cannot run here (a daemon did not start, or Slurm cannot
# be installed), with one line saying why and where the daemon's log is. `stop` may be run any number of
# times. Everything listens on 127.0.0.1 only, on the ports SLURM_CLUSTER_CTLD_PORT (default 16817) and
# SLURM_CLUSTER_SLURMD_PORT (default 16818), away from a real cluster's 6817/6818.
# SLURM_CLUSTER_START_TIMEOUT (default 60) bounds the wait for the idle node in seconds.
set -euo pipefail

usage() {
  echo "usage: $0 start|stop|status STATE_DIR" >&2
  exit 2
}
[ $# -eq 2 ] || usage
action=$1
case "$action" in start | stop | status) ;; *) usage ;; esac

ctld_port=${SLURM_CLUSTER_CTLD_PORT:-16817}
slurmd_port=${SLURM_CLUSTER_SLURMD_PORT:-16818}
start_timeout=${SLURM_CLUSTER_START_TIMEOUT:-60}

mkdir -p "$2"
state=$(cd "$2" && pwd)
conf=$state/slurm.conf
munge_socket=$state/munge/munge.socket
export SLURM_CONF=$conf
# The daemons live in /usr/sbin, which a non-root PATH may lack.
export PATH=$PATH:/usr/sbin:/sbin

say() { echo "slurm_cluster.sh: $*" >&2; }

# A cluster that cannot run here is a skip for the tests (status 77), not a failure.
cannot_run() {
  say "$*"
  stop_daemons >/dev/null 2>&1 || true
  exit 77
}

# The pid a daemon's pid file names, when that process is alive; empty otherwise.
live_pid() {
  local file=$state/$1.pid pid
  [ -s "$file" ] || return 0
  pid=$(cat "$file")
  if [[ "$pid" =~ ^[0-9]+$ ]] && kill -0 "$pid" 2>/dev/null; then echo "$pid"; fi
}

install_when_missing() {
  local missing_commands=() missing_packages=() p
  for c in munged slurmctld slurmd sbatch; do command -v "$c" >/dev/null || missing_commands+=("$c"); done
  [ ${#missing_commands[@]} -eq 0 ] && return 0
  for p in slurm-wlm munge; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing_packages+=("$p")
  done
  [ ${#missing_packages[@]} -gt 0 ] || cannot_run "${missing_commands[*]} not found although slurm-wlm and munge are installed"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  # Where systemd runs, Debian's packages also enable and start the system's own daemons (on the usual
  # ports 6817 and 6818); this cluster runs its own beside them.
  say "installing ${missing_packages[*]}"
  { $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
      "${missing_packages[@]}"; } >&2 || cannot_run "could not install ${missing_packages[*]} with apt-get"
}

write_config() {
  local node user mem_mib cpus
  node=$(hostname -s)
  user=$(id -un)
  cpus=$(nproc)
  mem_mib=$(awk '/^MemTotal:/ { print int($2 / 1024) }' /proc/meminfo)
  mkdir -p "$state/munge" "$state/munge-key" "$state/ctld" "$state/spool" "$state/log"
  # As munged wants them: the socket's folder open to every client, the key's to its owner only.
  chmod 755 "$state/munge"
  chmod 700 "$state/munge-key"
  if [ ! -s "$state/munge-key/munge.key" ]; then
    (umask 077 && head -c 1024 /dev/urandom >"$state/munge-key/munge.key")
  fi
  chmod 600 "$state/munge-key/munge.key"
  cat >"$conf" <<EOF
# Written by scripts/check/slurm_cluster.sh: one node, this machine, reachable on 127.0.0.1 only.
ClusterName=dqskin-local
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
# Bind to the addresses above rather than to every interface.
CommunicationParameters=NoCtldInAddrAny,NoInAddrAny
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$munge_socket
# No cgroups (containers and CI machines often cannot delegate them): processes are tracked by parentage.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=none
# One CPU per task and memory not counted, so the array's tasks run side by side.
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
# A finished array task's CPU goes to the next one at once rather than up to 3 s later (the default
# delay batches the scheduling of many submissions, of no use to one node): 16 two-CPU rounds of short
# tasks take 10 s instead of 24 s.
SchedulerParameters=batch_sched_delay=0
# Take the node as written here, whatever slurmd detects (a container may report other numbers).
SlurmdParameters=config_overrides
ReturnToService=2
MailProg=/bin/true
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
NodeName=$node NodeAddr=127.0.0.1 NodeHostname=$node CPUs=$cpus RealMemory=$mem_mib State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
}

# Waits up to 15 s until the daemon NAME runs (its pid file names a live process) and READY_COMMAND
# succeeds; otherwise the cluster cannot run here.
wait_for_daemon() {
  local name=$1 log=$2 i seen=""
  shift 2
  for ((i = 0; i < 150; i++)); do
    if [ -n "$(live_pid "$name")" ]; then
      seen=yes
      "$@" >/dev/null 2>&1 && return 0
    elif [ -n "$seen" ]; then
      break # it started and ended again
    fi
    sleep 0.1
  done
  cannot_run "$name did not start; its log: $log (last line: $(tail -n 1 "$log" 2>/dev/null))"
}

# start_daemon NAME LOG READY_COMMAND -- DAEMON_COMMAND
start_daemon() {
  local name=$1 log=$2 ready=()
  shift 2
  while [ "$1" != "--" ]; do
    ready+=("$1")
    shift
  done
  shift
  [ -n "$(live_pid "$name")" ] && return 0
  rm -f "$state/$name.pid"
  # The daemons fork into the background themselves; their standard streams go to a file so that a
  # caller reading this script's output (a test harness) does not wait for them.
  "$@" </dev/null >>"$log.stdout" 2>&1 || cannot_run "$name exited with status $? at start; its log: $log (and $log.stdout)"
  wait_for_daemon "$name" "$log" "${ready[@]}"
}

controller_answers() { scontrol ping | grep -q 'is UP'; }

start() {
  install_when_missing
  # Unix socket paths must fit sockaddr_un's 108 bytes; the longest here is a job step's in the spool
  # folder, NODE_JOBID.STEPID (a batch step's id is 4294967291).
  local longest_socket
  longest_socket="$state/spool/$(hostname -s)_9999999.4294967291"
  [ ${#longest_socket} -le 107 ] ||
    cannot_run "STATE_DIR's path is too long for the Unix sockets in it (${#longest_socket} > 107 bytes): $state"
  write_config
  # --force: munged also refuses to run when a folder above STATE_DIR may be written by a group (a build
  # tree under a shared folder); the key and socket folders themselves are as it wants them.
  start_daemon munged "$state/log/munged.log" test -S "$munge_socket" -- munged --force --socket="$munge_socket" \
    --key-file="$state/munge-key/munge.key" --pid-file="$state/munged.pid" --log-file="$state/log/munged.log" \
    --seed-file="$state/munge-key/munged.seed"
  start_daemon slurmctld "$state/log/slurmctld.log" controller_answers -- slurmctld -f "$conf"
  # slurmd is ready when the controller calls the node idle, below.
  start_daemon slurmd "$state/log/slurmd.log" true -- slurmd -f "$conf"

  local node deadline node_state=""
  node=$(hostname -s)
  deadline=$((SECONDS + start_timeout))
  while ((SECONDS < deadline)); do
    node_state=$(sinfo -h -n "$node" -o %T 2>/dev/null || true)
    case "$node_state" in idle | mixed | allocated) break ;; esac
    for d in munged slurmctld slurmd; do
      [ -n "$(live_pid "$d")" ] || cannot_run "$d stopped while the node came up; its log: $state/log/$d.log"
    done
    sleep 1
  done
  case "$node_state" in
    idle | mixed | allocated) ;;
    *) cannot_run "node $node not idle after ${start_timeout} s (sinfo says '${node_state:-nothing}'); logs: $state/log/slurmctld.log, $state/log/slurmd.log" ;;
  esac
  say "node $node is $node_state; for sbatch, squeue, sinfo and scancel:"
  echo "export SLURM_CONF=$conf"
}

# Sends SIGTERM to the daemon, waits up to 20 s for it to end, then SIGKILL.
stop_daemon() {
  local name=$1 pid i
  pid=$(live_pid "$name")
  if [ -n "$pid" ]; then
    kill -TERM "$pid" 2>/dev/null || true
    for ((i = 0; i < 200; i++)); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    if kill -0 "$pid" 2>/dev/null; then
      say "$name (pid $pid) still runs 20 s after SIGTERM; sending SIGKILL"
      kill -KILL "$pid" 2>/dev/null || true
    fi
  fi
  rm -f "$state/$name.pid"
}

# The job steps' slurmstepd processes detach from slurmd; those of this cluster have a socket in its spool
# folder, and /proc says which process holds it open.
stepd_pids() {
  local sockets
  sockets=$(find "$state/spool" -maxdepth 1 -type s 2>/dev/null) || true
  [ -n "$sockets" ] || return 0
  local inodes
  inodes=$(awk -v spool="$state/spool/" 'index($8, spool) == 1 { print $7 }' /proc/net/unix 2>/dev/null | sort -u)
  [ -n "$inodes" ] || return 0
  local fd pid
  for fd in /proc/[0-9]*/fd/*; do
    local target
    target=$(readlink "$fd" 2>/dev/null) || continue
    [[ "$target" =~ ^socket:\[([0-9]+)\]$ ]] || continue
    if grep -qx "${BASH_REMATCH[1]}" <<<"$inodes"; then
      pid=${fd#/proc/}
      echo "${pid%%/*}"
    fi
  done | sort -u
}

# Every process below PID, children first found by their parent's pid.
descendants() {
  local child
  for child in $(pgrep -P "$1"); do
    echo "$child"
    descendants "$child"
  done
}

stop_daemons() {
  if [ -n "$(live_pid slurmctld)" ] && [ -f "$conf" ]; then
    # Jobs first, so that their processes end with them rather than outlive the daemons.
    local jobs i
    jobs=$(squeue -h -o %A 2>/dev/null || true)
    if [ -n "$jobs" ]; then
      # shellcheck disable=SC2086  # one job id a word
      scancel $jobs 2>/dev/null || true
      for ((i = 0; i < 30; i++)); do
        [ -z "$(squeue -h -o %A 2>/dev/null || true)" ] && break
        sleep 1
      done
    fi
  fi
  stop_daemon slurmd
  local pid
  for pid in $(stepd_pids); do
    say "ending job step $pid ($(tr -d '\0' </proc/"$pid"/cmdline 2>/dev/null)) and its processes, left when jobs could not be cancelled"
    # shellcheck disable=SC2046  # one pid a word
    kill -KILL "$pid" $(descendants "$pid") 2>/dev/null || true
  done
  stop_daemon slurmctld
  stop_daemon munged
}

status() {
  local d pid running=0
  for d in munged slurmctld slurmd; do
    pid=$(live_pid "$d")
    if [ -n "$pid" ]; then
      echo "$d: running (pid $pid)"
      running=$((running + 1))
    else
      echo "$d: stopped"
    fi
  done
  if [ -n "$(live_pid slurmctld)" ]; then sinfo 2>&1 || true; fi
  [ $running -eq 3 ] && echo "export SLURM_CONF=$conf"
  return 0
}

case "$action" in
  start) start ;;
  stop) stop_daemons ;;
  status) status ;;
esac
