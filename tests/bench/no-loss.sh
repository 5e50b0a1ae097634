#!/usr/bin/env bash
# Bench (not CI): no lost data over 10 minutes of the full stack at real time, and the LCM
# receive buffer that 225 kB maps at 20 Hz need. About 12 minutes; --seconds S shortens.
#   tests/bench/no-loss.sh [--seconds 600] [--keep]
# Part 1, for --seconds: the whole stack (tools/lib/stack.sh: the simulated vehicle) with
# lcm-logger, LCM ttl=0 with recv_buf_size=2 MiB (the configuration of docs/deploy.md), the
# device daemons real-time as on the vehicle (UGV_BENCH_REALTIME=0: not), then
# the checks of logger-integrity.sh on the log: seq contiguous from 0 on every channel, every
# message each daemon counted as published is in the log, every daemon's drop counters 0.
# Part 2, for max(30, S/10) s: the stack again, ugv-terrain at publish_hz = 20 with a
# 27.4 m x 27.4 m map at 0.2 m (137 x 137 cells, 225 kB per map), the daemons on Debian's
# default receive buffer, and six lcm-loggers side by side, each with another receive buffer
# (the default, then recv_buf_size = 256 KiB .. 4 MiB; the kernel allots twice the request
# and caps it at 2 x net.core.rmem_max). A map is one LCM message in 4 fragments; one lost
# fragment loses the map. Lost maps per logger = maps ugv-terrain published (its last
# status) - maps in that logger's log. Reports the smallest loss-free buffer.
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=600
echo "# net.core.rmem_max = $(cat /proc/sys/net/core/rmem_max), rmem_default = $(cat /proc/sys/net/core/rmem_default)"

# ---- Part 1: nothing lost at real time
# The device daemons as on the vehicle (systemd/config): SCHED_FIFO 50, memory locked
# (UGV_BENCH_REALTIME=0: normal scheduling). The simulator runs at normal priority.
bench_flags none "$@"
bench_begin no-loss 7315
if [ "${UGV_BENCH_REALTIME:-1}" = 1 ]; then
    for d in lms gps imu servo; do stack_set "$d" $'[realtime]\nfifo_priority = 50\nlock_memory = true'; done
fi
bench_start_stack
echo "# part 1: the whole stack for $BENCH_SECONDS s"
sleep "$BENCH_SECONDS"
stop_clean
log_seq_contiguous "$STACK_OUT/ugv.lcm"
log_has_published "$STACK_OUT/ugv.lcm"
log_no_drops "$STACK_OUT/ugv.lcm"

# ---- Part 2: the receive buffer for 225 kB maps at 20 Hz
buffer_seconds=$(( BENCH_SECONDS / 10 > 30 ? BENCH_SECONDS / 10 : 30 ))
part2=$BENCH_WORK/buffer
base_url="udpm://239.255.76.67:7316?ttl=0"
stack_init "$part2" "$base_url"
sizes=(default 262144 524288 1048576 2097152 4194304)
for size in "${sizes[@]}"; do
    url=$base_url
    [ "$size" = default ] || url="$base_url&recv_buf_size=$size"
    stack_spawn "lcm-logger-$size" lcm-logger --lcm-url="$url" -c 'TERRAIN_MAP|STATUS_TERRAIN' -f "$part2/maps-$size.lcm"
done
stack_set terrain 'publish_hz = 20.0'
stack_set terrain 'extent_x_m = 27.4'
stack_set terrain 'extent_y_m = 27.4'
world=()
stack_has_world && world=(--duration "$((buffer_seconds + 30))")
stack_start_devices "${world[@]}" || { verdict devices 1 "the devices did not come up (part 2)"; bench_end; exit; }
stack_start_daemons
echo "# part 2: maps at 20 Hz for $buffer_seconds s, six loggers"
sleep "$buffer_seconds"
stack_stop

published=$(stack_counter STATUS_TERRAIN maps_published "$part2/maps-4194304.lcm")
kb=$("$STACK_BIN/ugv-logstat" "$part2/maps-4194304.lcm" --channel TERRAIN_MAP --json | jq -r '.bytes_per_msg / 1000 | floor')
verdict map-rate "$([ "${published:-0}" -ge $(( buffer_seconds * 20 * 8 / 10 )) ]; echo $?)" \
    "ugv-terrain published ${published:-?} maps of $kb kB in ~$buffer_seconds s (want >= 80 % of 20 Hz)"
smallest=
for size in "${sizes[@]}"; do
    got=$("$STACK_BIN/ugv-logstat" "$part2/maps-$size.lcm" --channel TERRAIN_MAP --json | jq -r '.count // 0')
    lost=$(( ${published:-0} - got ))
    echo "# recv_buf_size $size: $got of ${published:-?} maps recorded, $lost lost"
    [ "$size" = default ] && continue
    # the smallest size from which on every larger one was loss-free too
    if [ "$lost" -eq 0 ]; then smallest=${smallest:-$size}; else smallest=; fi
done
verdict buffer "$([ -n "$smallest" ]; echo $?)" \
    "smallest loss-free recv_buf_size: ${smallest:-none of the sizes tried} (225 kB maps at 20 Hz)"
bench_end
