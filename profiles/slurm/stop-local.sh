#!/usr/bin/env bash
# Stop the single-node Slurm started by profiles/slurm/start-local.sh, by the process ids in its pid
# files: slurmd, slurmctld and, if start-local.sh started it, munged (`--slurm-only` leaves munged
# running). Packages and configuration stay; start-local.sh starts it again.
#
#   sudo bash profiles/slurm/stop-local.sh
set -euo pipefail

MARK="# Written by profiles/slurm/start-local.sh: a single-node Slurm for local runs."
MUNGE_STARTED=/run/slurm-local-munged.pid

say() { printf '[stop-local] %s\n' "$*"; }

[[ $(id -u) -eq 0 ]] || { say "error: run as root (sudo bash $0)" >&2; exit 1; }
if [[ -e /etc/slurm/slurm.conf ]] && ! grep -qxF "$MARK" /etc/slurm/slurm.conf; then
    say "error: /etc/slurm/slurm.conf was not written by start-local.sh: not stopping this machine's Slurm" >&2
    exit 1
fi

# stop <pidfile> <command name>: SIGTERM the process the pid file names (if it is that command), wait
stop() {
    local pid
    if [[ ! -r $1 ]]; then
        say "$2: no pid file $1 (not running)"
        return 0
    fi
    pid=$(tr -dc '0-9' < "$1")
    if [[ -z $pid ]] || [[ $(ps -o comm= -p "$pid" 2> /dev/null) != "$2" ]]; then
        say "$2: pid file $1 names no running $2 (already stopped)"
        rm -f "$1"
        return 0
    fi
    kill -TERM "$pid"
    for _ in $(seq 40); do
        kill -0 "$pid" 2> /dev/null || break
        sleep 0.25
    done
    if kill -0 "$pid" 2> /dev/null; then
        say "$2: pid $pid did not stop after SIGTERM, sending SIGKILL"
        kill -KILL "$pid" 2> /dev/null || true
    fi
    rm -f "$1"
    say "$2: stopped pid $pid"
}

stop /run/slurmd.pid slurmd
stop /run/slurmctld.pid slurmctld
if [[ ${1:-} != --slurm-only ]]; then
    if [[ -e $MUNGE_STARTED ]]; then
        stop "$MUNGE_STARTED" munged
    else
        say "munged: not started by start-local.sh, left running"
    fi
fi
