#!/usr/bin/env bash
# Bench: the IMU's sign conventions (docs/imu.md, docs/pose.md), about 40 s with the emulator.
#   tests/bench/imu-signs.sh [--device /dev/ugv/imu] [--gps PATH] [--seconds 30] [--keep]
# It asks for three motions, one at a time, and checks that IMU and POSE see each with the
# project's signs (body X forward, Y left, Z up; ENU yaw counter-clockwise from east):
#   roll the unit right side down  -> roll up, angular_rate[0] > 0, POSE roll up, rate x > 0
#   tip the nose up                -> pitch down (FLU: nose down is +), angular_rate[1] < 0
#   turn it left (CCW from above)  -> yaw up, angular_rate[2] > 0, POSE yaw up
# For each it waits until the unit lies still for 0.5 s (every rate below 0.05 rad/s), then
# for the motion: the angle moving more than 20 deg (roll), 12 deg (pitch) or 45 deg (yaw)
# from where it lay, within --seconds (default 30) s. The rate's sign is that of the largest
# rate on the axis until then; POSE must move the same way by at least half the threshold,
# and its largest rate until then have the IMU's sign.
# A real unit: --device PATH (or UGV_IMU_DEVICE), 38400 baud, command 0x31, the unit set
# down on the bench level, its base down and its connector (-X) towards you; follow the
# prompts. The GPS is the emulator (standing still) unless --gps PATH is given.
# Default: `ugv-sim imu --attitude bench`, which makes the three motions in a 20 s loop.
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=30
bench_flags imu "$@"
bench_begin imu-signs 7890
real=$(stack_given_device imu)
if [[ $real == /* ]] && [ ! -e "$real" ]; then verdict device 1 "$real does not exist"; bench_end; exit; fi
if ! stack_start_device imu --attitude bench || ! stack_start_device gps; then
    verdict devices 1 "the IMU or the GPS did not come up"; bench_end; exit
fi
stack_start_daemons imu gps pose
running running STATUS_IMU 20
# ugv-pose standing still is DEGRADED ("heading not yet observed") but publishes POSE.
expect pose-flows --channel POSE --for 2 --min-count 10 --wait 20

# motion NAME AXIS THRESHOLD_DEG ANGLE_SIGN RATE_SIGN PROMPT...: one motion and its checks.
# AXIS: 0 roll, 1 pitch, 2 yaw (the angle field and the rate index).
motion() {
    local name=$1 axis=$2 thr=$3 want_angle=$4 want_rate=$5 out; shift 5
    echo "# $name: put the unit down level and still, then: $*"
    # shellcheck disable=SC2016  # jq and awk programs
    # ugv-dump writes to a file and is stopped by its PID once awk has its answer (a closed
    # pipe would not stop it before its timeout).
    local dump=$BENCH_WORK/$name.jsonl dump_pid
    "$STACK_BIN/ugv-dump" --lcm-url "$STACK_URL" --channel 'IMU|POSE' --timeout "$BENCH_SECONDS" >"$dump" 2>/dev/null &
    dump_pid=$!
    out=$(tail -n +1 -f --pid="$dump_pid" "$dump" |
        jq -r --unbuffered '[.channel, .fields.roll, .fields.pitch, .fields.yaw,
            ((.fields.angular_rate // .fields.rotation_rate)[])] | @tsv' |
        awk -v axis="$axis" -v thr="$thr" '
            function wrap(a) { while (a > pi) a -= 2 * pi; while (a < -pi) a += 2 * pi; return a }
            function abs(x) { return x < 0 ? -x : x }
            BEGIN { pi = atan2(0, -1); thr = thr * pi / 180; still = 0; armed = 0; done = 0 }
            {
                a = $(2 + axis); r = $(5 + axis)
                if ($1 == "IMU") {
                    if (!armed) {
                        # Still: every rate below 0.05 rad/s for 25 samples (0.5 s at 50 Hz).
                        still = (abs($5) < 0.05 && abs($6) < 0.05 && abs($7) < 0.05) ? still + 1 : 0
                        if (still >= 25) { armed = 1; a0 = a; peak = 0 }
                        next
                    }
                    d = wrap(a - a0)
                    if (!done && abs(r) > abs(peak)) peak = r
                    if (!done && abs(d) > thr) { done = 1; imu_d = d; after = 0 }
                    if (done && ++after > 75) exit  # 1.5 s more for POSE to follow
                } else if (armed) {
                    if (!pose_seen) { p0 = a; pose_seen = 1; pd = 0; pr = 0 }
                    if (abs(wrap(a - p0)) > abs(pd)) pd = wrap(a - p0)
                    if (!done && abs(r) > abs(pr)) pr = r  # the rate up to the IMU detection, as the IMU'"'"'s
                }
            }
            END { printf "%d %d %.4f %.4f %.4f %.4f %d\n", armed, done, imu_d, peak, pd, pr, pose_seen }')
    kill "$dump_pid" 2>/dev/null
    wait "$dump_pid" 2>/dev/null
    local armed moved imu_d peak pd pr pose_seen
    read -r armed moved imu_d peak pd pr pose_seen <<<"${out:-0 0 0 0 0 0 0}"
    if [ "$armed" != 1 ]; then verdict "$name" 1 "the unit never lay still for 0.5 s within $BENCH_SECONDS s"; return; fi
    if [ "$moved" != 1 ]; then verdict "$name" 1 "no motion beyond $thr deg within $BENCH_SECONDS s"; return; fi
    # awk prints the verdict inputs; the signs are compared here, in degrees for the reader.
    local deg pdeg ok
    deg=$(awk -v x="$imu_d" 'BEGIN { printf "%+.1f", x * 180 / atan2(0, -1) }')
    pdeg=$(awk -v x="$pd" 'BEGIN { printf "%+.1f", x * 180 / atan2(0, -1) }')
    ok=1; [ "$(sign "$imu_d" 0)" = "$want_angle" ] && ok=0
    verdict "$name-imu-angle" $ok "IMU ${AXES[$axis]} moved $deg deg (want $(want_text "$want_angle"))"
    ok=1; [ "$(sign "$peak" 0.1)" = "$want_rate" ] && ok=0
    verdict "$name-imu-rate" $ok "IMU angular_rate[$axis] peak $(printf '%+.3f' "$peak") rad/s (want $(want_text "$want_rate"), |rate| > 0.1)"
    local half
    half=$(awk -v t="$thr" 'BEGIN { print t * atan2(0, -1) / 360 }')
    ok=1; [ "$pose_seen" = 1 ] && [ "$(sign "$pd" "$half")" = "$want_angle" ] && ok=0
    verdict "$name-pose-angle" $ok "POSE ${AXES[$axis]} moved $pdeg deg (want $(want_text "$want_angle"), beyond half the threshold)"
    ok=1; [ "$pose_seen" = 1 ] && [ "$(sign "$pr" 0.1)" = "$want_rate" ] && ok=0
    verdict "$name-pose-rate" $ok "POSE rotation_rate[$axis] peak $(printf '%+.3f' "$pr") rad/s (want $(want_text "$want_rate"))"
}
AXES=(roll pitch yaw)
want_text() { [ "$1" = 1 ] && echo positive || echo negative; }
sign() { awk -v x="$1" -v min="$2" 'BEGIN { print (x > min) ? 1 : (x < -min) ? -1 : 0 }'; }  # sign X MIN: 1, -1, or 0 within MIN

motion roll 0 20 1 1 "roll it RIGHT side down by about 30 deg, then back level"
motion pitch 1 12 -1 -1 "tip its NOSE UP (the +X end) by about 20 deg, then back level"
motion turn 2 45 1 1 "turn it LEFT (counter-clockwise seen from above) by about 90 deg on the bench"
counters_zero errors STATUS_IMU live checksum_errors reconnects handshake_failures publish_failures bus_publish_failures
stop_clean
bench_end
