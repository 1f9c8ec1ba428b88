#!/usr/bin/env bash
# `shearcut tune` through a real Slurm: installs Slurm and munge from Debian's
# packages (if missing), starts a one-node cluster on localhost, submits a
# small sweep as a job array of 4 tasks (scripts/tune.sbatch), waits, merges
# the shards, and checks that the merged results.csv equals a local run's
# byte for byte. Stops the daemons it started (by pid) on exit.
#
# Needs root on Debian 12 (apt-get, munge's key, daemons). SHEARCUT names the
# binary to use (default: target/release/shearcut, built here).
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)
export PATH=$PATH:/usr/sbin:/sbin

if [[ $(id -u) -ne 0 ]]; then
    echo "slurm_local.sh: needs root (installs packages and starts daemons)" >&2
    exit 2
fi
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    echo "== installing slurm-wlm and munge"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurm-wlm munge >/dev/null
fi
if [[ -z ${SHEARCUT:-} ]]; then
    cargo build --release --bin shearcut
    SHEARCUT=$repo/target/release/shearcut
fi
export SHEARCUT

# Seconds since $1 (a `date +%s%N` stamp), to 0.1 s.
since() {
    local ms=$((($(date +%s%N) - $1) / 1000000))
    printf '%d.%d' $((ms / 1000)) $((ms % 1000 / 100))
}
started=$(date +%s%N)
work=$(mktemp -d /tmp/shearcut-slurm.XXXXXX)
pids=()
munge_pid=""
cleanup() {
    local rc=$?
    for pid in "${pids[@]}"; do
        kill "$pid" 2>/dev/null || true
    done
    for pid in "${pids[@]}"; do
        wait "$pid" 2>/dev/null || true
    done
    if [[ -n $munge_pid ]]; then
        kill "$munge_pid" 2>/dev/null || true
    fi
    if [[ $rc -ne 0 ]]; then
        echo "== failed; logs in $work" >&2
        tail -n 20 "$work"/*.log "$work"/out/*.out 2>/dev/null >&2 || true
    else
        rm -rf "$work"
    fi
}
trap cleanup EXIT

# munge: runs as user munge, /run/munge owned by munge, a key in /etc/munge.
mkdir -p /run/munge /var/log/munge /var/lib/munge /etc/munge
chown munge:munge /run/munge /var/log/munge /var/lib/munge /etc/munge
if [[ ! -s /etc/munge/munge.key ]]; then
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
fi
chown munge:munge /etc/munge/munge.key
chmod 0400 /etc/munge/munge.key
if ! munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1; then
    rm -f /run/munge/munged.pid
    runuser -u munge -- munged
    for _ in $(seq 50); do
        [[ -s /run/munge/munged.pid ]] && break
        sleep 0.1
    done
    munge_pid=$(cat /run/munge/munged.pid)
fi

# A one-node cluster.
host=$(hostname)
mkdir -p "$work/state" "$work/spool" "$work/out"
cat >"$work/slurm.conf" <<EOF
ClusterName=shearcut-local
SlurmctldHost=$host
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SlurmctldPort=${SLURMCTLD_PORT:-6817}
SlurmdPort=${SLURMD_PORT:-6818}
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=tune Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$work/slurm.conf
slurmctld -D -i -f "$SLURM_CONF" >"$work/slurmctld.stdout.log" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >"$work/slurmd.stdout.log" 2>&1 &
pids+=($!)
for i in $(seq 300); do
    state=$(sinfo -h -o %T 2>/dev/null | head -n 1 || true)
    [[ $state == idle* ]] && break
    if [[ $i -eq 300 ]]; then
        echo "the node did not come up (state: ${state:-none})" >&2
        exit 1
    fi
    sleep 0.2
done
echo "== one-node Slurm up on $host ($(sinfo -V)) in $(since "$started") s"

# A small sweep: the potato cuboid 6 mm deep, MPC at two weights and
# pressing, two stiffnesses: 6 runs, dealt to 4 array tasks.
sed -e 's/name = "fig7-potato"/name = "small-potato"/' -e 's/depth = 0.02 /depth = 0.006 /' \
    config/scenarios/fig7-potato.toml >"$work/small-potato.toml"
printf '\n[plant]\nsegments = 2\n\n[section]\nrow_spacing = 0.0005\n' >>"$work/small-potato.toml"
cat >"$work/sweep.toml" <<'EOF'
scenarios = ["small-potato.toml"]
[variants]
youngs_modulus_scale = [0.9, 1.1]
[[controllers]]
kind = "mpc"
grid = { "mpc.deformation_weight" = [0.0, 100.0] }
[[controllers]]
kind = "press"
EOF

submitted=$(date +%s%N)
(cd "$work/out" && sbatch --wait --array=0-3 --output="$work/out/task-%a.out" \
    "$repo/scripts/tune.sbatch" "$work/sweep.toml" "$work/array" >/dev/null)
echo "== job array done in $(since "$submitted") s"
"$SHEARCUT" tune merge "$work"/array/shard-*-of-4 --out "$work/merged" >/dev/null
"$SHEARCUT" tune "$work/sweep.toml" --out "$work/local" >/dev/null
if ! cmp "$work/merged/results.csv" "$work/local/results.csv"; then
    echo "merged results differ from the local run's" >&2
    diff "$work/merged/results.csv" "$work/local/results.csv" >&2 || true
    exit 1
fi
rows=$(($(wc -l <"$work/local/results.csv") - 1))
echo "== Slurm test passed: 4 array tasks merged to the local run's results.csv byte for byte ($rows runs); $(since "$started") s end to end (install and build excluded)"
