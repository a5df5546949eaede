#!/usr/bin/env bash
# A one-machine trial of scripts/cluster/surfcomp-screen.sbatch under a real Slurm: not part of
# the test suite (it installs packages and starts daemons, so it needs root).
#
#   bench/slurm_bench.sh [SURFCOMP_BINARY] [WORKDIR]
#
# SURFCOMP_BINARY: the program [build/release/tools/surfcomp]; WORKDIR: where the library, the
# hits, the job's output and Slurm's configuration, state and logs go [a new /tmp/surfcomp-slurm.*].
#
# 1. installs Debian's slurm-wlm and munge when missing (apt-get, non-interactive; the packages'
#    services are not started by the install);
# 2. starts munged, slurmctld and slurmd on this machine (or uses those already running): a
#    one-node cluster from a minimal slurm.conf written to WORKDIR/slurm (the node this host,
#    its CPUs from nproc, no cgroup, SlurmUser root), and waits until the node is idle;
# 3. copies the program and its modules (lib/surfcomp/) to WORKDIR/prefix, so that a rebuild of
#    the build tree during the run does not change the program under test;
# 4. submits the sbatch script with `sbatch --wait` on small data: a library of the 76 Sutherland
#    thermolysin inhibitors and three crystal ligands (../shared/datasets), queries the 1THL and
#    4TMN crystal ligands (without ../shared/datasets: rdkit-data's bzr.sdf from
#    datasets/fetch.sh, queries its first two molecules);
# 5. checks that every hits table has rows, prints the job's wall time and the top hits, and
#    stops the daemons it started. On a failure it prints the ends of the job's output and of the
#    slurmctld and slurmd logs.
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
binary=${1:-$repo/build/release/tools/surfcomp}
work=${2:-}
if [ -z "$work" ]; then work=$(mktemp -d /tmp/surfcomp-slurm.XXXXXX); fi
mkdir -p "$work"
work=$(cd "$work" && pwd)

say() { printf '[slurm_bench %s] %s\n' "$(date +%H:%M:%S)" "$*"; }
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }

slurm_dir=$work/slurm
started=()          # the daemons this script started: "name pid"
job_out=""
job_shown=0       # 1 once the job's output has been printed
ok=0

show_logs() {
  say "FAILED; the ends of the logs:"
  if [ -n "$job_out" ] && [ -f "$job_out" ] && [ "$job_shown" -eq 0 ]; then
    echo "---- $job_out"; tail -n 40 "$job_out"
  fi
  for log in "$slurm_dir/slurmctld.log" "$slurm_dir/slurmd.log"; do
    if [ -f "$log" ]; then echo "---- $log"; tail -n 25 "$log"; fi
  done
  if command -v sinfo >/dev/null 2>&1; then
    echo "---- sinfo -R"; sinfo -R 2>&1 | tail -n 5 || true
  fi
}

