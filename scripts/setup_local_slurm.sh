#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for trying scripts/slurm_batch.sh and for its test
# (tests/batch/slurm_batch_test.sh): installs Debian's slurm-wlm and munge when missing, writes
# /etc/slurm/slurm.conf (or $SLURM_CONF) for this host (all its cores, one partition "local"), and
# starts munged, slurmctld and slurmd unless they already run. Needs root (or sudo). Idempotent.
# A slurm.conf it did not write (a real cluster's) is left alone: it stops, before installing or
# starting anything, unless given --force (which keeps the old file as slurm.conf.bak).
#   scripts/setup_local_slurm.sh            set up and start
#   scripts/setup_local_slurm.sh --force    the same, replacing a slurm.conf of another origin
#   scripts/setup_local_slurm.sh --stop     stop the three daemons it started
set -euo pipefail

conf=${SLURM_CONF:-/etc/slurm/slurm.conf}
marker="# Written by gmg's scripts/setup_local_slurm.sh: one node, this machine."
force=0
[ "${1:-}" = "--force" ] && force=1
if [ "${1:-}" != "--stop" ] && [ -e "$conf" ] && [ "$(head -n 1 "$conf" 2>/dev/null)" != "$marker" ]; then
  if [ $force -eq 0 ]; then
    echo "setup_local_slurm: $conf exists and was not written by this script (a cluster's own configuration?);" \
      "left unchanged. Give --force to replace it (the old file is kept as $conf.bak)." >&2
    exit 1
  fi
  backup_needed=1
else
  backup_needed=0
fi

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
run() { "${sudo_cmd[@]}" "$@"; }
pidfile_dir=/run/gmg-local-slurm

if [ "${1:-}" = "--stop" ]; then
  for d in slurmd slurmctld munged; do
    f=$pidfile_dir/$d.pid
    if [ -s "$f" ] && run kill "$(cat "$f")" 2>/dev/null; then echo "setup_local_slurm: stopped $d"; fi
    run rm -f "$f"
  done
  exit 0
fi

missing=()
for p in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup_local_slurm: installing ${missing[*]}"
  run apt-get update -qq
  DEBIAN_FRONTEND=noninteractive run apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

host=$(hostname -s)
cpus=$(nproc)
memory=$(awk '/MemTotal/ {print int($2 / 1024 * 0.9)}' /proc/meminfo)
run mkdir -p "$(dirname "$conf")" /var/lib/slurm/slurmctld /var/lib/slurm/slurmd /var/log/slurm "$pidfile_dir"
run chown -R slurm:slurm /var/lib/slurm /var/log/slurm
if [ "$backup_needed" -eq 1 ]; then
  run cp -p "$conf" "$conf.bak"
  echo "setup_local_slurm: replacing $conf (the old one is $conf.bak)"
fi
run tee "$conf" >/dev/null <<CONF
$marker
ClusterName=gmg-local
SlurmctldHost=$host
SlurmUser=slurm
StateSaveLocation=/var/lib/slurm/slurmctld
SlurmdSpoolDir=/var/lib/slurm/slurmd
SlurmctldPidFile=$pidfile_dir/slurmctld.pid
SlurmdPidFile=$pidfile_dir/slurmd.pid
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF

running() { [ -s "$pidfile_dir/$1.pid" ] && run kill -0 "$(cat "$pidfile_dir/$1.pid")" 2>/dev/null; }
if ! running munged; then
  run mkdir -p /run/munge && run chown munge:munge /run/munge
  [ -s /etc/munge/munge.key ] || run mungekey --create
  run runuser -u munge -- /usr/sbin/munged --pid-file=/run/munge/munged.pid
  run cp /run/munge/munged.pid "$pidfile_dir/munged.pid"
fi
running slurmctld || run /usr/sbin/slurmctld
running slurmd || run /usr/sbin/slurmd
for _ in $(seq 1 30); do
  if sinfo -h -o '%T' 2>/dev/null | grep -qE '^(idle|mixed|allocated)'; then
    echo "setup_local_slurm: node $host is up ($cpus CPUs, partition local)"
    exit 0
  fi
  sleep 1
done
echo "setup_local_slurm: the node did not come up; see /var/log/slurm/" >&2
exit 1
