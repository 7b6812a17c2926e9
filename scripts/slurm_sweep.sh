#!/usr/bin/env bash
# Runs a sweep as a Slurm job array on a single-machine Slurm cluster that this script starts on
# this host, merges the shards and checks that the merged results.csv is byte-identical to the
# same sweep run unsharded here (results.csv holds no timings: those go to timings.csv).
#
#   1. Installs slurm-wlm and munge (Debian 12) if missing.
#   2. Starts munged and a one-node cluster (slurmctld + slurmd) with its own key, config, ports,
#      state and logs under <work dir>/cluster, so a cluster already running here is left alone
#      and two copies of this script can run at once. Everything started is stopped on exit.
#   3. Submits one array task per shard (the job script is <work dir>/shards.sbatch) and waits.
#   4. `retrace merge`s the shards, runs the sweep unsharded and compares the two results.csv.
# Prints the job id, the array's wall time and the whole run's; exit 0 only if equal.
#
# Usage: scripts/slurm_sweep.sh <retrace binary> <sweep file> <shards> [work dir]
#   The work dir (default: a new /tmp/slurm_sweep.XXXXXX, removed after a successful run) must be
#   absent or empty; given, it is kept. Runs as root (slurmd starts the jobs).
# Environment: SLURM_SWEEP_CPUS (default 1) CPUs per array task, passed to `--jobs`;
#   SLURM_SWEEP_TIMEOUT (s, default 1800) longest wait for the array.
set -euo pipefail

