#!/usr/bin/env bash
# Bench: the attitude's error against the simulator's truth, of the IMU's own output (the
# GX1's filter) and of ugv-pose, standing, straight and turning (docs/pose.md, "Attitude
# under the simulator's error models").
#   tests/bench/attitude-error.sh [WORLD.toml] [--imu ahrs|white] [--gps markov|white]
#                                 [--seed N] [--out DIR] [--seconds S] [--keep]
# WORLD: an `ugv-sim world` scenario (default: the built-in one; e.g.
# tools/sim/scenarios/s_curve.toml). --imu / --gps rewrite the scenario's [imu] / [gps]
# error_model (white: the model's own keys dropped, angle_sigma_deg = 0.7 as before); absent,
# the scenario's choice stands. Starts lcm-logger (SIM_TRUTH, IMU, GPS, POSE), ugv-sim world
# and ugv-gps, ugv-imu, ugv-pose only, runs the scenario, stops everything, then prints
# `ugv-eval attitude LOG` (one JSON line per source and motion; kept in attitude.jsonl).
# Checks:
#   running NAME   each daemon reports RUNNING within 30 s of its start;
#   scenario       the simulator ran to the end of the scenario (or of --seconds);
#   scored         ugv-eval attitude scored the IMU and the pose while turning;
#   clean-stop     every process exits 0 on SIGTERM.
source "$(dirname "$0")/bench.sh"
scenario='' seconds='' imu_model='' gps_model='' seed=1
while [ $# -gt 0 ]; do
    case $1 in
        --out) shift; export UGV_BENCH_OUT=$1 ;;
        --seconds) shift; seconds=$1 ;;
        --imu) shift; imu_model=$1 ;;
        --gps) shift; gps_model=$1 ;;
        --seed) shift; seed=$1 ;;
        --keep) export UGV_BENCH_KEEP=1 ;;
        -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
        -*) echo "attitude-error.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
        *) scenario=$(realpath "$1") || exit 2 ;;
    esac
    shift
done
[ -z "$scenario" ] || [ -f "$scenario" ] || { echo "attitude-error.sh: no scenario $scenario" >&2; exit 2; }
case $imu_model in ''|ahrs|white) ;; *) echo "attitude-error.sh: --imu: ahrs or white" >&2; exit 2 ;; esac
case $gps_model in ''|markov|white) ;; *) echo "attitude-error.sh: --gps: markov or white" >&2; exit 2 ;; esac
stack_has_world || { echo "attitude-error.sh: $STACK_BIN/ugv-sim has no world simulator" >&2; exit 2; }

bench_begin attitude-error 7841
# The scenario with the chosen models, rewritten inside its [imu] and [gps] tables only.
text=$(if [ -n "$scenario" ]; then cat "$scenario"; else "$STACK_BIN/ugv-sim" world --print-scenario; fi)
text=$(stack_scenario_models "$imu_model" "$gps_model" <<<"$text")
printf '%s\n' "$text" >"$STACK_OUT/scenario.toml"
world=(--scenario "$STACK_OUT/scenario.toml" --seed "$seed")
[ -n "$seconds" ] && world+=(--duration "$seconds")
stack_start_logger -c 'SIM_TRUTH|IMU|GPS.*|POSE|STATUS_.*'
if ! stack_start_devices "${world[@]}"; then verdict devices 1 "the simulator did not come up"; bench_end; exit; fi
stack_start_daemons gps imu pose
for d in gps imu pose; do running "running ugv-$d" "STATUS_${d^^}" 30; done
echo "# running the scenario ($([ -n "$scenario" ] && basename "$scenario" || echo default); imu ${imu_model:-as given}, gps ${gps_model:-as given}, seed $seed)"
while stack_alive sim-world; do sleep 0.5; done
stack_stop
sim_rc=${STACK_EXIT[sim-world]:-1}
verdict scenario "$sim_rc" "ugv-sim world exit status $sim_rc"
unclean=$(stack_unclean)
verdict clean-stop "$([ -z "$unclean" ] && [ ${#STACK_KILLED[@]} -eq 0 ]; echo $?)" \
    "${unclean:-every process exited 0}${STACK_KILLED[*]:+; killed: ${STACK_KILLED[*]}}"
"$STACK_BIN/ugv-eval" attitude "$STACK_OUT/ugv.lcm" >"$STACK_OUT/attitude.jsonl" 2>"$STACK_OUT/stderr/ugv-eval.log"
cat "$STACK_OUT/attitude.jsonl"
turning=$(jq -s '[.[] | select(.motion == "turning" and .samples > 0)] | length' "$STACK_OUT/attitude.jsonl" 2>/dev/null)
verdict scored "$([ "${turning:-0}" -eq 2 ]; echo $?)" "${turning:-0} of 2 sources scored while turning"
bench_end
