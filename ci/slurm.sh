#!/usr/bin/env bash
# Start/stop a real single-node SLURM (munged + slurmctld + slurmd) on Debian/Ubuntu, as root.
#
# Why: tests of `fiberfold map --shard` as a job array need a real scheduler (sbatch --array,
# SLURM_ARRAY_TASK_ID/COUNT), not a mock. No systemd, cgroups or accounting daemon needed.
#
#   ci/slurm.sh start DIR   install packages if missing, write DIR/slurm.conf (also copied to
#                           /etc/slurm/slurm.conf), start the daemons, wait until the node is idle
#   ci/slurm.sh stop DIR    kill the daemons by the pids in DIR/*.pid and wait for them to exit
#
# State, spool, pid and log files all live in DIR. Callers may also `export SLURM_CONF=DIR/slurm.conf`.
set -euo pipefail

[ $# -eq 2 ] && { [ "$1" = start ] || [ "$1" = stop ]; } || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[ "$(id -u)" -eq 0 ] || { echo "$0: must run as root" >&2; exit 1; }
mkdir -p "$2"
DIR=$(cd "$2" && pwd)
CONF=$DIR/slurm.conf
MARK="# written by ci/slurm.sh"
export SLURM_CONF=$CONF

alive() { # pid is running and not a zombie (PID 1 here may not reap daemons)
  [ -r "/proc/$1/stat" ] && [ "$(awk '{print $3}' "/proc/$1/stat" 2>/dev/null)" != Z ]
}

stop_pidfile() { # $1 = pid file, $2 = expected command name (guards against reused pids)
  local pid
  [ -s "$1" ] || return 0
  pid=$(cat "$1")
  if alive "$pid" && [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$2" ]; then
    kill "$pid"
    for _ in $(seq 100); do alive "$pid" || break; sleep 0.2; done
    if alive "$pid"; then echo "$2 ($pid) ignored SIGTERM, sending SIGKILL" >&2; kill -9 "$pid"; fi
  fi
  rm -f "$1"
}

stop() {
  stop_pidfile "$DIR/slurmd.pid" slurmd
  stop_pidfile "$DIR/slurmctld.pid" slurmctld
  stop_pidfile "$DIR/munged.pid" munged # absent if a munged we did not start was reused
}

start() {
  stop # a previous start in the same DIR may have left daemons running
  if ! command -v sbatch >/dev/null || ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq && apt-get install -y -qq slurm-wlm munge >/dev/null
  fi

  # munge: key and dirs, then the daemon (reuse one that already answers, e.g. a system service)
  install -d -o munge -g munge -m 0700 /etc/munge /var/lib/munge /var/log/munge
  install -d -o munge -g munge -m 0755 /var/run/munge
  if [ ! -s /etc/munge/munge.key ]; then
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
    chown munge:munge /etc/munge/munge.key && chmod 0400 /etc/munge/munge.key
  fi
  if ! munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1; then
    munged --force --pid-file="$DIR/munged.pid" --log-file="$DIR/munged.log"
  fi

  rm -rf "$DIR/state" "$DIR/spool" # fresh scheduler state: no jobs left from earlier runs
  mkdir -p "$DIR/state" "$DIR/spool"
  cat >"$CONF" <<EOF
$MARK
ClusterName=ci
SlurmctldHost=localhost
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
NodeName=localhost CPUs=$(nproc) RealMemory=2000 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
  # sbatch/squeue/sinfo in other processes read /etc/slurm/slurm.conf; never clobber a foreign one
  mkdir -p /etc/slurm
  if [ -e /etc/slurm/slurm.conf ] && ! grep -qxF "$MARK" /etc/slurm/slurm.conf; then
    echo "warning: /etc/slurm/slurm.conf not ours, left alone; export SLURM_CONF=$CONF" >&2
  else
    cp "$CONF" /etc/slurm/slurm.conf
  fi

  slurmctld -f "$CONF"
  slurmd -f "$CONF" -N localhost
  for _ in $(seq 120); do
    [ "$(sinfo -h -o %T 2>/dev/null)" = idle ] && { echo "slurm up; SLURM_CONF=$CONF"; return 0; }
    sleep 0.5
  done
  echo "slurm node did not become idle within 60 s: $(sinfo -h -o %T 2>&1)" >&2
  tail -n 20 "$DIR/slurmctld.log" "$DIR/slurmd.log" "$DIR/munged.log" >&2 2>/dev/null || true
  exit 1
}

"$1"
