#!/usr/bin/env bash
# A real one-node Slurm cluster on localhost, for tests: munged, slurmctld and
# slurmd from Debian's munge and slurm-wlm packages (scripts/install-deps.sh
# --cluster), started directly as background daemons (no systemd, no cgroups),
# so it works as root in a container without an init system.
#
#   scripts/slurm/local-cluster.sh up        start (a fast no-op when already up);
#                                            waits until the node is idle
#   scripts/slurm/local-cluster.sh down      cancel all jobs, stop the daemons
#   scripts/slurm/local-cluster.sh status    sinfo + squeue, or "not running" (exit 1)
#   scripts/slurm/local-cluster.sh selftest  sbatch, array, dependency, srun and
#                                            scancel checks against a running cluster
#
# Clients (sbatch, squeue, srun, scancel, sinfo) need SLURM_CONF: `up` prints
# the export line, and `. $ASBUILT_SLURM_DIR/env.sh` sets it.
#
# All state lives in ASBUILT_SLURM_DIR (default /tmp/asbuilt-slurm; keep the
# path short: the munge socket's path must fit in 108 bytes): slurm.conf,
# env.sh, munge/ (its own key, made on first `up`; seed), run/ (munge socket,
# pid files), spool/ (slurmctld state, slurmd spool), log/. No system path is
# written. Cluster "asbuilt-local": one node (this host, `hostname -s`, with
# `nproc` CPUs), partition "debug", ports 6817 (slurmctld) and 6818 (slurmd).
#
# `up` and `down` need root: slurmd runs jobs as the submitting user, and
# munged's key must belong to the daemons' user (SlurmUser=root). As another
# user, run them with sudo (sudo ASBUILT_SLURM_DIR=... scripts/slurm/local-cluster.sh up);
# then any user can submit jobs after sourcing env.sh.
set -euo pipefail

DIR=${ASBUILT_SLURM_DIR:-/tmp/asbuilt-slurm}
CONF=$DIR/slurm.conf
SOCKET=$DIR/run/munge.socket.2
NODE=$(hostname -s)
DAEMONS=(munged slurmctld slurmd)
export SLURM_CONF=$CONF

say() { echo "local-cluster: $*" >&2; }

# The pid of a running daemon (from its pid file; not a zombie), or nothing.
pid_of() {
  local f=$DIR/run/$1.pid pid stat
  [[ -r $f ]] || return 0
  pid=$(<"$f")
  [[ $pid =~ ^[0-9]+$ ]] || return 0
  stat=$(cat "/proc/$pid/stat" 2>/dev/null) || return 0 # "pid (comm) state ..."
  [[ $stat == "$pid ($1"*") "[^Z]* ]] && echo "$pid"
  return 0
}

# The node's state as sinfo sees it ("idle", "mixed", "down*", ...), or nothing.
node_state() { timeout 10 sinfo -h -N -n "$NODE" -o %T 2>/dev/null | head -1 || true; }

need_root() {
  if [[ $(id -u) -ne 0 ]]; then
    say "'$1' needs root (slurmd runs jobs as their users; SlurmUser=root). Run:"
    say "  sudo ASBUILT_SLURM_DIR=$DIR $0 $1"
    exit 1
  fi
  for bin in munged slurmctld slurmd sinfo; do
    command -v "$bin" >/dev/null || { say "$bin missing: run bash scripts/install-deps.sh --cluster"; exit 1; }
  done
}

