#!/usr/bin/env bash
# A single-node Slurm cluster on localhost, private to one test: a MUNGE key and munged, slurmctld and
# slurmd with a minimal generated slurm.conf, all in the folder DIR, on free ports.
#   slurm_cluster.sh start DIR   starts the daemons, waits for the node to be idle, prints
#                                `export SLURM_CONF=DIR/slurm.conf` (what sbatch, scontrol need)
#   slurm_cluster.sh stop DIR    stops the daemons it started (by their pid files)
# Exit code 77 from start: the daemons cannot run on this machine (the reason on stderr, last line).
set -euo pipefail
cmd=${1:-}
dir=${2:-}
[ -n "$cmd" ] && [ -n "$dir" ] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }

stop() {
  for d in slurmd slurmctld munged; do
    if [ -f "$dir/$d.pid" ]; then
      pid=$(cat "$dir/$d.pid")
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2>/dev/null || true
      rm -f "$dir/$d.pid"
    fi
  done
}

cannot() {
  echo "$1" >&2
  for log in munged slurmctld slurmd; do [ -f "$dir/$log.log" ] && tail -n 5 "$dir/$log.log" >&2; done
  stop
  echo "SKIPPED: a local Slurm cluster cannot start here: $1" >&2
  exit 77
}

if [ "$cmd" = stop ]; then stop; exit 0; fi
[ "$cmd" = start ] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }

for tool in mungekey munged slurmctld slurmd sbatch scontrol sinfo; do
  command -v "$tool" >/dev/null || cannot "$tool is not installed (scripts/install-workflow-deps.sh)"
done
[ "$(id -u)" -eq 0 ] || cannot "slurmd must run as root to start jobs (this is $(id -un))"

mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
chmod 0700 "$dir"
mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
chmod 0700 "$dir/munge"

mungekey --create --keyfile="$dir/munge/munge.key" --force 2>/dev/null || cannot "mungekey could not make a key"
chmod 0600 "$dir/munge/munge.key"
munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
  --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/munged.seed" \
  || cannot "munged did not start"

free_port() { /usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
host=$(hostname -s)
# The node as slurmd sees this machine (CPUs, sockets, cores, memory), under this host's name.
# sed reads slurmd's whole output: head would close the pipe after one line, and under pipefail slurmd's
# SIGPIPE would fail the script.
node=$(slurmd -C | sed -n "1{s/^NodeName=[^ ]*/NodeName=$host NodeAddr=127.0.0.1/;p}")
cat > "$dir/slurm.conf" <<CONF
ClusterName=vesalius-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
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
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
MinJobAge=3600
SlurmctldTimeout=30
SlurmdTimeout=30
$node State=UNKNOWN
PartitionName=cohort Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$dir/slurm.conf"

slurmctld -i -f "$SLURM_CONF" || cannot "slurmctld did not start"
slurmd -f "$SLURM_CONF" -N "$host" || cannot "slurmd did not start"
for _ in $(seq 60); do
  state=$(sinfo -h -n "$host" -o %T 2>/dev/null || true)
  case "$state" in idle*) echo "export SLURM_CONF=$SLURM_CONF"; exit 0 ;; esac
  sleep 1
done
cannot "the node did not become idle within 60 s (state: ${state:-none})"
