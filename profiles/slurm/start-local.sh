#!/usr/bin/env bash
# Start a single-node Slurm on this machine, for trying the workflow with `--profile profiles/slurm`
# (and for tests/test_slurm.py, which is skipped where Slurm is not running).
#
#   sudo bash profiles/slurm/start-local.sh     # install if missing, configure, start, check
#   sudo bash profiles/slurm/stop-local.sh      # stop the daemons it started, by their process ids
#
# What it does (each step is printed, and skipped when it is already done, so it can be rerun):
#   1. installs slurm-wlm and munge with apt-get if slurmctld, slurmd, sinfo, srun or munged is missing;
#   2. writes a munge key if there is none, and starts munged (as the munge user) unless munge answers;
#   3. writes /etc/slurm/slurm.conf for this host: one node with its real CPU layout and memory (from
#      `slurmd -C`), one default partition `local`, no accounting database (so `sacct` knows no jobs:
#      run the workflow with `--slurm-status-command squeue`); an existing slurm.conf that this script
#      did not write is left alone (the script stops), a stale one that it wrote is replaced;
#   4. starts slurmctld and slurmd unless their pid files name running daemons (they are restarted
#      when the configuration changed);
#   5. waits until `sinfo` shows the node idle and `srun -N1 hostname` answers.
# Needs root and, for step 1, apt-get (Debian/Ubuntu). Environment: SLURM_LOCAL_TIMEOUT (seconds to
# wait in step 5, default 60).
set -euo pipefail

CONF_DIR=/etc/slurm
CONF=$CONF_DIR/slurm.conf
MARK="# Written by profiles/slurm/start-local.sh: a single-node Slurm for local runs."
CTLD_PID=/run/slurmctld.pid
SLURMD_PID=/run/slurmd.pid
MUNGE_KEY=/etc/munge/munge.key
MUNGE_STARTED=/run/slurm-local-munged.pid
TIMEOUT=${SLURM_LOCAL_TIMEOUT:-60}

say() { printf '[start-local] %s\n' "$*"; }
die() { printf '[start-local] error: %s\n' "$*" >&2; exit 1; }

# running <pidfile> <command name>: the pid file names a live process with that command name
running() {
    local pid
    [[ -r $1 ]] || return 1
    pid=$(tr -dc '0-9' < "$1")
    [[ -n $pid ]] && [[ $(ps -o comm= -p "$pid" 2>/dev/null) == "$2" ]]
}

[[ $(id -u) -eq 0 ]] || die "run as root (sudo bash $0)"

# 1. packages
missing=()
for cmd in slurmctld slurmd sinfo srun squeue munged munge unmunge; do
    command -v "$cmd" > /dev/null || missing+=("$cmd")
