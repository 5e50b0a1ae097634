#!/usr/bin/env bash
# Bench: latency of each daemon from its input to its output on LCM, p50/p99/max.
#   device daemons: the arrival of the chunk that completed a frame (raw_bytes_t utime, with
#                   publish_raw on) -> the decoded message received on LCM;
#   ugv-servo:      the CAN frame's receive stamp (servo_state_t utime) -> received on LCM;
#   ugv-pose:       an IMU message received -> the next POSE received, and a pose's own time
#                   (utime) -> received, which includes its reorder buffer;
#   ugv-nodscan:    an LMS_SCAN received -> the next POINTS received.
# Runs against the emulators (ugv-sim) on pseudo-terminals, LCM on its own port, for
# --seconds (UGV_BENCH_SECONDS, default 10). Prints a line per check and `N passed, N failed`;
# a check passes when it measured something, and the goals (p99 < 1 ms for the drivers) are
# reported.
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=${UGV_BENCH_SECONDS:-10}
bench_flags none "$@"
bench_begin latency 7305

for d in lms gps imu; do stack_set "$d" 'publish_raw = true'; done
for d in lms gps imu servo; do stack_start_device "$d" || { verdict devices 1 "ugv-sim $d did not start"; bench_end; exit; }; done
stack_start_daemons lms gps imu servo nodscan pose
sleep 4   # handshakes

measure() {  # measure NAME ARGS...: ugv-latency in the background, collected below
    local name=$1; shift
    "$STACK_BIN/ugv-latency" --for "$BENCH_SECONDS" "$@" >"$BENCH_WORK/latency-$name.out" 2>&1 &
    BENCH_BG+=("$name:$!")
}
measure lms --from RAW_LMS --to LMS_SCAN
measure gps --from RAW_GPS --to GPS_FIX
measure imu --from RAW_IMU --to IMU
measure servo --to SERVO_STATE
measure nodscan --from LMS_SCAN --from-recv --to POINTS
measure pose-imu --from IMU --from-recv --to POSE
measure pose-own --to POSE   # the pose's own time -> on LCM: includes the reorder buffer (buffer_s)
for entry in "${BENCH_BG[@]}"; do
    wait "${entry##*:}"
    line=$(tail -n 1 "$BENCH_WORK/latency-${entry%:*}.out")
    verdict "${entry%:*}" "$(grep -q ' samples' <<<"$line" && ! grep -q ': 0 samples' <<<"$line"; echo $?)" "$line"
done
BENCH_BG=()
bench_end