write_conf() {
  local mem
  mem=$(awk '/^MemTotal:/ {print int($2 / 1024)}' /proc/meminfo)
  cat >"$CONF" <<EOF
# Written by scripts/slurm/local-cluster.sh; rewritten on every 'up'.
ClusterName=asbuilt-local
SlurmctldHost=$NODE(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$SOCKET
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MailProg=/bin/true
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# Schedule at once after a submit or a job's end (the default waits up to 3 s).
SchedulerParameters=batch_sched_delay=0
SlurmdParameters=config_overrides
PropagateResourceLimits=NONE
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
MessageTimeout=10
InactiveLimit=0
KillWait=5
MinJobAge=300
Waittime=0
StateSaveLocation=$DIR/spool/slurmctld
SlurmdSpoolDir=$DIR/spool/slurmd
SlurmctldPidFile=$DIR/run/slurmctld.pid
SlurmdPidFile=$DIR/run/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF
  echo "export SLURM_CONF=$CONF" >"$DIR/env.sh"
}

logs_tail() {
  for f in "$DIR"/log/*; do
    [[ -s $f ]] && { echo "==> $f <=="; tail -n 20 "$f"; }
  done >&2
}

cmd_up() {
  need_root up
  if [[ -n $(pid_of munged) && -n $(pid_of slurmctld) && -n $(pid_of slurmd) ]] &&
    [[ $(node_state) =~ ^(idle|mixed|allocated)$ ]]; then
    say "already up ($DIR)"
    echo "export SLURM_CONF=$CONF"
    return 0
  fi
  local start=$SECONDS
  mkdir -p "$DIR"/{run,log,spool/slurmctld,spool/slurmd,munge}
  chmod 755 "$DIR" "$DIR/run" "$DIR/log"
  chmod 700 "$DIR/munge"
  write_conf
  # munge: our own key (munged insists it is owned by its user, mode 0400/0600).
  if [[ ! -s $DIR/munge/munge.key ]]; then
    dd if=/dev/urandom of="$DIR/munge/munge.key" bs=1024 count=1 status=none
  fi
  chmod 400 "$DIR/munge/munge.key"
  if [[ -z $(pid_of munged) ]]; then
    rm -f "$SOCKET" "$SOCKET.lock"
    munged --socket="$SOCKET" --key-file="$DIR/munge/munge.key" \
      --pid-file="$DIR/run/munged.pid" --seed-file="$DIR/munge/munged.seed" \
      --log-file="$DIR/log/munged.log" </dev/null >>"$DIR/log/munged.out" 2>&1
  fi
  # slurmctld -c: start from a clean slate (no jobs or node state of an earlier run).
  [[ -n $(pid_of slurmctld) ]] ||
    slurmctld -c -f "$CONF" </dev/null >>"$DIR/log/slurmctld.out" 2>&1
  [[ -n $(pid_of slurmd) ]] ||
    slurmd -f "$CONF" -N "$NODE" </dev/null >>"$DIR/log/slurmd.out" 2>&1
  # Wait for the node to register and become idle.
  local state="" up="" dead=""
  while ((SECONDS - start < 60)); do
    state=$(node_state)
    dead=$(for d in "${DAEMONS[@]}"; do [[ -n $(pid_of "$d") ]] || echo "$d"; done | xargs)
    [[ $state == idle && -z $dead ]] && up=1 && break
    ((SECONDS - start >= 5)) && [[ -n $dead ]] && break # a daemon exited: fail fast
    sleep 1
  done
  if [[ -z $up ]]; then
    say "node $NODE not idle after $((SECONDS - start)) s (state: ${state:-no answer}${dead:+; not running: $dead}); daemon logs:"
    logs_tail
    say "stop what did start with: $0 down"
    exit 1
  fi
  say "up in $((SECONDS - start)) s: node $NODE ($(nproc) CPUs), partition debug; state in $DIR"
  say "clients need SLURM_CONF (or: . $DIR/env.sh):"
  echo "export SLURM_CONF=$CONF"
}

# Sends TERM to a pid, waits up to 10 s, then KILL.
stop_pid() {
  local pid=$1
  kill "$pid" 2>/dev/null || return 0
  for _ in $(seq 50); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.2
  done
  say "pid $pid ignored TERM; killing it"
  kill -9 "$pid" 2>/dev/null || true
}

# slurmstepd processes of this cluster (they hold its slurmd log open); they
# outlive slurmd by design, so `down` ends them itself.
stepds() {
  local p fd
  for p in $(pgrep -x slurmstepd || true); do
    for fd in /proc/"$p"/fd/*; do
      [[ $(readlink "$fd" 2>/dev/null) == "$DIR/log/"* ]] && { echo "$p"; break; }
    done
  done
  return 0
}

cmd_down() {
  need_root down
  local pid p
  if [[ -n $(pid_of slurmctld) ]]; then
    # Cancel every job, and give their steps a moment to end.
    timeout 10 squeue -h -o %A 2>/dev/null | xargs -r timeout 10 scancel 2>/dev/null || true
    for _ in $(seq 50); do
      [[ -z $(stepds) ]] && break
      sleep 0.2
    done
  fi
  for p in $(stepds); do stop_pid "$p"; done
  for d in slurmd slurmctld munged; do
    pid=$(pid_of "$d")
    [[ -n $pid ]] && { stop_pid "$pid"; say "stopped $d ($pid)"; }
  done
  rm -f "$DIR"/run/*.pid
  say "down"
}

cmd_status() {
  if [[ -z $(pid_of slurmctld) ]]; then
    echo "not running ($DIR)"
    return 1
  fi
  for d in "${DAEMONS[@]}"; do echo "$d: $(pid_of "$d" | sed 's/^/pid /')"; done
  timeout 10 sinfo
  timeout 10 squeue
}

# --- selftest: one line per check; exit 1 when any fails. ---
fails=0
check() { # check NAME COMMAND...: runs COMMAND, prints ok/FAIL with its output's last line
  local name=$1 out
  shift
  if out=$("$@" 2>&1); then
    echo "ok    $name${out:+: $(tail -n 1 <<<"$out")}"
  else
    echo "FAIL  $name: $(tail -n 3 <<<"$out" | tr '\n' ' ')"
    fails=$((fails + 1))
  fi
}

# Waits (up to 60 s) until job ID, all its array tasks, ended; prints their states.
wait_job() {
  local states
  for _ in $(seq 120); do
    states=$(scontrol -o show job "$1" | grep -o 'JobState=[A-Z_]*' | sort -u | xargs)
    grep -qE 'PENDING|RUNNING|CONFIGURING|COMPLETING|SUSPENDED' <<<"$states" || break
    sleep 0.5
  done
  echo "$states"
}

t_batch() {
  local id
  id=$(sbatch --parsable -o "$T/batch.out" --wrap hostname) || return 1
  [[ $(wait_job "$id") == JobState=COMPLETED ]] || { echo "job $id: $(wait_job "$id")"; return 1; }
  [[ $(<"$T/batch.out") == "$NODE" ]] || { echo "job $id printed '$(<"$T/batch.out")'"; return 1; }
  echo "job $id printed $(<"$T/batch.out")"
}

t_array() {
  local id got
  # shellcheck disable=SC2016 # $SLURM_ARRAY_TASK_ID is the task's, not ours
  id=$(sbatch --parsable --array=0-3 -o "$T/array_%a.out" --wrap 'echo $SLURM_ARRAY_TASK_ID') || return 1
  [[ $(wait_job "$id") == JobState=COMPLETED ]] || { echo "job $id: $(wait_job "$id")"; return 1; }
  got=$(cat "$T"/array_{0..3}.out | tr '\n' ' ')
  [[ $got == "0 1 2 3 " ]] || { echo "job $id tasks printed '$got'"; return 1; }
  echo "job $id tasks printed $got"
}

t_dependency() {
  local a b
  a=$(sbatch --parsable -o /dev/null --wrap "sleep 2; touch $T/a.done") || return 1
  # b fails unless it runs after a has finished.
  b=$(sbatch --parsable --dependency=afterok:"$a" -o "$T/dep.out" \
    --wrap "test -f $T/a.done && echo ran after $a") || return 1
  [[ $(wait_job "$b") == JobState=COMPLETED ]] || { echo "job $b: $(wait_job "$b")"; return 1; }
  echo "job $b: $(<"$T/dep.out")"
}

t_concurrent() {
  local a b state
  a=$(sbatch --parsable -n 1 -o /dev/null --wrap 'sleep 30') || return 1
  b=$(sbatch --parsable -n 1 -o /dev/null --wrap 'sleep 30') || { scancel "$a"; return 1; }
  for _ in $(seq 40); do
    state=$(squeue -h -j "$a,$b" -o %T | sort -u | tr '\n' ' ')
    [[ $state == "RUNNING " ]] && break
    sleep 0.5
  done
  scancel "$a" "$b"
  [[ $state == "RUNNING " ]] || { echo "jobs $a $b: $state"; return 1; }
  echo "jobs $a and $b running at once"
}

t_srun() {
  local out
  out=$(timeout 60 srun -n 2 hostname) || return 1
  [[ $(wc -l <<<"$out") -eq 2 ]] || { echo "printed: $out"; return 1; }
  echo "printed $(tr '\n' ' ' <<<"$out")"
}

t_scancel() {
  local id pid state=""
  rm -f "$T/sleep.pid"
  id=$(sbatch --parsable -o /dev/null --wrap "echo \$\$ >$T/sleep.pid; exec sleep 100") || return 1
  for _ in $(seq 60); do
    [[ -s $T/sleep.pid ]] && break
    sleep 0.5
  done
  [[ -s $T/sleep.pid ]] || { echo "job $id never started"; scancel "$id"; return 1; }
  pid=$(<"$T/sleep.pid")
  scancel "$id"
  for _ in $(seq 40); do
    state=$(scontrol show job "$id" | grep -o 'JobState=[A-Z]*' || true)
    [[ $state == JobState=CANCELLED ]] && ! kill -0 "$pid" 2>/dev/null && break
    sleep 0.5
  done
  [[ $state == JobState=CANCELLED ]] || { echo "job $id: $state"; return 1; }
  ! kill -0 "$pid" 2>/dev/null || { echo "job $id's sleep ($pid) still runs"; return 1; }
  echo "job $id $state, its sleep ($pid) gone"
}

cmd_selftest() {
  [[ -n $(node_state) ]] || { say "not running: $0 up first"; exit 1; }
  T=$(mktemp -d "${TMPDIR:-/tmp}/asbuilt-slurm-selftest.XXXXXX")
  cd "$T"
  check "sbatch --wrap hostname" t_batch
  check "sbatch --array=0-3" t_array
  check "--dependency=afterok" t_dependency
  check "two 1-CPU jobs at once" t_concurrent
  check "srun -n 2 hostname" t_srun
  check "scancel of sleep 100" t_scancel
  cd /
  rm -rf "$T"
  ((fails == 0)) || { say "$fails check(s) failed"; exit 1; }
}

case "${1:-}" in
  up) cmd_up ;;
  down) cmd_down ;;
  status) cmd_status ;;
  selftest) cmd_selftest ;;
  *) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2; exit 2 ;;
esac
