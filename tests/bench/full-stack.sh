#!/usr/bin/env bash
# Bench: the whole stack on the simulated vehicle (or real devices), about 50 s.
#   tests/bench/full-stack.sh [--seconds 20] [--lms PATH --gps PATH --imu PATH --servo TRANSPORT] [--keep]
# tools/lib/stack.sh starts lcm-logger, the devices (`ugv-sim world` when ugv-sim has it, else
# the four separate emulators; real ones where given) and all eight daemons with their
# default configs. Checks:
#   running NAME      each daemon reports RUNNING within 30 s of its start (ugv-pose may be
#                     DEGRADED on the parked emulators: the heading is not observable);
#   rate CHANNEL      live, for --seconds at once: the documented rate (docs/<daemon>.md) and
#                     no seq gap (ugv-expect);
#   map               the last TERRAIN_MAP of the log is 150x150 cells and has known cells;
#   map-accuracy      (the simulated vehicle only) `ugv-eval compare --truth` of the last map
#                     against the world's true height field: RMSE < 0.05 m, |bias| < 0.05 m;
#   obstacles         (the same) over all maps, >= 80 % of the obstacle cells in view detected;
#   clean-stop        every process exits 0 on SIGTERM.
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=20
bench_whole_stack full-stack 7310 "$@"

# Parked (the separate emulators: a GPS that does not move) ugv-pose cannot observe the
# heading and says DEGRADED (2) while it publishes poses; the world drives.
for d in "${STACK_DAEMONS[@]}"; do
    also=1
    [ "$d" = pose ] && [ "$STACK_SIM" = emulators ] && also=2
    running "running ugv-$d" "STATUS_${d^^}" 30 $also
done

# channel, rate (Hz) as documented for the default configs
while read -r ch rate; do
    expect_bg "rate $ch" --channel "$ch" --for "$BENCH_SECONDS" --rate "$rate" --max-gap 0
done <<'RATES'
LMS_SCAN 35:40
SERVO_STATE 95:105
IMU 48:53
GPS_FIX 3.5:4.5
GPS_VEL 3.5:4.5
POINTS 35:40
POSE 9.5:10.5
TERRAIN_MAP 1.7:2.3
STATUS_TERRAIN 0.8:1.2
ARCS 1.7:2.3
TRAVERSABILITY_MAP 1.7:2.3
RATES
expect_collect
stop_clean

log=$STACK_OUT/ugv.lcm
map=$("$STACK_BIN/ugv-dump" --log "$log" --channel TERRAIN_MAP | tail -n 1 |
    jq -r '.fields | [.nx, .ny, ([.mean_z[] | select(. != null)] | length)] | join(" ")')
read -r nx ny known <<<"${map:-0 0 0}"
verdict map "$([ "$nx" = 150 ] && [ "$ny" = 150 ] && [ "$known" -gt 0 ]; echo $?)" \
    "last map ${nx}x$ny cells, $known known"
if [ "$STACK_SIM" = world ] && [ -f "$STACK_OUT/run/truth.hf" ]; then
    # Bounds: on this machine the default scenario's last map had RMSE 0.011-0.026 m and bias
    # -0.013 to +0.023 m against the truth: about 2x.
    eval_line=$("$STACK_BIN/ugv-eval" compare "$log" --truth "$STACK_OUT/run/truth.hf" 2>&1 | tail -n 1)
    read -r rmse bias < <(jq -r '"\(.rmse_m // 99) \(.bias_m // 99)"' <<<"$eval_line" 2>/dev/null || echo "99 99")
    verdict map-accuracy "$(awk -v r="${rmse:-99}" -v b="${bias:-99}" 'BEGIN { exit !(r < 0.05 && b > -0.05 && b < 0.05) }'; echo $?)" \
        "last map against the truth: $eval_line (want rmse < 0.05 m, |bias| < 0.05 m)"
    # The scenario's box and wall: over every map with obstacle cells in view, the share the
    # map shows above half the 0.2 m threshold (measured here: 96-98 %).
    read -r seen detected < <("$STACK_BIN/ugv-eval" compare "$log" --truth "$STACK_OUT/run/truth.hf" --all |
        jq -rs '"\(map(.obstacle_cells) | add // 0) \(map(.obstacles_detected) | add // 0)"')
    if [ "${seen:-0}" -gt 0 ]; then
        verdict obstacles "$([ $((detected * 10)) -ge $((seen * 8)) ]; echo $?)" \
            "$detected of $seen obstacle cells in view detected, over all maps (want >= 80 %)"
    fi
fi
"$STACK_BIN/ugv-render" "$log" --out "$BENCH_WORK/map-last.png" >/dev/null 2>&1 && echo "# map picture: $BENCH_WORK/map-last.png"
bench_end
