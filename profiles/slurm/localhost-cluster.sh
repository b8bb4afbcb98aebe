#!/usr/bin/env bash
# A one-node SLURM cluster on localhost, to try profiles/slurm without
# a real cluster (and what tests/workflow/test_slurm.py runs the profile on).
#
#   localhost-cluster.sh install      apt-get install slurm-wlm munge (Debian/Ubuntu; skipped if present)
#   localhost-cluster.sh start        write a slurm.conf, start munged, slurmctld, slurmd; wait for the node
#   localhost-cluster.sh stop         cancel the cluster's jobs, stop the three daemons
#   localhost-cluster.sh status       sinfo and squeue of the cluster
#
# Needs root (slurmd runs jobs as their user) and no systemd: the daemons run in
# the background with their pid files, logs and state in one directory,
# $ASPERITY_SLURM_DIR (default /tmp/asperity-slurm). Outside it, only the
# symbolic link /etc/slurm/slurm.conf -> $ASPERITY_SLURM_DIR/slurm.conf is
# written (srun inside a job finds its configuration there only: Snakemake's
# job step drops SLURM_CONF), and removed again by `stop`; an
# /etc/slurm/slurm.conf of a real installation is never touched (start
# refuses). One node, `localhost`, with $ASPERITY_SLURM_CPUS cores
# (default: all) and $ASPERITY_SLURM_MEM_MB of memory (default: 90 % of the
# machine's), in one partition, `local`. Cgroups are not used
# (proctrack/linuxproc, task/none), so it also runs inside a container; there
# is no accounting database (squeue, not sacct, reports job states, and a
# finished job stays visible for MinJobAge = 600 s).
# Ports: $ASPERITY_SLURMCTLD_PORT (default 6817), $ASPERITY_SLURMD_PORT (6818).
set -euo pipefail

DIR=${ASPERITY_SLURM_DIR:-/tmp/asperity-slurm}
CONF=$DIR/slurm.conf
ETC_CONF=/etc/slurm/slurm.conf
MARK="# Written by localhost-cluster.sh"
SOCKET=$DIR/munge/munge.socket
CTLD_PORT=${ASPERITY_SLURMCTLD_PORT:-6817}
SLURMD_PORT=${ASPERITY_SLURMD_PORT:-6818}
PACKAGES=(slurm-wlm munge)

say() { echo "localhost-cluster: $*" >&2; }
die() { say "$*"; exit 1; }

alive() {  # the pid in file $1 is a running process
    [[ -s $1 ]] && kill -0 "$(cat "$1")" 2>/dev/null
}

installed() {
    local status
    for pkg in slurmctld slurmd slurm-client munge; do
        status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
        [[ $status == "install ok installed" ]] || return 1
    done
}

cmd_install() {
    if installed; then
        say "slurm-wlm and munge already installed"
        return
    fi
    [[ $(id -u) -eq 0 ]] || die "installing needs root (apt-get)"
    command -v apt-get >/dev/null || die "no apt-get: install SLURM (slurmctld, slurmd) and munge with your distribution's packages"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    # policy-rc.d-less containers would try to start the services: they are
    # started by this script instead, so their failure to start is harmless
    apt-get install -y -qq --no-install-recommends "${PACKAGES[@]}" >/dev/null
    installed || die "apt-get did not install ${PACKAGES[*]}"
    say "installed ${PACKAGES[*]}"
}

write_conf() {
    local cpus mem_mb
    cpus=${ASPERITY_SLURM_CPUS:-$(nproc)}
    mem_mb=${ASPERITY_SLURM_MEM_MB:-$(awk '/^MemTotal:/ {printf "%d", $2 / 1024 * 0.9}' /proc/meminfo)}
    cat >"$CONF" <<EOF
$MARK: a one-node cluster on localhost.
ClusterName=asperity
SlurmctldHost=localhost
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$SOCKET
CredType=cred/munge
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
# no cgroups, no systemd: what works inside a container
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
# finished jobs stay visible to squeue (Snakemake's status query) for 10 min
MinJobAge=600
SlurmdTimeout=60
InactiveLimit=0
KillWait=5
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
}

ours() {  # $1 is a symbolic link to a configuration this script wrote (or to nothing)
    [[ -L $1 ]] || return 1
    [[ -e $1 ]] || return 0
    head -n 1 "$1" | grep -q "^$MARK"
}

