#!/usr/bin/env bash
# The whole stack on the simulated vehicle (the default scenario: 10 s standing, then 3 m/s
# east) for 25 s, started and stopped with tools/lib/stack.sh, then checked from the
# lcm-logger log:
#   LMS_SCAN >= 35 Hz, SERVO_STATE >= 100 Hz (99.5: the window's ends are receive times on a
#   loaded machine), POSE at the IMU's rate +/- 5 % (one pose after each IMU sample),
#   TERRAIN_MAP at its configured 4 Hz +/- 5 %, no sequence gap on any channel, every process
#   stopped cleanly, and the last map against the truth height field (cells within 0.3 m of a
#   step left out): RMSE <= 0.06 m, |bias| <= 0.05 m (the map inherits the pose's height
#   error: the RTK receiver's height sigma is 3 cm per fix), coverage >= 0.15. The simulator
#   runs its default error models (the GX1's "ahrs" filter with its false tilt, the "markov"
#   GPS), which the pose must remove (docs/pose.md, "Attitude under the simulator's error
#   models").
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
bin=${UGV_BIN_DIR:?UGV_BIN_DIR must point to build/bin}
out=$(mktemp -d /tmp/ugv-stack-test.XXXXXX)
trap 'stack_stop >/dev/null 2>&1; rm -rf "$out"' EXIT
# shellcheck source=../../../tools/lib/stack.sh
. "$root/tools/lib/stack.sh"

stack_init "$out" "udpm://239.255.76.67:7990?ttl=0&recv_buf_size=4194304"
stack_set lms 'units = "cm"'
stack_set terrain 'publish_hz = 4.0'
stack_start_logger
stack_start_devices --duration 25 || { echo "FAIL: the simulator did not come up"; cat "$out/stderr/sim-world.log"; exit 1; }
stack_start_daemons
while stack_alive sim-world; do sleep 0.5; done
stack_stop

pass=0 fail=0
check() {  # check DESCRIPTION CONDITION-EXIT-STATUS SEEN
    if [ "$2" -eq 0 ]; then pass=$((pass + 1)); echo "ok   $1: $3"; else fail=$((fail + 1)); echo "FAIL $1: $3"; fi
}
stats=$("$bin/ugv-logstat" "$out/ugv.lcm" --json)
rate() { jq -r --arg c "$1" 'select(.channel == $c) | .rate_hz' <<<"$stats"; }
in_range() { awk -v v="$1" -v lo="$2" -v hi="$3" 'BEGIN { exit !(v != "" && v >= lo && v <= hi) }'; }

r=$(rate LMS_SCAN); in_range "$r" 35 1000; check "LMS_SCAN >= 35 Hz" $? "${r:-none} Hz"
r=$(rate SERVO_STATE); in_range "$r" 99.5 1000; check "SERVO_STATE >= 100 Hz" $? "${r:-none} Hz"
r=$(rate POSE); imu=$(rate IMU)
in_range "$r" "$(awk -v i="${imu:-0}" 'BEGIN { print 0.95 * i }')" "$(awk -v i="${imu:-0}" 'BEGIN { print 1.05 * i }')" && [ -n "$imu" ]
check "POSE at the IMU's rate +/- 5 %" $? "${r:-none} Hz, IMU ${imu:-none} Hz"
r=$(rate TERRAIN_MAP); in_range "$r" 3.8 4.2; check "TERRAIN_MAP 4 Hz +/- 5 %" $? "${r:-none} Hz"
r=$(rate SIM_TRUTH); in_range "$r" 95 105; check "SIM_TRUTH 100 Hz" $? "${r:-none} Hz"
gaps=$(jq -r 'select(.seq_gaps > 0 or .seq_backwards > 0) | "\(.channel): \(.seq_gaps) missing, \(.seq_backwards) back"' <<<"$stats")
[ -z "$gaps" ]; check "no sequence gaps in the log" $? "${gaps:-$(jq -s 'length' <<<"$stats") channels contiguous}"
unclean=$(stack_unclean)
[ -z "$unclean" ] && [ ${#STACK_KILLED[@]} -eq 0 ]; check "every process stopped cleanly" $? "${unclean:-all exit 0}${STACK_KILLED[*]:+, killed: ${STACK_KILLED[*]}}"

if [ -f "$out/run/truth.hf" ] && m=$("$bin/ugv-eval" compare "$out/ugv.lcm" --truth "$out/run/truth.hf" --exclude-edges 0.3); then
  rmse=$(jq -r .rmse_m <<<"$m"); bias=$(jq -r .bias_m <<<"$m"); cov=$(jq -r .coverage <<<"$m")
  in_range "$rmse" 0 0.06; check "map RMSE against truth <= 0.06 m" $? "$rmse m over $(jq -r .known <<<"$m") cells"
  in_range "$bias" -0.05 0.05; check "map bias against truth within 0.05 m" $? "$bias m"
  in_range "$cov" 0.15 1; check "map coverage >= 0.15" $? "$cov"
else
  check "the last map compared with the truth" 1 "no map or no truth (see $out)"
fi
echo "$pass passed, $fail failed"
if [ $fail -gt 0 ]; then
  for f in "$out"/stderr/*.log; do echo "--- $(basename "$f")"; tail -5 "$f"; done
  exit 1
fi
