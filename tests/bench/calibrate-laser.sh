#!/usr/bin/env bash
# Bench: `ugv-calibrate laser` on a simulated parking lot (docs/calibration.md). Runs
# tools/sim/scenarios/parking_lot.toml (its laser 1.5 deg rolled, 1.2 deg pitched, 0.95 m high)
# with lcm-logger, ugv-lms and ugv-servo, then estimates the mount from the log starting from
# ugv-nodscan's defaults (0, 0, 0.87: 1.2-1.5 deg and 8 cm off) and from the true mount.
#   tests/bench/calibrate-laser.sh [--out DIR] [--keep] [--score DIR]
# --score DIR   only calibrate the log kept in DIR by an earlier --out DIR.
# Checks:
#   running NAME   ugv-lms and ugv-servo report RUNNING within 30 s of their start;
#   scenario       the simulator ran to the end of the scenario;
#   from-defaults  from the defaults: roll and pitch within 0.1 deg of the truth, height within
#                  1 cm, yaw reported as not determined;
#   from-truth     from the true mount: the same estimate within 0.02 deg and 2 mm.
source "$(dirname "$0")/bench.sh"
bench_world_log_flags "$@"
score_only=$BENCH_SCORE_ONLY
scenario=$(realpath "$(dirname "$0")/../../tools/sim/scenarios/parking_lot.toml")

bench_begin calibrate-laser 7933
log=$STACK_OUT/ugv.lcm
if [ -z "$score_only" ]; then
    stack_start_logger
    if ! stack_start_devices --scenario "$scenario"; then verdict devices 1 "the simulator did not come up"; bench_end; exit; fi
    stack_start_daemons lms servo
    running "running ugv-lms" STATUS_LMS 30
    running "running ugv-servo" STATUS_SERVO 30
    echo "# running the parking lot"
    while stack_alive sim-world; do sleep 0.5; done
    stack_stop
    sim_rc=${STACK_EXIT[sim-world]:-1}
    verdict scenario "$sim_rc" "ugv-sim world exit status $sim_rc"
fi

# The truth: the scenario's true [laser] mount (the simulator writes it into run/true-calibration/).
truth=$STACK_OUT/run/true-calibration/nodscan.toml
read -r _ _ true_z <<<"$(bench_toml_vec "$truth" tilt_axis_xyz_m)"
read -r true_roll true_pitch _ <<<"$(bench_toml_vec "$truth" tilt_axis_rpy_deg)"
echo "# truth: roll $true_roll deg, pitch $true_pitch deg, height $true_z m"

calibrate() {  # calibrate OUT ARGS...: the JSON line of ugv-calibrate laser LOG ARGS
    "$STACK_BIN/ugv-calibrate" laser "$log" --json "${@:2}" >"$STACK_OUT/$1.json" 2>"$STACK_OUT/stderr/$1.log"
    echo $?
}
within() {  # within JSON PARAM TRUTH TOL: |value - truth| <= tol
    jq -e --argjson t "$3" --argjson tol "$4" ".$2.value - \$t | fabs <= \$tol" "$1" >/dev/null
}
rc=$(calibrate from-defaults)
f=$STACK_OUT/from-defaults.json
if [ "$rc" -ne 0 ]; then
    verdict from-defaults 1 "exit status $rc: $(tail -n 1 "$STACK_OUT/stderr/from-defaults.log")"
else
    ok=0
    within "$f" roll_deg "$true_roll" 0.1 && within "$f" pitch_deg "$true_pitch" 0.1 && within "$f" height_m "$true_z" 0.01 &&
        [ "$(jq -r .yaw_deg.determined "$f")" = false ] || ok=1
    verdict from-defaults $ok "$(jq -c '{roll: .roll_deg.value, pitch: .pitch_deg.value, height: .height_m.value,
        yaw_determined: .yaw_deg.determined, rms_before_m, rms_after_m, ground_beams}' "$f")"
fi
rc=$(calibrate from-truth --mount-config "$truth")
g=$STACK_OUT/from-truth.json
if [ "$rc" -ne 0 ]; then
    verdict from-truth 1 "exit status $rc: $(tail -n 1 "$STACK_OUT/stderr/from-truth.log")"
else
    ok=0
    for p in roll_deg pitch_deg; do within "$g" $p "$(jq .$p.value "$f")" 0.02 || ok=1; done
    within "$g" height_m "$(jq .height_m.value "$f")" 0.002 || ok=1
    verdict from-truth $ok "$(jq -c '{roll: .roll_deg.value, pitch: .pitch_deg.value, height: .height_m.value}' "$g")"
fi
bench_end