node_state() {
    SLURM_CONF=$CONF sinfo -h -N -n localhost -o %t 2>/dev/null | head -1 || true
}

cmd_start() {
    [[ $(id -u) -eq 0 ]] || die "start needs root (slurmd)"
    for exe in munged mungekey slurmctld slurmd sinfo; do
        command -v "$exe" >/dev/null || die "$exe not found: run '$0 install' first"
    done
    if alive "$DIR/slurmctld.pid" || alive "$DIR/slurmd.pid" || alive "$DIR/munge/munged.pid"; then
        die "already running in $DIR (stop it first: $0 stop)"
    fi
    if [[ -e $ETC_CONF || -L $ETC_CONF ]] && ! ours "$ETC_CONF"; then
        die "$ETC_CONF exists and was not written by this script: a SLURM installation is configured here; not touching it"
    fi
    local other
    other=$(dirname "$(readlink "$ETC_CONF" 2>/dev/null || echo /nonexistent/x)")
    if [[ $other != "$DIR" ]] && alive "$other/slurmctld.pid"; then
        die "a localhost cluster is already running from $other: stop it first (ASPERITY_SLURM_DIR=$other $0 stop)"
    fi
    mkdir -p "$DIR"/{munge,state,spool,log}
    chmod 755 "$DIR" "$DIR/munge"  # munged wants its socket directory searchable by all
    [[ -s $DIR/munge/munge.key ]] || mungekey --create --keyfile="$DIR/munge/munge.key"
    chmod 600 "$DIR/munge/munge.key"
    write_conf
    mkdir -p "$(dirname "$ETC_CONF")"
    ln -sfn "$CONF" "$ETC_CONF"

    # whatever fails from here on: stop what was started, then exit non-zero
    trap 'say "start failed; stopping what was started"; cmd_stop; exit 1' ERR
    munged --socket="$SOCKET" --key-file="$DIR/munge/munge.key" \
        --pid-file="$DIR/munge/munged.pid" --log-file="$DIR/log/munged.log" \
        --seed-file="$DIR/munge/munged.seed"
    slurmctld -f "$CONF"
    slurmd -f "$CONF" -N localhost

    local state="" i
    for i in $(seq 1 60); do
        state=$(node_state)
        [[ $state == idle ]] && break
        sleep 1
    done
    if [[ $state != idle ]]; then
        say "node not idle after 60 s (state '${state:-none}'); logs in $DIR/log:"
        tail -n 20 "$DIR"/log/*.log >&2 || true
        cmd_stop
        exit 1
    fi
    trap - ERR
    say "cluster up: node localhost idle, partition 'local'; files in $DIR"
}

stop_daemon() {  # stop_daemon NAME PIDFILE: TERM, then KILL after 10 s
    local name=$1 pidfile=$2 pid i
    alive "$pidfile" || return 0
    pid=$(cat "$pidfile")
    kill "$pid" 2>/dev/null || true
    for i in $(seq 1 50); do
        kill -0 "$pid" 2>/dev/null || { say "stopped $name ($pid)"; return 0; }
        sleep 0.2
    done
    kill -9 "$pid" 2>/dev/null || true
    say "killed $name ($pid)"
}

cmd_stop() {
    if alive "$DIR/slurmctld.pid"; then
        # the cluster's own jobs only (a private cluster: all of its jobs)
        SLURM_CONF=$CONF scancel --full --quiet --partition=local 2>/dev/null || true
        local i
        for i in $(seq 1 20); do
            [[ -z $(SLURM_CONF=$CONF squeue -h -t running,completing -o %i 2>/dev/null) ]] && break
            sleep 0.5
        done
    fi
    stop_daemon slurmd "$DIR/slurmd.pid"
    stop_daemon slurmctld "$DIR/slurmctld.pid"
    stop_daemon munged "$DIR/munge/munged.pid"
    if [[ -L $ETC_CONF && $(readlink "$ETC_CONF") == "$CONF" ]]; then
        rm -f "$ETC_CONF"
    fi
}

cmd_status() {
    alive "$DIR/slurmctld.pid" || die "not running ($DIR)"
    SLURM_CONF=$CONF sinfo
    SLURM_CONF=$CONF squeue
}

case ${1:-} in
    install) cmd_install ;;
    start) cmd_start ;;
    stop) cmd_stop ;;
    status) cmd_status ;;
    *) sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2 ;;
esac