stop_daemons() {
  local i name pid
  # In reverse order of starting: slurmd, slurmctld, munged.
  for ((i = ${#started[@]} - 1; i >= 0; i--)); do
    read -r name pid <<<"${started[$i]}"
    if kill -0 "$pid" 2>/dev/null; then
      say "stopping $name (pid $pid)"
      kill -TERM "$pid" 2>/dev/null || true
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
      if kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid" 2>/dev/null || true; fi
    fi
  done
}

finish() {
  local rc=$?
  if [ "$ok" -ne 1 ]; then show_logs; fi
  stop_daemons
  if [ "$ok" -eq 1 ]; then say "PASSED (work folder $work)"; else say "work folder: $work"; fi
  exit "$rc"
}
trap finish EXIT
trap 'exit 130' INT TERM

fail() { say "error: $*" >&2; exit 1; }

[ -x "$binary" ] || fail "no program at $binary (build it: cmake --preset release && cmake --build build/release)"
binary=$(cd "$(dirname "$binary")" && pwd)/$(basename "$binary")

# ---- 1. packages ------------------------------------------------------------------------------
need_install=0
for program in slurmctld slurmd sbatch sinfo munged mpirun; do
  command -v "$program" >/dev/null 2>&1 || need_install=1
done
if [ "$need_install" -eq 1 ]; then
  [ "$(id -u)" -eq 0 ] || fail "slurm-wlm, munge or openmpi-bin is missing and only root can install them"
  say "installing slurm-wlm, munge and openmpi-bin (apt-get)"
  export DEBIAN_FRONTEND=noninteractive
  # The packages would start their services from their install scripts (invoke-rc.d); a
  # policy-rc.d that says no keeps them stopped, this script starts what it needs itself.
  policy=/usr/sbin/policy-rc.d
  own_policy=0
  if [ ! -e "$policy" ]; then
    printf '#!/bin/sh\nexit 101\n' >"$policy" && chmod 755 "$policy" && own_policy=1
  fi
  packages=(slurm-wlm munge openmpi-bin)
  if ! apt-get install -y -q --no-install-recommends "${packages[@]}" >"$work/apt.log" 2>&1; then
    say "apt-get install failed; apt-get update, then again"
    apt-get update -q >>"$work/apt.log" 2>&1 || true
    apt-get install -y -q --no-install-recommends "${packages[@]}" >>"$work/apt.log" 2>&1 || {
      [ "$own_policy" -eq 1 ] && rm -f "$policy"
      tail -n 20 "$work/apt.log"; fail "apt-get install ${packages[*]} failed (log: $work/apt.log)"; }
  fi
  [ "$own_policy" -eq 1 ] && rm -f "$policy"
  say "installed: $(dpkg-query -W -f '${Package} ${Version}, ' slurmctld slurmd munge openmpi-bin)"
fi
say "$(slurmctld -V), $(mpirun --version | head -n 1)"

# ---- 2. munge and Slurm -----------------------------------------------------------------------
if munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
  say "munged: already running, used as it is"
else
  [ "$(id -u)" -eq 0 ] || fail "munged is not running and only root can start it"
  key=/etc/munge/munge.key
  if [ ! -s "$key" ]; then
    say "munge: creating $key"
    mkdir -p /etc/munge
    mungekey --create --keyfile "$key" 2>/dev/null ||
      dd if=/dev/urandom of="$key" bs=1 count=1024 status=none
  fi
  chown munge:munge /etc/munge "$key"; chmod 700 /etc/munge; chmod 400 "$key"
  mkdir -p /run/munge /var/lib/munge /var/log/munge
  chown munge:munge /run/munge /var/lib/munge /var/log/munge
  chmod 755 /run/munge
  say "munged: starting (as user munge)"
  # munged forks into the background and writes its pid file once it is ready.
  rm -f /run/munge/munged.pid
  runuser -u munge -- /usr/sbin/munged
  for _ in $(seq 50); do [ -s /run/munge/munged.pid ] && break; sleep 0.1; done
  [ -s /run/munge/munged.pid ] || fail "munged did not start (see /var/log/munge/munged.log)"
  started+=("munged $(cat /run/munge/munged.pid)")
  munge -n | unmunge >/dev/null || fail "munge does not work (see /var/log/munge/munged.log)"
fi

node=$(hostname -s)
cpus=$(nproc)
if sinfo -h >/dev/null 2>&1 && [ -z "${SLURM_CONF:-}" ] && pgrep -x slurmctld >/dev/null; then
  say "slurmctld: already running, used as it is ($(scontrol show config | awk '/^SLURM_CONF/ {print $3}'))"
  node=$(sinfo -h -N -o %N | head -n 1)
  cpus=$(sinfo -h -N -n "$node" -o %c | head -n 1)
else
  pgrep -x slurmctld >/dev/null && fail "a slurmctld runs that sinfo cannot reach; stop it first"
  pgrep -x slurmd >/dev/null && fail "a slurmd runs without a slurmctld; stop it first"
  [ "$(id -u)" -eq 0 ] || fail "Slurm is not running and only root can start it here"
  mkdir -p "$slurm_dir/state" "$slurm_dir/spool"
  rm -f "$slurm_dir"/*.log
  # 90 % of the memory, so that slurmd never finds less than the configuration says.
  memory=$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)
  cat >"$slurm_dir/slurm.conf" <<CONF
# A one-node cluster for bench/slurm_bench.sh, everything on the loopback address.
ClusterName=surfcomp-trial
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=$slurm_dir/state
SlurmdSpoolDir=$slurm_dir/spool
SlurmctldPidFile=$slurm_dir/slurmctld.pid
SlurmdPidFile=$slurm_dir/slurmd.pid
SlurmctldLogFile=$slurm_dir/slurmctld.log
SlurmdLogFile=$slurm_dir/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
MailProg=/bin/true
# No cgroup: processes are tracked through /proc, and tasks are bound with sched_setaffinity.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/affinity
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
# Keep a finished job's record for 10 minutes (scontrol show job reads its times).
MinJobAge=600
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=trial Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$slurm_dir/slurm.conf
  say "slurm.conf: $SLURM_CONF (node $node, $cpus CPUs, ${memory} MB)"
  say "slurmctld: starting"
  slurmctld -c   # -c: a fresh state (no jobs of an earlier trial)
  for _ in $(seq 100); do scontrol ping 2>/dev/null | grep -q UP && break; sleep 0.2; done
  [ -s "$slurm_dir/slurmctld.pid" ] || fail "slurmctld did not start"
  started+=("slurmctld $(cat "$slurm_dir/slurmctld.pid")")
  scontrol ping | grep -q UP || fail "slurmctld does not answer"
  say "slurmd: starting"
  slurmd
  for _ in $(seq 50); do [ -s "$slurm_dir/slurmd.pid" ] && break; sleep 0.2; done
  [ -s "$slurm_dir/slurmd.pid" ] || fail "slurmd did not start"
  started+=("slurmd $(cat "$slurm_dir/slurmd.pid")")
fi

say "waiting for node $node to be idle"
state=""
for _ in $(seq 120); do
  state=$(sinfo -h -N -n "$node" -o %T 2>/dev/null | head -n 1)
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] || fail "node $node is '$state', not idle"
sinfo

# ---- 3. the program ---------------------------------------------------------------------------
# The program finds its modules (the MPI one among them) in ../lib/surfcomp beside itself.
modules=$(cd "$(dirname "$binary")/.." && pwd)/lib/surfcomp
if [ -d "$modules" ]; then
  rm -rf "${work:?}/prefix"
  mkdir -p "$work/prefix/bin" "$work/prefix/lib"
  cp "$binary" "$work/prefix/bin/surfcomp"
  cp -r "$modules" "$work/prefix/lib/surfcomp"
  surfcomp=$work/prefix/bin/surfcomp
  say "program: $binary, copied with its modules to $work/prefix"
else
  surfcomp=$binary
  say "program: $surfcomp (no lib/surfcomp beside it: used in place)"
fi

# ---- 4. data and the job ----------------------------------------------------------------------
shared=$(cd "$repo/.." && pwd)/shared/datasets
if [ -f "$shared/sutherland/therm_3dqsar.sdf" ] && [ -d "$shared/thermolysin/ligands-common-frame" ]; then
  frame=$shared/thermolysin/ligands-common-frame
  inputs="$shared/sutherland/therm_3dqsar.sdf $frame/1TLP_ligand.sdf $frame/1TMN_ligand.sdf $frame/3TMN_ligand.sdf"
  queries="$frame/1THL_ligand.sdf $frame/4TMN_ligand.sdf"
  data="76 Sutherland thermolysin inhibitors + 3 crystal ligands; queries 1THL, 4TMN"
else
  say "no $shared: rdkit-data's bzr.sdf from datasets/fetch.sh"
  "$repo/datasets/fetch.sh"
  bzr=$repo/datasets/cache/rdkit-data/bzr.sdf
  mkdir -p "$work/queries"
  # The first two molecules of bzr.sdf, one file each.
  awk -v dir="$work/queries" 'BEGIN { n = 1 } n <= 2 { print > (dir "/bzr" n ".sdf") }
       /^\$\$\$\$/ { n++ }' "$bzr"
  inputs=$bzr
  queries="$work/queries/bzr1.sdf $work/queries/bzr2.sdf"
  data="rdkit-data bzr.sdf (163 molecules); queries its first two"
fi

lib=$work/lib/trial.sclib
out=$work/out
rm -rf "${work:?}/lib" "$out"
export SURFCOMP=$surfcomp INPUTS=$inputs QUERIES=$queries LIB=$lib OUT=$out
# Shards of 20 records: the trial's library is built in shards across the job's processes.
export BUILD_OPTIONS="--shard-records 20" SCREEN_OPTIONS="" FUSION=max
# Show the nodes and slots mpirun takes from the allocation.
export MPIRUN_OPTIONS="--display-allocation"

script=$repo/scripts/cluster/surfcomp-screen.sbatch
say "data: $data"
sbatch_args=(--wait --parsable --nodes=1 --ntasks-per-node=1 --cpus-per-task="$cpus"
  --time=00:30:00 --job-name=surfcomp-trial --chdir="$work" --output="$work/job-%j.out")
say "submitting: sbatch ${sbatch_args[*]} $script"
submitted=$(now)
set +e
sbatch "${sbatch_args[@]}" "$script" >"$work/sbatch.out" 2>&1
sbatch_rc=$?
set -e
wait_seconds=$(elapsed "$submitted")
job=$(grep -E '^[0-9]+' "$work/sbatch.out" | head -n 1 | cut -d';' -f1 || true)
[ -n "$job" ] || { cat "$work/sbatch.out"; fail "sbatch did not submit the job"; }
job_out=$work/job-$job.out
say "job $job ended, sbatch --wait returned $sbatch_rc after $wait_seconds s"
record=$(scontrol show job -o "$job" 2>/dev/null || true)
field() { tr ' ' '\n' <<<"$record" | awk -F= -v k="$1" '$1 == k { print $2; exit }'; }
job_state=$(field JobState)
echo "---- $job_out"
cat "$job_out"
echo "----"
job_shown=1
[ "$sbatch_rc" -eq 0 ] || fail "job $job failed (state ${job_state:-unknown}, exit code $(field ExitCode))"

# ---- 5. checks --------------------------------------------------------------------------------
tables=("$out/hits.csv")
for table in "${tables[@]}"; do
  [ -f "$table" ] || fail "no $table"
  rows=$(($(wc -l <"$table") - 1))
  [ "$rows" -gt 0 ] || fail "$table has no rows"
  say "$(basename "$table"): $rows rows; the first three:"
  # The columns rank, name and score, and stage (one query) or query (the best query's number,
  # several queries), found by name in the header.
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; last = col["stage"] ? "stage" : "query"
                     printf "    rank  name  score  %s\n", last; next }
           NR <= 4 { printf "    %s  %s  %s  %s\n", $col["rank"], $col["name"], $col["score"],
                             col[last] ? $col[last] : "" }' "$table"
done
grep -q "ALLOCATED NODES" "$job_out" || fail "mpirun did not print the allocation it got"
say "library: $("$surfcomp" library info "$lib" | head -n 1)"
say "job $job: $job_state, Slurm's RunTime $(field RunTime) (StartTime $(field StartTime)," \
  "EndTime $(field EndTime)); submit to sbatch --wait's return: $wait_seconds s"
grep -E '^(library: built|screen: done|surfcomp-screen: finished)' "$job_out" | sed 's/^/    /'
ok=1
