#!/usr/bin/env bash
# Bench: the nodding servo (CiA 402 drive on CAN) and ugv-servo alone, about 25 s.
#   tests/bench/servo-nod.sh [--device socketcan:can0 | --device slcan:/dev/ttyACM0@115200] [--seconds 10] [--keep]
# Default: against `ugv-sim servo --pty` (a drive behind an slcan adapter). A real drive:
# --device TRANSPORT or UGV_SERVO_TRANSPORT=TRANSPORT (the `transport` key of ugv-servo;
# node id and limits from the daemon's defaults), the axis free to nod 2..30 deg.
# The daemon runs its default profile: CONSTANT_RATE 30 deg/s between 2 and 30 deg, a nod
# period of 2 x 28 / 30 = 1.87 s. UGV_BENCH_SERVO_RATE (MIN:MAX Hz, default 95:105: TPDO 100 Hz).
# Checks: RUNNING, SERVO_STATE rate and seq gaps, every sample enabled and without fault and
# inside the limits, the nod covering its range at its period, the error counters, a clean
# stop (the daemon halts and switches the power stage off).
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=10
rate=${UGV_BENCH_SERVO_RATE:-95:105}
bench_one_device servo-nod 7304 servo "$@"

expect state-rate --channel SERVO_STATE --for "$BENCH_SECONDS" --rate "$rate" --max-gap 0
# Operation enabled (5), CONSTANT_RATE (2), no fault; angle inside 2..30 deg with 0.5 deg of
# overshoot allowed (0.0262 and 0.5236 rad).
expect state-content --channel SERVO_STATE --for 3 \
    --where 'cia402_state == 5 && profile == 2 && fault == 0 && angle > 0.0262 && angle < 0.5323'
# The nod over 4 s (two periods): lowest and highest angle within 1 deg of the limits, and
# the period from the upward crossings of the middle (16 deg = 0.2793 rad).
"$STACK_BIN/ugv-dump" --lcm-url "$STACK_URL" --channel SERVO_STATE --count 400 --timeout 8 >"$BENCH_WORK/nod.jsonl"
read -r lo hi period < <(jq -rs '[.[] | {t: .utime, a: .fields.angle}] as $s
    | ([range(1; $s | length) | select($s[. - 1].a < 0.2793 and $s[.].a >= 0.2793) | $s[.].t]) as $up
    | [($s | map(.a) | min), ($s | map(.a) | max),
       (if ($up | length) > 1 then (($up[-1] - $up[0]) / (($up | length) - 1) / 1e6) else 0 end)]
    | map(tostring) | join(" ")' "$BENCH_WORK/nod.jsonl")
in_range() { awk -v v="$1" -v a="$2" -v b="$3" 'BEGIN { exit !(v >= a && v <= b) }'; }
verdict nod-range "$(in_range "${lo:-9}" 0.0175 0.0524 && in_range "${hi:-0}" 0.5061 0.5411; echo $?)" \
    "angle from ${lo:-?} to ${hi:-?} rad (want 2 and 30 deg = 0.0349 and 0.5236, +/- 1 deg)"
verdict nod-period "$(in_range "${period:-0}" 1.77 1.97; echo $?)" \
    "period ${period:-?} s (want 1.87 +/- 0.1: 2 x 28 deg at 30 deg/s)"
counters_zero errors STATUS_SERVO live sdo_timeouts sdo_aborts heartbeat_losses faults enable_failures bus_errors \
    reconnects reinits tx_failures setpoint_timeouts bus_publish_failures
stop_clean
bench_end
