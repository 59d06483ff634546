#!/usr/bin/env bash
# A single-node Slurm cluster on this machine, for the study tests (tests/cli/slurm.rs)
# and for trying `cablesim study slurm` without a real cluster. Needs root and Debian's
# packages: apt-get install slurm-wlm munge.
#
#   scripts/slurm_local.sh start   # munged, slurmctld, slurmd; waits until sinfo answers
#   scripts/slurm_local.sh stop    # stops what `start` started
#   scripts/slurm_local.sh status
#
# Both are idempotent: `start` with the cluster up does nothing, `stop` with it down
# does nothing. Everything (config, state, logs, pid files) lives in $CABLESIM_SLURM_DIR
# (default /tmp/cablesim-slurm); the config is not written to /etc/slurm, so a machine's
# own Slurm set-up is left alone. Slurm's commands find this cluster through
#
#   export SLURM_CONF=/tmp/cablesim-slurm/slurm.conf
#
# (the test does that itself when SLURM_CONF is unset and this file exists).
#
# The config is the least that runs jobs on a bare machine or a container: one node
# named after `hostname -s` with the machine's CPUs, process tracking without cgroups
# (proctrack/linuxproc, task/none), no accounting, daemons and jobs as root, and
# kill_invalid_depend so that a merge job whose array failed is cancelled instead of
# waiting forever (`sbatch --wait` then returns).
set -euo pipefail

DIR=${CABLESIM_SLURM_DIR:-/tmp/cablesim-slurm}
CONF=$DIR/slurm.conf
export SLURM_CONF=$CONF
HOST=$(hostname -s)

answers() {
  timeout 5 sinfo -h -o %T >/dev/null 2>&1
}

munge_answers() {
  munge -n 2>/dev/null | unmunge >/dev/null 2>&1
}

write_conf() {
  mkdir -p "$DIR/ctld" "$DIR/d"
  cat >"$CONF" <<EOF
# Written by scripts/slurm_local.sh: a single-node cluster for tests.
ClusterName=cablesim
SlurmctldHost=$HOST(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CryptoType=crypto/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
DependencyParameters=kill_invalid_depend
ReturnToService=2
StateSaveLocation=$DIR/ctld
SlurmdSpoolDir=$DIR/d
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MinJobAge=300
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=local Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
}

# Stops the process whose pid a pid file of ours holds, if it is still running.
stop_pid() {
  local f=$1
  if [ -f "$f" ]; then
    local pid
    pid=$(cat "$f")
    if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then
      kill "$pid"
      for _ in $(seq 50); do
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.1
      done
    fi
    rm -f "$f"
  fi
}

start() {
  if [ -f "$CONF" ] && answers; then
    echo "slurm_local: cluster up (SLURM_CONF=$CONF)"
    return
  fi
  for exe in munged slurmctld slurmd sinfo; do
    command -v "$exe" >/dev/null 2>&1 || {
      echo "slurm_local: $exe not found: apt-get install slurm-wlm munge" >&2
      exit 1
    }
  done
  [ "$(id -u)" -eq 0 ] || { echo "slurm_local: run as root" >&2; exit 1; }
  mkdir -p "$DIR"
  if ! munge_answers; then
    # munged runs as its own user, with its socket in /run/munge.
    # munged runs as its own user (with its socket in /run/munge) and writes its pid
    # and log file in a folder of its own.
    mkdir -p /run/munge /var/lib/munge "$DIR/munge"
    chown munge:munge /run/munge /var/lib/munge "$DIR/munge"
    runuser -u munge -- munged --pid-file="$DIR/munge/munged.pid" \
      --log-file="$DIR/munge/munged.log"
    for _ in $(seq 50); do munge_answers && break; sleep 0.1; done
    munge_answers || {
      echo "slurm_local: munged does not answer ($DIR/munge/munged.log)" >&2
      exit 1
    }
  fi
  stop_pid "$DIR/slurmd.pid"
  stop_pid "$DIR/slurmctld.pid"
  write_conf
  # -c: a clean start, without jobs a previous cluster in $DIR left behind.
  slurmctld -c -f "$CONF"
  slurmd -f "$CONF"
  for _ in $(seq 100); do
    if answers && [ -n "$(sinfo -h -N -t idle,mix,alloc -o %N 2>/dev/null)" ]; then
      echo "slurm_local: cluster up: node $HOST, $(nproc) CPUs (SLURM_CONF=$CONF)"
      return
    fi
    sleep 0.2
  done
  echo "slurm_local: the cluster does not answer; see $DIR/slurmctld.log and $DIR/slurmd.log" >&2
  sinfo -N -l >&2 || true
  exit 1
}

stop() {
  stop_pid "$DIR/slurmd.pid"
  stop_pid "$DIR/slurmctld.pid"
  stop_pid "$DIR/munge/munged.pid"
  echo "slurm_local: stopped"
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  status)
    if [ -f "$CONF" ] && answers; then sinfo -N -l; else echo "slurm_local: down"; exit 1; fi
    ;;
  *)
    echo "usage: $0 start|stop|status" >&2
    exit 2
    ;;
esac
