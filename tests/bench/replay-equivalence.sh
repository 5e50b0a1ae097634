#!/usr/bin/env bash
# Bench: a recorded run mapped again gives the same maps, about 90 s.
#   tests/bench/replay-equivalence.sh [--seconds 30] [--keep]
# 1. Record: the whole stack (tools/lib/stack.sh, the simulated vehicle) with lcm-logger.
# 2. Map the recording's POINTS.* and POSE again three ways, each with the same config:
#    lcm-logplayer at 1x and at 4x into a live ugv-terrain (on an LCM port of its own, its
#    maps recorded by a second lcm-logger), and `ugv-terrain --replay` (as fast as it goes).
# 3. Compare each with the maps of the recorded run: `ugv-eval diff`, maps paired by the time
#    of the pose they refer to, every cell of one looked up at the same world place in the other.
# Tolerance: none, 0 m in every cell known in both and no cell known in one only. Why: the map
# is a function of its input messages in their order, and of nothing else (maps are published
# on message time, not wall time; no random numbers). lcm-logplayer plays the log in file
# order, which is the order lcm-logger received the messages, and on one host (loopback
# multicast) every subscriber receives the datagrams in the order they were sent. So any
# difference means a message lost or reordered on the way, which is what the bench looks for.
# The live replays are also checked for what ugv-terrain received: its status counters.
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=30
bench_whole_stack replay-equivalence 7312 "$@"
record=$BENCH_WORK/ugv.lcm

sleep "$BENCH_SECONDS"
stop_clean
live_maps=$("$STACK_BIN/ugv-logstat" "$record" --channel TERRAIN_MAP --json | jq -r '.count // 0')
verdict recorded "$([ "$live_maps" -gt 0 ]; echo $?)" "$live_maps maps in the recording"
cp "$STACK_OUT/config/terrain.toml" "$BENCH_WORK/terrain.toml"

diff_check() {  # diff_check NAME LOG: the maps of LOG against the recording's
    check "$1" "$STACK_BIN/ugv-eval" diff "$record" "$2" --pair time --max-dz 0 --max-one-sided 0
}

# lcm-logplayer at SPEED into a live ugv-terrain on port PORT.
replay_live() {
    local speed=$1 port=$2 dir=$BENCH_WORK/replay-${1}x
    stack_init "$dir" "udpm://239.255.76.67:$port?ttl=0&recv_buf_size=${UGV_BENCH_RECV_BUF:-2097152}"
    stack_start_logger -c 'TERRAIN_MAP|STATUS_TERRAIN'
    stack_spawn ugv-terrain "$STACK_BIN/ugv-terrain" --config "$BENCH_WORK/terrain.toml"
    sleep 1
    lcm-logplayer -s "$speed" -e '^(POINTS.*|POSE)$' -l "$STACK_URL" "$record" >"$dir/stderr/lcm-logplayer.log" 2>&1
    sleep 1
    stack_stop
    diff_check "maps ${speed}x" "$dir/ugv.lcm"
    counters_zero "terrain ${speed}x" STATUS_TERRAIN "$dir/ugv.lcm" clouds_malformed poses_rejected_out_of_order bus_decode_failures
}
replay_live 1 7313
replay_live 4 7314

"$STACK_BIN/ugv-terrain" --config "$BENCH_WORK/terrain.toml" --replay "$record" --out "$BENCH_WORK/replay.lcm" \
    >"$BENCH_WORK/stderr/ugv-terrain-replay.log" 2>&1
verdict "--replay" $? "ugv-terrain --replay exit status (log in stderr/ugv-terrain-replay.log)"
diff_check "maps --replay" "$BENCH_WORK/replay.lcm"
bench_end