usage() {
  echo "usage: $0 <retrace binary> <sweep file> <shards> [work dir]" >&2
  exit 2
}
if [ $# -lt 3 ] || [ $# -gt 4 ] || ! [[ "$3" =~ ^[1-9][0-9]*$ ]]; then usage; fi
[ -x "$1" ] || { echo "slurm_sweep: not an executable: $1" >&2; exit 2; }
[ -f "$2" ] || { echo "slurm_sweep: no sweep file: $2" >&2; exit 2; }
if [ "$(id -u)" -ne 0 ]; then
  echo "slurm_sweep: must run as root (slurmd starts the jobs)" >&2
  exit 2
fi
retrace=$(realpath "$1")
sweep=$(realpath "$2")
shards=$3
cpus_per_task=${SLURM_SWEEP_CPUS:-1}
timeout=${SLURM_SWEEP_TIMEOUT:-1800}
script_start=$(date +%s.%N)
keep_work=1
if [ $# -eq 4 ]; then
  mkdir -p "$4"
  [ -z "$(ls -A "$4")" ] || { echo "slurm_sweep: work dir is not empty: $4" >&2; exit 2; }
  work=$(realpath "$4")
else
  work=$(mktemp -d /tmp/slurm_sweep.XXXXXX)
  keep_work=0
fi
cluster="$work/cluster"
mkdir -p "$cluster"/{munge,state,spool,log} "$work/logs"

die() {
  echo "FAIL: $*" >&2
  exit 1
}
elapsed() {  # elapsed <start>: seconds since <start> (date +%s.%N), one decimal
  awk -v a="$1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }'
}

# --- 1. Packages ------------------------------------------------------------------------------
missing=()
for tool in slurmctld:slurmctld slurmd:slurmd sbatch:slurm-client munged:munge; do
  command -v "${tool%%:*}" >/dev/null || missing+=("${tool#*:}")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "slurm_sweep: installing slurm-wlm munge (missing: ${missing[*]})"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq >"$work/logs/apt.log" 2>&1 ||
    die "apt-get update failed (see $work/logs/apt.log)"
  # The packages' init scripts would start daemons with the system's config; this script starts
  # its own. Debian's policy-rc.d hook (exit 101) keeps them from starting during the install.
  install_slurm() {
    apt-get install -y -qq --no-install-recommends slurm-wlm munge >>"$work/logs/apt.log" 2>&1 ||
      die "apt-get install slurm-wlm munge failed (see $work/logs/apt.log)"
  }
  policy=/usr/sbin/policy-rc.d
  if [ -e "$policy" ]; then
    install_slurm
  else
    printf '#!/bin/sh\nexit 101\n' >"$policy"
    chmod 755 "$policy"
    trap 'rm -f "$policy"' EXIT
    install_slurm
    rm -f "$policy"
    trap - EXIT
  fi
fi

# --- 2. The cluster ---------------------------------------------------------------------------
# Stop, in order: the array (if still queued or running), slurmd, slurmctld, munged.
job=""
pids=()
cleanup() {
  local code=$?
  trap - EXIT INT TERM
  if [ -n "$job" ] && [ -n "$(squeue -h -j "$job" 2>/dev/null)" ]; then
    scancel "$job" 2>/dev/null || true
    for _ in $(seq 40); do
      [ -z "$(squeue -h -j "$job" 2>/dev/null)" ] && break
      sleep 0.25
    done
  fi
  local i pid
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
    pid=${pids[i]}
    kill "$pid" 2>/dev/null || continue
    for _ in $(seq 40); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.25
    done
    kill -9 "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  if [ "$code" -eq 0 ] && [ "$keep_work" -eq 0 ]; then
    rm -rf "$work"
  elif [ "$code" -ne 0 ]; then
    echo "slurm_sweep: logs kept in $work (cluster/log, logs)" >&2
  fi
  exit "$code"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# Two ports nobody listens on (not Slurm's defaults 6817/6818), so an existing cluster or a
# second copy of this script keeps its own.
listening() { (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
port=$((20000 + RANDOM % 20000))
while listening "$port" || listening $((port + 1)); do port=$((port + 2)); done

host=$(hostname -s)
cpus=$(nproc)
# RealMemory (MB): 90% of the machine's, so that slurmd's own count is never below it.
memory=$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)
munge_socket="$cluster/munge/munge.socket"
[ ${#munge_socket} -lt 100 ] || die "work dir path too long for a socket: $munge_socket"

# munged with this cluster's own key and socket.
mungekey --create --keyfile="$cluster/munge/munge.key" 2>/dev/null ||
  dd if=/dev/urandom of="$cluster/munge/munge.key" bs=1024 count=1 status=none
chmod 600 "$cluster/munge/munge.key"
munged --foreground --force --socket="$munge_socket" --key-file="$cluster/munge/munge.key" \
  --pid-file="$cluster/munge/munged.pid" --seed-file="$cluster/munge/munged.seed" \
  --log-file="$cluster/log/munged.log" >"$cluster/log/munged.stderr" 2>&1 &
pids+=($!)
for _ in $(seq 40); do
  munge -n -S "$munge_socket" 2>/dev/null | unmunge -S "$munge_socket" >/dev/null 2>&1 && break
  sleep 0.25
done
munge -n -S "$munge_socket" | unmunge -S "$munge_socket" >/dev/null ||
  die "munged did not start (see $cluster/log/munged.log)"

export SLURM_CONF="$cluster/slurm.conf"
cat >"$SLURM_CONF" <<EOF
# One-node cluster of scripts/slurm_sweep.sh: everything under $cluster.
ClusterName=retrace
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$munge_socket
StateSaveLocation=$cluster/state
SlurmdSpoolDir=$cluster/spool
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
SlurmctldLogFile=$cluster/log/slurmctld.log
SlurmdLogFile=$cluster/log/slurmd.log
# No cgroups, no accounting database: processes tracked through /proc, plain task launch.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# The node comes up as soon as slurmd registers; its CPUs and memory are taken from here.
ReturnToService=2
SlurmdParameters=config_overrides
MailProg=/bin/true
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=retrace Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF

cluster_start=$(date +%s.%N)
# In the foreground (-D) so that $! is the daemon; they log to the files named above, and what
# goes wrong before a log file is open goes to <daemon>.stderr.
slurmctld -D -c >"$cluster/log/slurmctld.stderr" 2>&1 &
pids+=($!)
slurmd -D >"$cluster/log/slurmd.stderr" 2>&1 &
pids+=($!)
state=""
for _ in $(seq 240); do
  state=$(sinfo -h -N -n "$host" -o %t 2>/dev/null || true)
  [ "$state" = idle ] && break
  for pid in "${pids[@]}"; do
    kill -0 "$pid" 2>/dev/null || die "a daemon exited (see $cluster/log)"
  done
  sleep 0.25
done
[ "$state" = idle ] ||
  die "node $host is '${state:-not known}', not idle, after 60 s (see $cluster/log)"
echo "slurm_sweep: cluster up in $(elapsed "$cluster_start") s: node $host ($cpus CPUs," \
  "$memory MB), ports $port/$((port + 1)), config $SLURM_CONF"

# --- 3. The job array -------------------------------------------------------------------------
# Slurm numbers array tasks from 0, retrace numbers shards from 1 (--shard i/N, 1 <= i <= N).
cat >"$work/shards.sbatch" <<EOF
#!/bin/bash
#SBATCH --job-name=retrace-sweep
#SBATCH --array=0-$((shards - 1))
#SBATCH --cpus-per-task=$cpus_per_task
#SBATCH --output=$work/logs/shard_%a.out
#SBATCH --chdir=$work
exec "$retrace" sweep "$sweep" --shard \$((SLURM_ARRAY_TASK_ID + 1))/$shards \\
    --jobs \$SLURM_CPUS_PER_TASK --out "$work/shard_\$SLURM_ARRAY_TASK_ID" --no-plot
EOF
array_start=$(date +%s.%N)
job=$(sbatch --parsable "$work/shards.sbatch")
job=${job%%;*}
echo "slurm_sweep: submitted job array $job (tasks 0-$((shards - 1)), $cpus_per_task CPU each):" \
  "$work/shards.sbatch"
while [ -n "$(squeue -h -j "$job")" ]; do
  for pid in "${pids[@]}"; do
    kill -0 "$pid" 2>/dev/null || die "a daemon exited while job $job ran (see $cluster/log)"
  done
  [ "$(elapsed "$array_start" | cut -d. -f1)" -lt "$timeout" ] ||
    die "job $job still running after $timeout s"
  sleep 0.5
done
array_time=$(elapsed "$array_start")
# Finished jobs stay known to slurmctld for MinJobAge (300 s): one line per array task.
failed=0
tasks=0
while read -r line; do
  tasks=$((tasks + 1))
  task=$(grep -o '^JobId=[0-9]*' <<<"$line" | cut -d= -f2)
  index=$(grep -o 'ArrayTaskId=[0-9]*' <<<"$line" | cut -d= -f2)
  state=$(grep -o 'JobState=[A-Z_]*' <<<"$line" | cut -d= -f2)
  code=$(grep -o ' ExitCode=[0-9:]*' <<<"$line" | cut -d= -f2)
  runtime=$(grep -o 'RunTime=[0-9:-]*' <<<"$line" | cut -d= -f2)
  echo "  task ${job}_$index (job $task): $state, exit $code, run time $runtime"
  [ "$state" = COMPLETED ] || failed=1
done < <(scontrol -o show job "$job")
[ "$tasks" -eq "$shards" ] || die "job array $job: slurmctld knows $tasks of its $shards tasks"
[ "$failed" -eq 0 ] || die "job array $job: a task did not complete (see $work/logs)"
echo "slurm_sweep: job array $job done in $array_time s (submission to last task's end)"

# --- 4. Merge, unsharded run, comparison ------------------------------------------------------
shard_dirs=()
for ((i = 0; i < shards; i++)); do shard_dirs+=("$work/shard_$i"); done
"$retrace" merge "${shard_dirs[@]}" --out "$work/merged" --no-plot >"$work/logs/merge.out" 2>&1 ||
  die "retrace merge: $(tail -n 1 "$work/logs/merge.out")"
local_start=$(date +%s.%N)
"$retrace" sweep "$sweep" --jobs "$cpus" --out "$work/whole" --no-plot \
  >"$work/logs/whole.out" 2>&1 ||
  die "unsharded sweep: $(tail -n 1 "$work/logs/whole.out")"
echo "slurm_sweep: unsharded sweep (--jobs $cpus) done in $(elapsed "$local_start") s"
cases=$(($(wc -l <"$work/whole/results.csv") - 1))
cmp -s "$work/merged/results.csv" "$work/whole/results.csv" ||
  die "merged results.csv of job $job differs from the unsharded run's:" \
    "diff $work/merged/results.csv $work/whole/results.csv"
# timings.csv (wall time, cpu.*) differs from run to run; only its cases must match.
cmp -s <(cut -d, -f1 "$work/merged/timings.csv") <(cut -d, -f1 "$work/whole/timings.csv") ||
  die "merged timings.csv of job $job holds other cases than the unsharded run's"
echo "slurm_sweep: equal: merged results.csv of $shards shards ($cases cases) is byte-identical" \
  "to the unsharded run's; job $job, array $array_time s, whole script $(elapsed "$script_start") s"