done
if ((${#missing[@]})); then
    command -v apt-get > /dev/null || die "missing ${missing[*]} and no apt-get: install Slurm and munge by hand"
    say "installing slurm-wlm and munge (missing: ${missing[*]})"
    apt-get update -q
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q slurm-wlm munge
else
    say "slurm-wlm and munge already installed ($(slurmctld -V))"
fi

# 2. munge
if [[ ! -s $MUNGE_KEY ]]; then
    say "writing a munge key: $MUNGE_KEY"
    install -d -o munge -g munge -m 700 /etc/munge
    dd if=/dev/urandom bs=1 count=1024 of="$MUNGE_KEY" status=none
    chown munge:munge "$MUNGE_KEY"
    chmod 400 "$MUNGE_KEY"
else
    say "munge key present: $MUNGE_KEY"
fi
if munge -n 2> /dev/null | unmunge > /dev/null 2>&1; then
    say "munged already answers"
else
    say "starting munged"
    install -d -o munge -g munge -m 755 /run/munge
    install -d -o munge -g munge -m 700 /var/log/munge /var/lib/munge
    if ! runuser -u munge -- munged 2> /dev/null; then
        munged --force    # as root (e.g. where the munge user cannot run it)
    fi
    for _ in $(seq 20); do
        munge -n 2> /dev/null | unmunge > /dev/null 2>&1 && break
        sleep 0.5
    done
    munge -n | unmunge > /dev/null || die "munged does not answer"
    # remembered so that stop-local.sh stops munged only if this script started it
    cp /run/munge/munged.pid "$MUNGE_STARTED" 2> /dev/null || pgrep -x -n munged > "$MUNGE_STARTED" || true
    say "munged started, pid $(cat "$MUNGE_STARTED" 2> /dev/null || echo '?')"
fi

# 3. slurm.conf for this host
host=$(hostname -s)
layout=$(slurmd -C 2> /dev/null | head -n 1 || true)
field() { grep -o "\b$1=[0-9]*" <<< "$layout" | cut -d= -f2; }
cpus=$(field CPUs); mem=$(field RealMemory)
cpus=${cpus:-$(nproc)}
mem=${mem:-$(awk '/^MemTotal:/ {print int($2 / 1024)}' /proc/meminfo)}
topology=""
for key in Boards SocketsPerBoard CoresPerSocket ThreadsPerCore; do
    value=$(field "$key")
    [[ -n $value ]] && topology+=" $key=$value"
done
wanted=$(cat << EOF
$MARK
# Stop it with profiles/slurm/stop-local.sh. No accounting database: sacct knows no jobs.
ClusterName=local
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=$CTLD_PID
SlurmdPidFile=$SLURMD_PID
SlurmctldLogFile=/var/log/slurm/slurmctld.log
SlurmdLogFile=/var/log/slurm/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MinJobAge=300
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus$topology RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
)
changed=0
if [[ -e $CONF ]] && ! grep -qxF "$MARK" "$CONF"; then
    die "$CONF exists and was not written by this script: leaving it (and this machine's Slurm) alone"
fi
if [[ -e $CONF ]] && [[ $(cat "$CONF") == "$wanted" ]]; then
    say "$CONF is up to date (node $host: CPUs=$cpus RealMemory=${mem}MB)"
else
    say "writing $CONF (node $host: CPUs=$cpus$topology RealMemory=${mem}MB, partition local)"
    install -d "$CONF_DIR"
    printf '%s\n' "$wanted" > "$CONF"
    changed=1
fi
mkdir -p /var/spool/slurmctld /var/spool/slurmd /var/log/slurm

# 4. daemons
if ((changed)) && { running $CTLD_PID slurmctld || running $SLURMD_PID slurmd; }; then
    say "configuration changed: restarting the daemons"
    bash "$(dirname "$0")/stop-local.sh" --slurm-only
fi
start_daemon() {  # start_daemon NAME PIDFILE: start it unless it runs, wait for its pid file
    local name=$1 pidfile=$2
    if running "$pidfile" "$name"; then
        say "$name already running, pid $(cat "$pidfile")"
        return
    fi
    "$name"
    for _ in $(seq 20); do running "$pidfile" "$name" && break; sleep 0.5; done
    running "$pidfile" "$name" || die "$name did not start: see /var/log/slurm/$name.log"
    say "$name started, pid $(cat "$pidfile")"
}
start_daemon slurmctld "$CTLD_PID"
start_daemon slurmd "$SLURMD_PID"

# 5. wait for the node, then run a job
say "waiting (up to ${TIMEOUT}s) for node $host to be idle"
state=""
for ((i = 0; i < TIMEOUT * 2; i++)); do
    state=$(sinfo -h -N -n "$host" -o %T 2> /dev/null | head -n 1 || true)
    [[ $state == idle ]] && break
    sleep 0.5
done
[[ $state == idle ]] || die "node $host is '${state:-not reported}', not idle: see /var/log/slurm/slurmd.log"
sinfo
say "srun -N1 hostname"
answer=$(timeout "$TIMEOUT" srun -N1 hostname) || die "srun -N1 hostname failed"
printf '%s\n' "$answer"
say "Slurm is running on $host (slurmctld pid $(cat $CTLD_PID), slurmd pid $(cat $SLURMD_PID));" \
    "stop it with: bash $(dirname "$0")/stop-local.sh"
say "no accounting database here: run the workflow with" \
    "snakemake --profile profiles/slurm --slurm-status-command squeue"
