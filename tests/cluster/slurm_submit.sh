#!/usr/bin/env bash
# hilite submit on a real single-node Slurm (slurm-wlm 22.05 + munge, as Debian 12 ships them), started here as
# root with its own configuration, state and logs in a temporary folder and its ports on loopback, and stopped
# at the end, also on failure: `hilite submit EXPERIMENT --shards 4 --wait` gives the rows of `hilite run`
# (timing columns aside); then an array task cancelled mid-run (scancel), `hilite submit --resume --wait`
# completes with the same rows. Usage: slurm_submit.sh HILITE_EXE
set -euo pipefail
hilite=$(realpath "$1")
for p in munged slurmctld slurmd sbatch squeue scancel sinfo; do
  command -v "$p" >/dev/null || { echo "SKIP: $p not found (Debian packages slurm-wlm and munge; scripts/quickstart installs them)"; exit 77; }
done
[[ $(id -u) == 0 ]] || { echo "SKIP: a single-node Slurm is started as root here (slurmd runs jobs as their user)"; exit 77; }
# slurmd 22.05 initializes its cgroup plugin whatever the configuration and stops without a cgroup file system
# (seen in a debootstrap chroot with /sys mounted but not /sys/fs/cgroup).
grep -q ' /sys/fs/cgroup ' /proc/mounts ||
  { echo "SKIP: no cgroup file system at /sys/fs/cgroup, which slurmd 22.05 needs (a chroot: mount --rbind /sys)"; exit 77; }

tmp=$(mktemp -d /tmp/hilite-slurm.XXXXXX)
stop() {
  local rc=$?
  if ((rc != 0 && rc != 77)); then  # what the daemons said, before their folder goes
    for log in "$tmp"/*.log; do [[ -e $log ]] && { echo "--- $log"; tail -8 "$log"; }; done
  fi
  for pid in "$tmp"/slurmd.pid "$tmp"/slurmctld.pid "$tmp"/munged.pid; do
    [[ -s $pid ]] && kill "$(cat "$pid" 2>/dev/null)" 2>/dev/null || true
  done
  for pid in "$tmp"/slurmd.pid "$tmp"/slurmctld.pid "$tmp"/munged.pid; do  # gone within 10 s, or killed
    [[ -s $pid ]] || continue
    local n
    n=$(cat "$pid" 2>/dev/null) || continue  # a daemon removes its pid file as it exits
    for i in $(seq 100); do kill -0 "$n" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$n" 2>/dev/null || true
  done
  rm -rf "$tmp"
}
trap stop EXIT

# Two free loopback ports (bound and released by the kernel's choice).
read -r ctld_port d_port < <(/usr/bin/python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')

mkdir -p "$tmp/ctld" "$tmp/d"
head -c 1024 /dev/urandom > "$tmp/munge.key"
chmod 400 "$tmp/munge.key"
munged --force --key-file="$tmp/munge.key" --socket="$tmp/munge.socket" --pid-file="$tmp/munged.pid" \
  --log-file="$tmp/munged.log" --seed-file="$tmp/munged.seed"
cat > "$tmp/slurm.conf" <<CONF
ClusterName=hilitetest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
SlurmctldParameters=enable_configless=no
AuthType=auth/munge
AuthInfo=socket=$tmp/munge.socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$tmp/ctld
SlurmdSpoolDir=$tmp/d
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 RealMemory=1000 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$tmp/slurm.conf
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF" -N localhost
for i in $(seq 60); do
  [[ $(sinfo -h -o %T 2>/dev/null) == idle ]] && break
  sleep 0.5
done
[[ $(sinfo -h -o %T) == idle ]] || { echo "FAIL: the node did not come up"; tail -n 5 "$tmp"/*.log; exit 1; }
echo "single-node Slurm up: slurmctld on 127.0.0.1:$ctld_port, slurmd on :$d_port, state in $tmp"

# The rows of two result folders, timing columns aside, equal?
same_rows() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import json, sys
timing = {"render_ms", "measure_ms", "time_ms", "startup_ms"}
def rows(d):
    return sorted((json.dumps({k: v for k, v in json.loads(l).items() if k not in timing}, sort_keys=True)
                   for l in open(d + "/results.jsonl")), key=lambda r: json.loads(r)["config"])
a, b = rows(sys.argv[1]), rows(sys.argv[2])
print(f"{len(a)} rows against {len(b)}; equal: {a == b}")
sys.exit(0 if a == b and a else 1)
PY
}

cd "$tmp"
"$hilite" run eccentricity -o single >/dev/null
"$hilite" submit eccentricity --shards 4 -o cluster --wait
same_rows single cluster

# An experiment slow enough to cancel a task mid-run: 48 configurations at 1024^2.
cat > slow.toml <<'TOML'
[experiment]
name = "slow"
[scene.camera]
size = "1024"
[scene.material]
model = "ggx"
[[sweep]]
key = "material.roughness"
values = [0.05, 0.1, 0.2, 0.3]
[[sweep]]
key = "light.incidence"
range = [0, 55, 5]
TOML
"$hilite" run slow.toml -o slow_single >/dev/null
"$hilite" submit slow.toml --shards 4 -o slow
job=$(/usr/bin/python3 -c 'import json; print(json.load(open("slow/slurm/submit.json"))["array_job"])')
for i in $(seq 600); do  # shard 2 cancelled once it has written a row
  [[ -s slow/shards/2/results.jsonl ]] && break
  sleep 0.05
done
scancel "${job}_2"
rows_at_cancel=$(wc -l < slow/shards/2/results.jsonl || echo 0)
echo "shard 2 cancelled with $rows_at_cancel of 12 rows"
for i in $(seq 600); do  # until the array has left the queue (the merge stays pending: afterok can never be met)
  [[ -z $(squeue -h -j "$job" -o %i) ]] && break
  sleep 0.1
done
"$hilite" status slow
if "$hilite" submit --resume -o slow --wait; then :; else echo "FAIL: submit --resume --wait"; tail -n 3 slow/slurm/logs/*.err; exit 1; fi
same_rows slow_single slow
