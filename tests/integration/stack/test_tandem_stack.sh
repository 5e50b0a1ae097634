#!/usr/bin/env bash
# The report's tandem configuration end to end: ugv-sim world on tools/sim/scenarios/tandem.toml
# (two nodding lasers, left and right, each on its own servo) with two ugv-lms, two ugv-servo
# and two ugv-nodscan instances, ugv-gps, ugv-imu, ugv-pose and ugv-terrain (tools/lib/stack.sh),
# during the scenario's standing start: until each ugv-nodscan has sent 200 clouds (about
# 10 s on an idle machine: the LMS handshakes at 9600 baud first), at most 60 s. Checked
# from the lcm-logger log:
#   the run folder holds both lasers' devices and the stack ran one instance per laser;
#   each laser's scans, servo states and clouds are on its own channels (LMS_SCAN_LEFT ...);
#   ugv-terrain took the clouds of both: its clouds_in (last status) exceeds what either
#   laser sent by half again, no cloud counted as a duplicate (distinct sensor_ids), its
#   points_fused at least 100 a cloud; the last map against the truth: RMSE <= 0.06 m, coverage >= 0.15;
#   every process stopped cleanly.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
bin=${UGV_BIN_DIR:?UGV_BIN_DIR must point to build/bin}
out=$(mktemp -d /tmp/ugv-tandem-test.XXXXXX)
trap 'stack_stop >/dev/null 2>&1; rm -rf "$out"' EXIT
# shellcheck source=../../../tools/lib/stack.sh
. "$root/tools/lib/stack.sh"

pass=0 fail=0
check() {  # check DESCRIPTION CONDITION-EXIT-STATUS SEEN
    if [ "$2" -eq 0 ]; then pass=$((pass + 1)); echo "ok   $1: $3"; else fail=$((fail + 1)); echo "FAIL $1: $3"; fi
}

stack_init "$out" "udpm://239.255.76.67:7924?ttl=0&recv_buf_size=4194304"
stack_set lms 'units = "cm"'
stack_set terrain 'publish_hz = 4.0'
stack_start_logger
stack_start_devices --scenario "$root/tools/sim/scenarios/tandem.toml" --duration 60 \
    || { echo "FAIL: the simulator did not come up"; cat "$out/stderr/sim-world.log"; exit 1; }
[ "${STACK_LASERS[*]}" = "left right" ]; check "the scenario's lasers" $? "${STACK_LASERS[*]:-none}"
stack_start_daemons lms servo nodscan gps imu pose terrain
want="ugv-gps ugv-imu ugv-lms-left ugv-lms-right ugv-nodscan-left ugv-nodscan-right ugv-pose ugv-servo-left ugv-servo-right ugv-terrain"
got=$(printf '%s\n' "${!STACK_PIDS[@]}" | grep '^ugv-' | sort | tr '\n' ' ')
[ "${got% }" = "$want" ]; check "one ugv-lms, ugv-servo and ugv-nodscan per laser" $? "${got% }"
# Until both lasers' clouds flow (each status read waits for the next 1 Hz message).
deadline=$((SECONDS + 60))
while stack_alive sim-world && [ $SECONDS -lt $deadline ]; do
    l=$(stack_counter STATUS_NODSCAN_LEFT scans_out) r=$(stack_counter STATUS_NODSCAN_RIGHT scans_out)
    [ "${l:-0}" -ge 200 ] && [ "${r:-0}" -ge 200 ] && break
done
stack_stop

stats=$("$bin/ugv-logstat" "$out/ugv.lcm" --json)
count() { jq -r --arg c "$1" 'select(.channel == $c) | .count' <<<"$stats"; }
at_least() { awk -v v="$1" -v lo="$2" 'BEGIN { exit !(v != "" && v >= lo) }'; }
for side in LEFT RIGHT; do
    # Each nodscan sent 200 clouds; the logger's copy may miss a few of a stall.
    n=$(count "LMS_SCAN_$side"); at_least "$n" 150; check "LMS_SCAN_$side scans" $? "${n:-none}"
    n=$(count "SERVO_STATE_$side"); at_least "$n" 500; check "SERVO_STATE_$side states" $? "${n:-none}"
    n=$(count "POINTS_$side"); at_least "$n" 150; check "POINTS_$side clouds" $? "${n:-none}"
done
for ch in LMS_SCAN SERVO_STATE POINTS; do
    n=$(count "$ch"); [ -z "$n" ]; check "nothing on the one-laser channel $ch" $? "${n:-0}"
done
left=$(count POINTS_LEFT) right=$(count POINTS_RIGHT)
status=$(stack_status_json STATUS_TERRAIN "$out/ugv.lcm")
clouds=$(stack_counter_in "$status" clouds_in)
dups=$(stack_counter_in "$status" clouds_duplicate)
fused=$(stack_counter_in "$status" points_fused)
# More than either laser sent: the clouds of both. (Not compared with the sum: the last status
# is up to a second old, and the logger may miss a cloud that ugv-terrain took.)
awk -v c="${clouds:-0}" -v l="${left:-0}" -v r="${right:-0}" 'BEGIN { m = l > r ? l : r; exit !(c >= 1.5 * m) }'
check "ugv-terrain took both lasers' clouds" $? "clouds_in ${clouds:-none} of ${left:-0} left + ${right:-0} right"
[ "${dups:-x}" = 0 ]; check "no cloud of one laser taken for the other's (clouds_duplicate)" $? "${dups:-none}"
# ~280 of a cloud's 361 beams hit the ground within range while the lasers nod 2-30 deg.
at_least "${fused:-0}" $((100 * ${clouds:-1})); check "ugv-terrain fused their points (>= 100 a cloud)" $? "points_fused ${fused:-none}"

unclean=$(stack_unclean)
[ -z "$unclean" ] && [ ${#STACK_KILLED[@]} -eq 0 ]; check "every process stopped cleanly" $? "${unclean:-all exit 0}${STACK_KILLED[*]:+, killed: ${STACK_KILLED[*]}}"
if [ -f "$out/run/truth.hf" ] && m=$("$bin/ugv-eval" compare "$out/ugv.lcm" --truth "$out/run/truth.hf" --exclude-edges 0.3); then
  rmse=$(jq -r .rmse_m <<<"$m"); cov=$(jq -r .coverage <<<"$m")
  awk -v v="$rmse" 'BEGIN { exit !(v != "" && v <= 0.06) }'; check "map RMSE against truth <= 0.06 m" $? "$rmse m over $(jq -r .known <<<"$m") cells"
  at_least "$cov" 0.15; check "map coverage >= 0.15" $? "$cov"
else
  check "the last map compared with the truth" 1 "no map or no truth (see $out)"
fi
echo "$pass passed, $fail failed"
if [ $fail -gt 0 ]; then
  for f in "$out"/stderr/*.log; do echo "--- $(basename "$f")"; tail -5 "$f"; done
  exit 1
fi
