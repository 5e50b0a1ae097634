#!/usr/bin/env bash
# Bench (not CI): each daemon's resident memory in the whole simulated stack, the figures
# the units' MemoryHigh=/MemoryMax= are sized from (docs/deploy.md "Memory limits"). About
# 3 minutes; --seconds S changes the 120 s of sampling.
#   tests/bench/memory.sh [--seconds 120] [--keep]
# The stack as on the vehicle: the device daemons with [realtime] lock_memory = true and
# SCHED_FIFO 50, as systemd/config has them (mlockall makes every mapping resident at once:
# thread stacks and malloc arenas count in full), ugv-sim world driving its scenario, and
# lcm-logger with its preload. VmRSS of each process is read every second; printed per
# process: the median of the second half (steady), the largest sample and VmHWM (the peak
# resident set) at the end. A check per daemon: VmHWM is below its installed unit's
# MemoryHigh= (it never reaches the throttling point in normal running).
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=120
bench_flags none "$@"
bench_begin memory 7736
for d in lms gps imu servo; do stack_set "$d" $'[realtime]\nfifo_priority = 50\nlock_memory = true'; done
bench_start_stack
samples=$BENCH_WORK/rss
mkdir -p "$samples"
echo "# sampling VmRSS of ${!STACK_PIDS[*]} for $BENCH_SECONDS s"
for ((k = 0; k < BENCH_SECONDS; k++)); do
    for name in "${!STACK_PIDS[@]}"; do
        rss=$(awk '/^VmRSS:/ {print $2}' "/proc/${STACK_PIDS[$name]}/status" 2>/dev/null)
        [ -n "$rss" ] && echo "$rss" >>"$samples/$name"
    done
    sleep 1
done
declare -A hwm=()
for name in "${!STACK_PIDS[@]}"; do
    hwm[$name]=$(awk '/^VmHWM:/ {print $2}' "/proc/${STACK_PIDS[$name]}/status" 2>/dev/null)
done
# MemoryHigh= of a unit in MiB (K, M, G suffixes), empty when it sets none.
unit_high_mib() {
    local f=$BENCH_DIR/../../systemd/$1 v
    v=$(sed -n 's/^MemoryHigh=//p' "$f" 2>/dev/null)
    case $v in
        *K) echo $(( ${v%K} / 1024 )) ;; *M) echo "${v%M}" ;; *G) echo $(( ${v%G} * 1024 )) ;; *) echo "" ;;
    esac
}
printf "%-14s %10s %10s %10s %12s\n" process steady_MiB max_MiB VmHWM_MiB MemoryHigh
for name in $(printf "%s\n" "${!STACK_PIDS[@]}" | sort); do
    f=$samples/$name
    [ -s "$f" ] || continue
    n=$(wc -l <"$f")
    steady=$(tail -n $(( (n + 1) / 2 )) "$f" | sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}')
    max=$(sort -n "$f" | tail -n 1)
    unit=${name}.service
    [[ $name == ugv-lms || $name == ugv-nodscan ]] && unit=${name}@.service
    high=$(unit_high_mib "$unit")
    printf "%-14s %10.1f %10.1f %10.1f %12s\n" "$name" "$(bc -l <<<"$steady / 1024")" "$(bc -l <<<"$max / 1024")" \
        "$(bc -l <<<"${hwm[$name]:-0} / 1024")" "${high:+${high}M}"
    if [[ $name == ugv-* ]]; then
        verdict "$name below MemoryHigh" "$([ -n "$high" ] && [ "${hwm[$name]:-0}" -lt $(( high * 1024 )) ]; echo $?)" \
            "VmHWM $(( ${hwm[$name]:-0} / 1024 )) MiB, MemoryHigh=${high:-unset}M"
    fi
done
stop_clean
bench_end
