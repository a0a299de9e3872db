#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# A one-node Slurm cluster on loopback for gnssemu sweep (docs/sweep.md
# §Local Slurm): Debian's slurmctld, slurmd and munge (tools/install-deps.sh),
# all state, sockets and logs in one folder, nothing in /etc. Needs root
# (slurmd runs jobs as their user). No systemd, no cgroups.
#
#   tools/slurm-local.sh start   start munged, slurmctld, slurmd; wait until the node is idle
#   tools/slurm-local.sh stop    cancel every job, drain, stop the daemons, remove the folder
#   tools/slurm-local.sh env     print the export that points Slurm's clients at it
#
# Folder: $GNSSEMU_SLURM_DIR (default /tmp/gnssemu-slurm). Clients find the
# cluster through SLURM_CONF=$GNSSEMU_SLURM_DIR/slurm.conf.
set -euo pipefail

DIR=${GNSSEMU_SLURM_DIR:-/tmp/gnssemu-slurm}
CONF=$DIR/slurm.conf
CTLD_PORT=${GNSSEMU_SLURM_PORT:-16817}
SLURMD_PORT=$((CTLD_PORT + 1))
export SLURM_CONF=$CONF

die() { echo "slurm-local: $*" >&2; exit 1; }

pid_of() { [ -s "$1" ] && cat "$1" || true; }

alive() {
  # A zombie (a PID 1 that does not reap) is not alive.
  local pid=$1
  [ -n "$pid" ] && [ -r "/proc/$pid/stat" ] || return 1
  local state
  state=$(sed -E 's/^[0-9]+ \(.*\) ([A-Za-z]).*/\1/' "/proc/$pid/stat" 2>/dev/null || echo Z)
  [ "$state" != Z ]
}

stop_pid() {
  local pid=$1 name=$2
  alive "$pid" || return 0
  kill "$pid" 2>/dev/null || true
  for _ in $(seq 1 50); do alive "$pid" || return 0; sleep 0.1; done
  echo "slurm-local: $name ($pid) did not stop on TERM; killing" >&2
  kill -9 "$pid" 2>/dev/null || true
}

start() {
  for p in munged slurmctld slurmd sbatch squeue scontrol sinfo; do
    command -v "$p" >/dev/null || die "$p not found: run tools/install-deps.sh (slurmctld slurmd slurm-client munge)"
  done
  [ "$(id -u)" -eq 0 ] || die "needs root (slurmd starts jobs as their user)"
  if alive "$(pid_of "$DIR/slurmctld.pid")"; then die "already running in $DIR (tools/slurm-local.sh stop first)"; fi
  # Slurm binds what the host name resolves to: it must be loopback.
  local addr
  addr=$(getent ahostsv4 "$(hostname)" | awk 'NR == 1 { print $1 }')
  case "$addr" in
    127.*) ;;
    *) die "$(hostname) resolves to '${addr:-nothing}', not 127.x: add '127.0.1.1 $(hostname)' to /etc/hosts" ;;
  esac
  rm -rf "$DIR"
  mkdir -p "$DIR/state" "$DIR/spool" "$DIR/munge"
  chmod 0700 "$DIR/munge"
  # munge: our own key and socket, root-owned as munged demands.
  dd if=/dev/urandom of="$DIR/munge/munge.key" bs=1024 count=1 status=none
  chmod 0400 "$DIR/munge/munge.key"
  munged --socket="$DIR/munge/munge.socket" --key-file="$DIR/munge/munge.key" \
    --pid-file="$DIR/munge/munged.pid" --log-file="$DIR/munge/munged.log" --seed-file="$DIR/munge/munged.seed" --force
  local cpus mem
  cpus=$(nproc)
  mem=$(awk '/MemTotal/ { print int($2 / 1024 / 2) }' /proc/meminfo)
  cat >"$CONF" <<CONF
# Written by tools/slurm-local.sh: one node on loopback for gnssemu sweep.
ClusterName=gnssemu
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$DIR/munge/munge.socket
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
# No cgroups: processes tracked by parentage; no task binding or accounting.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$DIR/jobcomp.txt
# One CPU per array task, not the whole node.
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
CommunicationParameters=NoCtldInAddrAny,NoInAddrAny
MpiDefault=none
SchedulerParameters=sched_interval=1
MinJobAge=600
MaxArraySize=100001
MaxJobCount=200000
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
  slurmctld -f "$CONF"
  slurmd -f "$CONF" -N localhost
  for _ in $(seq 1 100); do
    if [ "$(sinfo -h -o %T 2>/dev/null | head -1)" = idle ]; then
      echo "slurm-local: cluster up in $DIR ($cpus CPUs); export SLURM_CONF=$CONF" >&2
      return 0
    fi
    sleep 0.1
  done
  sinfo >&2 || true
  tail -5 "$DIR/slurmctld.log" "$DIR/slurmd.log" >&2 || true
  die "the node did not become idle in 10 s (logs in $DIR)"
}

stop() {
  [ -d "$DIR" ] || return 0
  if alive "$(pid_of "$DIR/slurmctld.pid")"; then
    # Stopping the daemons does not stop running jobs: cancel and drain first.
    scontrol update NodeName=localhost State=DRAIN Reason=stopping >/dev/null 2>&1 || true
    scancel --full $(squeue -h -o %A 2>/dev/null) >/dev/null 2>&1 || true
    for _ in $(seq 1 100); do
      [ -z "$(squeue -h -o %A 2>/dev/null)" ] && break
      sleep 0.1
    done
  fi
  stop_pid "$(pid_of "$DIR/slurmd.pid")" slurmd
  stop_pid "$(pid_of "$DIR/slurmctld.pid")" slurmctld
  # slurmstepd of a job that outlived its slurmd.
  for p in $(pgrep -x slurmstepd 2>/dev/null || true); do
    if grep -qs "$DIR" "/proc/$p/cmdline" "/proc/$p/environ" 2>/dev/null; then stop_pid "$p" slurmstepd; fi
  done
  stop_pid "$(pid_of "$DIR/munge/munged.pid")" munged
  rm -rf "$DIR"
  echo "slurm-local: stopped" >&2
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  env) echo "export SLURM_CONF=$CONF" ;;
  *) echo "usage: $0 start|stop|env" >&2; exit 2 ;;
esac
