#!/usr/bin/env bash
# Bench: `ugv-calibrate imu` and `ugv-calibrate antenna` on a simulated drive
# (docs/calibration.md). Runs tools/sim/scenarios/calibration_drive.toml (the demo's path on a
# flat lot; the IMU mounted 1.2, -1.5, 1.8 deg and the antenna at 0.08, -0.06 m while ugv-imu
# and ugv-pose are told 0, 0, 0 and 0, 0) with lcm-logger, ugv-gps and ugv-imu, then estimates
# both from the log, starting from what the daemons were told.
#   tests/bench/calibrate-imu-antenna.sh [--out DIR] [--keep] [--score DIR]
# --score DIR   only calibrate the log kept in DIR by an earlier --out DIR.
# Checks:
#   running NAME   ugv-gps and ugv-imu report RUNNING within 30 s of their start;
#   scenario       the simulator ran to the end of the scenario;
#   imu            roll, pitch and yaw determined and within 0.2 deg of the true mounting;
#   antenna        x and y determined and within 5 cm (horizontal distance) of the true arm.
source "$(dirname "$0")/bench.sh"
bench_world_log_flags "$@"
score_only=$BENCH_SCORE_ONLY
scenario=$(realpath "$(dirname "$0")/../../tools/sim/scenarios/calibration_drive.toml")

bench_begin calibrate-imu-antenna 7956
log=$STACK_OUT/ugv.lcm
if [ -z "$score_only" ]; then
    stack_start_logger
    if ! stack_start_devices --scenario "$scenario"; then verdict devices 1 "the simulator did not come up"; bench_end; exit; fi
    stack_start_daemons gps imu
    running "running ugv-gps" STATUS_GPS 30
    running "running ugv-imu" STATUS_IMU 30
    echo "# driving the demo's path"
    while stack_alive sim-world; do sleep 0.5; done
    stack_stop
    sim_rc=${STACK_EXIT[sim-world]:-1}
    verdict scenario "$sim_rc" "ugv-sim world exit status $sim_rc"
fi

# The truth: the scenario's true mounts (run/true-calibration/); the configured: what the
# daemons were told (ugv-imu's config as run, ugv-pose's calibration file).
read -r true_roll true_pitch true_yaw <<<"$(bench_toml_vec "$STACK_OUT/run/true-calibration/imu.toml" mount_rpy_deg)"
read -r true_x true_y _ <<<"$(bench_toml_vec "$STACK_OUT/run/true-calibration/pose.toml" gps_antenna_m)"
echo "# truth: IMU mounting $true_roll, $true_pitch, $true_yaw deg; antenna x $true_x m, y $true_y m"

calibrate() {  # calibrate WHAT ARGS...: the JSON line of ugv-calibrate WHAT LOG ARGS
    "$STACK_BIN/ugv-calibrate" "$1" "$log" --json "${@:2}" >"$STACK_OUT/$1.json" 2>"$STACK_OUT/stderr/calibrate-$1.log"
    echo $?
}
within() {  # within JSON PARAM TRUTH TOL: determined and |value - truth| <= tol
    jq -e --argjson t "$3" --argjson tol "$4" ".$2.determined and (.$2.value - \$t | fabs <= \$tol)" "$1" >/dev/null
}

rc=$(calibrate imu --mount-config "$STACK_OUT/config/imu.toml")
f=$STACK_OUT/imu.json
if [ "$rc" -ne 0 ]; then
    verdict imu 1 "exit status $rc: $(tail -n 1 "$STACK_OUT/stderr/calibrate-imu.log")"
else
    ok=0
    within "$f" roll_deg "$true_roll" 0.2 && within "$f" pitch_deg "$true_pitch" 0.2 &&
        within "$f" yaw_deg "$true_yaw" 0.2 || ok=1
    verdict imu $ok "$(jq -c '{roll: .roll_deg.value, pitch: .pitch_deg.value, yaw: .yaw_deg.value,
        sigma: [.roll_deg.sigma, .pitch_deg.sigma, .yaw_deg.sigma], still_s, accel_samples}' "$f")"
fi

rc=$(calibrate antenna --pose-config "$STACK_OUT/run/calibration/pose.toml")
g=$STACK_OUT/antenna.json
if [ "$rc" -ne 0 ]; then
    verdict antenna 1 "exit status $rc: $(tail -n 1 "$STACK_OUT/stderr/calibrate-antenna.log")"
else
    ok=0
    jq -e --argjson x "$true_x" --argjson y "$true_y" \
        '.x_m.determined and .y_m.determined and ((.x_m.value - $x) * (.x_m.value - $x) + (.y_m.value - $y) * (.y_m.value - $y) | sqrt <= 0.05)' \
        "$g" >/dev/null || ok=1
    verdict antenna $ok "$(jq -c '{x: .x_m.value, y: .y_m.value, sigma: [.x_m.sigma, .y_m.sigma], turn_deg, samples}' "$g")"
fi
bench_end
