#!/bin/bash
# docs/sweeps.md's recipes run for real: a one-node Slurm (munged, slurmctld and slurmd from
# Debian's slurm-wlm, started here with a private configuration in WORK, no systemd) runs a tiny
# grid as a job array, one `boxpile sweep --shard K/N` per task; GNU parallel runs the same shards
# on this machine; `boxpile sweep-merge` merges each, and both merges must hold the unsharded
# sweep's cells exactly, timings aside. Every daemon started here is stopped here, by its pid.
#
#   slurm_sweep_test.sh BOXPILE FIXTURES WORK
set -euo pipefail
boxpile=$1 fixtures=$2 work=$3
shards=3

for tool in munged slurmctld slurmd sbatch squeue sinfo parallel python3; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool not found: run scripts/install-deps"; exit 1; }
done
rm -rf "$work"
mkdir -p "$work"/{munge,socket,state,spool,log}
work=$(cd "$work" && pwd)

pids=()
stop() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
}
trap stop EXIT
fail() {
  echo "FAIL: $*"
  for f in "$work"/log/*; do echo "--- $f"; tail -n 20 "$f"; done
  exit 1
}

# --- munge: a private key and socket (munged wants the key's folder private, the socket's open) ---
chmod 700 "$work/munge"
chmod 755 "$work/socket"
head -c 1024 /dev/urandom > "$work/munge/munge.key"
chmod 400 "$work/munge/munge.key"
socket=$work/socket/munge.socket
munged --foreground --force --socket="$socket" --key-file="$work/munge/munge.key" \
  --log-file="$work/log/munged.log" --pid-file="$work/munge/munged.pid" --seed-file="$work/munge/seed" \
  > "$work/log/munged.out" 2>&1 &
pids+=($!)

# --- slurm: one node, this machine, on two free loopback ports ---
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
node=$(hostname -s)
cpus=$(nproc)
export SLURM_CONF=$work/slurm.conf
cat > "$SLURM_CONF" <<CONF
ClusterName=boxpiletest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done
[ -S "$socket" ] || fail "munged made no socket"
slurmctld -D -f "$SLURM_CONF" > "$work/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N "$node" -f "$SLURM_CONF" > "$work/log/slurmd.out" 2>&1 &
pids+=($!)
state=""
for _ in $(seq 100); do
  state=$(sinfo -h -o %T 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.2
done
[ "$state" = idle ] || fail "the node is not idle after 20 s (state: '$state')"

# --- the grid: 4 cells, a fraction of a second each ---
cat > "$work/grid.json" <<GRID
{"scenes": ["$fixtures/scenes/stack_5.json"], "duration": 0.25, "repetitions": 1,
 "engines": {"own": {"contact_passes": [2, 10]}, "ode": {"iterations": [5, 20]}}}
GRID
"$boxpile" sweep "$work/grid.json" --report "$work/whole" > "$work/log/whole.out" 2>&1 || fail "the unsharded sweep"

# --- Slurm: docs/sweeps.md's job array ---
cat > "$work/sweep.sbatch" <<'JOB'
#!/bin/bash
#SBATCH --job-name=boxpile-sweep
#SBATCH --cpus-per-task=1
I=$((SLURM_ARRAY_TASK_ID + 1))
"$BOXPILE" sweep "$GRID" --shard "$I/$SHARDS" --report "$OUT/$I"
echo $? > "$OUT/$I.exit"
JOB
mkdir -p "$work/slurm-shards"
job=$(BOXPILE=$boxpile GRID=$work/grid.json SHARDS=$shards OUT=$work/slurm-shards \
      sbatch --parsable --array=0-$((shards - 1)) --chdir="$work" --output="$work/log/task-%a.out" "$work/sweep.sbatch")
for _ in $(seq 300); do
  [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break
  sleep 0.2
done
[ -z "$(squeue -h -j "$job")" ] || fail "job array $job still queued after 60 s"
for k in $(seq "$shards"); do
  [ "$(cat "$work/slurm-shards/$k.exit" 2>/dev/null)" = 0 ] || fail "array task $k did not end with exit 0"
done
"$boxpile" sweep-merge "$work"/slurm-shards/*/ --report "$work/slurm-merged" > "$work/log/merge.out" 2>&1 ||
  fail "sweep-merge of the Slurm shards"

# --- GNU parallel: docs/sweeps.md's one-machine recipe ---
parallel -j 2 "$boxpile" sweep "$work/grid.json" --shard {}/$shards --report "$work/parallel-shards/{}" \
  ::: $(seq 1 $shards) > "$work/log/parallel.out" 2>&1 || fail "the shards under GNU parallel"
"$boxpile" sweep-merge "$work"/parallel-shards/*/ --report "$work/parallel-merged" >> "$work/log/merge.out" 2>&1 ||
  fail "sweep-merge of the parallel shards"

# --- each merge holds the unsharded sweep's cells, timings aside ---
python3 - "$work" "$shards" <<'CHECK' || fail "a merged sweep differs from the unsharded one"
import json, sys
work, shards = sys.argv[1], int(sys.argv[2])
TIMINGS = {"us_per_step", "us_per_simulated_second"}  # the only timings of a cell (validation/sweep/sweep.cpp)
def cells(report):
    doc = json.load(open(f"{work}/{report}/sweep.json"))
    return doc, [{k: v for k, v in c.items() if k not in TIMINGS} for c in doc["cells"]]
whole_doc, whole = cells("whole")
assert len(whole) == 4, f"{len(whole)} cells in the unsharded sweep, expected 4"
for merged in ("slurm-merged", "parallel-merged"):
    doc, got = cells(merged)
    assert got == whole, f"{merged}: cells differ from the unsharded sweep's"
    assert sorted(doc["shards"]) == [f"{k}/{shards}" for k in range(1, shards + 1)], doc["shards"]
    print(f"{merged}: {len(got)} cells from shards {sorted(doc['shards'])}, equal to the unsharded sweep's")
CHECK
echo "PASS: the job array ($shards tasks) and GNU parallel ($shards shards) merge to the unsharded sweep"
