#!/usr/bin/env bash
# Bench: latency of each daemon from its input to its output on LCM, p50/p99/max.
#   device daemons: the arrival of the chunk that completed a frame (raw_bytes_t utime, with
#                   publish_raw on) -> the decoded message received on LCM;
#   ugv-servo:      the CAN frame's receive stamp (servo_state_t utime) -> received on LCM;
#   ugv-pose:       an IMU message received -> the next POSE received, and a pose's own time
#                   (utime) -> received, which includes its reorder buffer;
#   ugv-nodscan:    an LMS_SCAN received -> the next POINTS received.
# Runs against the emulators (ugv-sim) on pseudo-terminals, LCM on its own port, for
# UGV_BENCH_SECONDS (default 10). Prints a line per check and `N passed, N failed`; a check
# passes when it measured something, and the goals (p99 < 1 ms for the drivers) are reported.
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${UGV_BIN_DIR:-$root/build/bin}
seconds=${UGV_BENCH_SECONDS:-10}
work=$(mktemp -d /tmp/ugv-bench-latency-XXXXXX)
export LCM_DEFAULT_URL="udpm://239.255.76.67:7690?ttl=0"
pids=()
cleanup() { for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null; done; sleep 1; for p in "${pids[@]}"; do kill -KILL "$p" 2>/dev/null; done; rm -rf "$work"; }
trap cleanup EXIT
bg() { "$@" >>"$work/log" 2>&1 & pids+=($!); }

bg "$bin/ugv-sim" lms --pty "$work/lms"
bg "$bin/ugv-sim" gps --pty "$work/gps"
bg "$bin/ugv-sim" imu --pty "$work/imu"
bg "$bin/ugv-sim" servo --pty "$work/servo"
sleep 1
printf 'device = "%s"\npublish_raw = true\n' "$work/lms" >"$work/lms.toml"
printf 'device = "%s"\npublish_raw = true\n' "$work/gps" >"$work/gps.toml"
printf 'device = "%s"\npublish_raw = true\n' "$work/imu" >"$work/imu.toml"
printf 'transport = "slcan:%s@115200"\n' "$work/servo" >"$work/servo.toml"
for d in lms gps imu servo; do bg "$bin/ugv-$d" --config "$work/$d.toml"; done
bg "$bin/ugv-nodscan"
bg "$bin/ugv-pose"
sleep 4   # handshakes

measure() { "$bin/ugv-latency" --for "$seconds" "$@" >"$work/lat-$RANDOM$RANDOM" 2>&1 & }
measure --from RAW_LMS --to LMS_SCAN
measure --from RAW_GPS --to GPS_FIX
measure --from RAW_IMU --to IMU
measure --to SERVO_STATE
measure --from LMS_SCAN --from-recv --to POINTS
measure --from IMU --from-recv --to POSE
measure --to POSE   # the pose's own time -> on LCM: includes the reorder buffer (buffer_s)
wait_for=$(( ${seconds%.*} + 5 ))
sleep "$wait_for"
pass=0 fail=0
for f in "$work"/lat-*; do
  line=$(cat "$f")
  if grep -q ' samples' <<<"$line" && ! grep -q ': 0 samples' <<<"$line"; then pass=$((pass+1)); echo "ok   $line"
  else fail=$((fail+1)); echo "FAIL $line"; fi
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
