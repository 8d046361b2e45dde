#!/usr/bin/env bash
# A real one-node Slurm cluster on this machine, for the slurm tests and for trying the job
# scripts (docs/cluster.md, "A local cluster"). As root:
#   scripts/slurm/local-cluster.sh start [DIR]    # then: export SLURM_CONF=DIR/slurm.conf
#   scripts/slurm/local-cluster.sh status [DIR]
#   scripts/slurm/local-cluster.sh stop [DIR]
# DIR (default build/slurm) holds everything: slurm.conf, a munge key and socket of its own, the
# daemons' state, spool, pid and log files. The daemons are this machine's munged, slurmctld and
# slurmd, started as root on free TCP ports with this folder's configuration: nothing under /etc,
# /run or /var is read or written, so a system Slurm or munge, or another local cluster in
# another folder, is left alone. One node: this machine's CPUs, sockets, cores and memory as
# `slurmd -C` reports them; one partition, `local`. No cgroups (containers seldom grant them):
# processes are tracked through /proc (proctrack/linuxproc), tasks are not bound (task/none), no
# accounting. srun launches MPI ranks through PMIx (MpiDefault=pmix, Open MPI's own).
# `stop` cancels the cluster's jobs, then ends exactly the daemons whose pid files DIR holds
# (each checked to be that program before it is signalled).
set -euo pipefail

usage() {
  echo "usage: local-cluster.sh start|stop|status [DIR] (default DIR: build/slurm)" >&2
  exit 2
}
[[ $# -ge 1 && $# -le 2 ]] || usage
action=$1
dir=${2:-build/slurm}
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
export SLURM_CONF=$dir/slurm.conf

# The pid in FILE when that process is still the program NAME, else nothing.
live_pid() {
  local file=$1 name=$2 pid
  [[ -f $file ]] || return 0
  pid=$(<"$file")
  [[ $pid =~ ^[0-9]+$ ]] || return 0
  [[ $(cat "/proc/$pid/comm" 2>/dev/null) == "$name" ]] && echo "$pid"
  return 0
}

# Ends the daemon NAME whose pid file is FILE: SIGTERM, then SIGKILL after 20 s.
end_daemon() {
  local file=$1 name=$2 pid
  pid=$(live_pid "$file" "$name")
  if [[ -n $pid ]]; then
    kill -TERM "$pid" 2>/dev/null || true
    for _ in $(seq 200); do
      [[ -d /proc/$pid ]] || break
      sleep 0.1
    done
    if [[ -d /proc/$pid ]]; then kill -KILL "$pid" 2>/dev/null || true; fi
    echo "local-cluster: stopped $name (pid $pid)"
  fi
  rm -f "$file"
}

stop() {
  if [[ -n $(live_pid "$dir/slurmctld.pid" slurmctld) ]]; then
    # The cluster's own jobs (this SLURM_CONF's controller): their steps would outlive slurmd.
    scancel --full --quiet --user=root 2>/dev/null || true
    for _ in $(seq 100); do
      [[ -z $(squeue --noheader --format=%i 2>/dev/null) ]] && break
      sleep 0.1
    done
  fi
  end_daemon "$dir/slurmd.pid" slurmd
  end_daemon "$dir/slurmctld.pid" slurmctld
  end_daemon "$dir/munge/munged.pid" munged
}

# Two free TCP ports on this machine (the kernel's pick), for slurmctld and slurmd.
free_ports() {
  python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))'
}

start() {
  [[ $(id -u) -eq 0 ]] || { echo "local-cluster: start needs root (munged, slurmctld and slurmd run as root)" >&2; exit 2; }
  local program
  for program in munged slurmctld slurmd sinfo; do
    command -v "$program" >/dev/null ||
      { echo "local-cluster: $program is not installed (deps/debian-packages.txt: munge, slurmctld, slurmd, slurm-client)" >&2; exit 2; }
  done
  if [[ -n $(live_pid "$dir/slurmctld.pid" slurmctld) || -n $(live_pid "$dir/slurmd.pid" slurmd) ]]; then
    echo "local-cluster: already running in $dir (stop it first)" >&2
    exit 1
  fi
  stop >/dev/null  # a daemon left from a start that failed half-way
  rm -rf "$dir/state" "$dir/spool" "$dir/munge"
  mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
  # munged wants its socket's folder searchable by everyone and its key readable by itself alone.
  chmod 755 "$dir/munge"
  head -c 1024 /dev/urandom >"$dir/munge/munge.key"
  chmod 400 "$dir/munge/munge.key"

  local node ports ctld_port d_port
  node=$(slurmd -C | head -n 1)  # NodeName=HOST CPUs=.. Boards=.. ... RealMemory=..
  read -r ctld_port d_port <<<"$(free_ports)"
  cat >"$SLURM_CONF" <<EOF
# Written by scripts/slurm/local-cluster.sh: a one-node cluster whose files are all in $dir.
ClusterName=asperitylocal
SlurmctldHost=$(hostname -s)(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=pmix
ReturnToService=2
# scancel's SIGTERM reaches the job first: KillWait seconds to clean up before SIGKILL.
KillWait=10
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF

  munged --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
    --seed-file="$dir/munge/munged.seed"
  slurmctld
  slurmd
  # The node is idle once slurmd has registered with the controller.
  local state=""
  for _ in $(seq 600); do
    state=$(sinfo --noheader --format=%T 2>/dev/null || true)
    [[ $state == idle ]] && break
    sleep 0.1
  done
  if [[ $state != idle ]]; then
    echo "local-cluster: the node is not idle after 60 s (state '${state:-none}'); the logs:" >&2
    tail -n 5 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
    stop >&2
    exit 1
  fi
  echo "local-cluster: $(sinfo --noheader --format='%P %D node(s), %c CPUs, %T') (slurmctld port $ctld_port)"
  echo "export SLURM_CONF=$SLURM_CONF"
}

case $action in
  start) start ;;
  stop) stop ;;
  status)
    if [[ -n $(live_pid "$dir/slurmctld.pid" slurmctld) ]]; then
      sinfo
    else
      echo "local-cluster: not running in $dir"
      exit 1
    fi
    ;;
  *) usage ;;
esac
