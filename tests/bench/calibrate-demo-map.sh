#!/usr/bin/env bash
# Bench: does calibration from data give the demo's map the accuracy of the true mounts
# (docs/calibration.md, "The map with the estimated mounts")? One vehicle, whose laser, IMU
# and antenna are mounted as in parking_lot.toml and calibration_drive.toml:
#   1. tests/bench/calibrate-laser.sh and calibrate-imu-antenna.sh record their logs and
#      estimate the three mounts, starting from the daemons' defaults;
#   2. the report's demonstration (`ugv-sim world --print-scenario`) is driven with the whole
#      stack once per configuration: the daemons told the defaults (tape measure), the
#      estimates, the truth; RUNS times each but the defaults (--runs, default 2);
#   3. each run's maps are scored against the world's true height field (`ugv-eval compare
#      --truth --exclude-edges 0.3`, every map and the last).
#   tests/bench/calibrate-demo-map.sh [--out DIR] [--runs N] [--reuse]
# --reuse   keep the calibrations an earlier run left in --out DIR (step 1 skipped).
# Checks:
#   calibrated      both calibration benches pass (their own checks);
#   run CONFIG-K    the stack ran the scenario to its end and published maps;
#   map             the mean over the runs of the last map's RMSE, and of the mean RMSE over the
#                   maps, with the estimates within 5 mm of those with the true mounts.
here=$(cd "$(dirname "$0")" && pwd)
runs=2 out= reuse=
while [ $# -gt 0 ]; do
    case $1 in
        --out) shift; out=$1 ;;
        --runs) shift; runs=$1 ;;
        --reuse) reuse=1 ;;
        -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
        *) echo "$(basename "$0"): unknown argument $1 (see --help)" >&2; exit 2 ;;
    esac
    shift
done
[ -n "$reuse" ] && [ -z "$out" ] && { echo "$(basename "$0"): --reuse needs --out DIR" >&2; exit 2; }
[[ $runs =~ ^[1-9][0-9]*$ ]] || { echo "$(basename "$0"): --runs: a whole number >= 1, not '$runs'" >&2; exit 2; }
[ -n "$out" ] && export UGV_BENCH_OUT=$out
source "$here/bench.sh"
stack_has_world || { echo "$(basename "$0"): $STACK_BIN/ugv-sim has no world simulator" >&2; exit 2; }
bench_begin calibrate-demo-map 7997
top=$BENCH_WORK

# 1. The calibrations, each in a folder of its own (their own ports).
if [ -z "$reuse" ]; then
    "$here/calibrate-laser.sh" --out "$top/laser" >"$top/laser.txt" 2>&1
    laser_rc=$?
    "$here/calibrate-imu-antenna.sh" --out "$top/imu-antenna" >"$top/imu-antenna.txt" 2>&1
    imu_rc=$?
    verdict calibrated "$(( laser_rc | imu_rc ))" \
        "calibrate-laser: $(tail -n 1 "$top/laser.txt"); calibrate-imu-antenna: $(tail -n 1 "$top/imu-antenna.txt")"
fi
laser=$top/laser/from-defaults.json imu=$top/imu-antenna/imu.json antenna=$top/imu-antenna/antenna.json
for f in "$laser" "$imu" "$antenna"; do
    [ -s "$f" ] || { verdict estimates 1 "$f is missing: see $top/*.txt"; bench_end; exit; }
done

# The truth, from the runs' true-calibration folders; the defaults, from their configured ones.
key() { printf '[%s, %s, %s]' $(bench_toml_vec "$1" "$2"); }  # as a TOML array
true_axis_xyz=$(key "$top/laser/run/true-calibration/nodscan.toml" tilt_axis_xyz_m)
true_axis_rpy=$(key "$top/laser/run/true-calibration/nodscan.toml" tilt_axis_rpy_deg)
true_imu=$(key "$top/imu-antenna/run/true-calibration/imu.toml" mount_rpy_deg)
true_antenna=$(key "$top/imu-antenna/run/true-calibration/pose.toml" gps_antenna_m)
# The laser's fit keeps the axis's x and y as configured (they do not move flat ground).
read -r ax ay _ <<<"$(bench_toml_vec "$top/laser/run/calibration/nodscan.toml" tilt_axis_xyz_m)"
read -r _ _ antenna_z <<<"$(bench_toml_vec "$top/imu-antenna/run/true-calibration/pose.toml" gps_antenna_m)"
est_axis_xyz=$(jq -r --arg x "$ax" --arg y "$ay" '"[\($x), \($y), \(.height_m.value)]"' "$laser")
est_axis_rpy=$(jq -r '"[\(.roll_deg.value), \(.pitch_deg.value), \(.yaw_deg.value)]"' "$laser")
est_imu=$(jq -r '"[\(.roll_deg.value), \(.pitch_deg.value), \(.yaw_deg.value)]"' "$imu")
est_antenna=$(jq -r --arg z "$antenna_z" '"[\(.x_m.value), \(.y_m.value), \($z)]"' "$antenna")
# The laser bench starts from ugv-nodscan's defaults (the fit's initial values); the IMU and the
# antenna from what the drive's daemons were told.
def_axis_xyz=$(jq -r --arg x "$ax" --arg y "$ay" '"[\($x), \($y), \(.height_m.initial)]"' "$laser")
def_axis_rpy=$(jq -r '"[\(.roll_deg.initial), \(.pitch_deg.initial), \(.yaw_deg.initial)]"' "$laser")
def_imu=$(key "$top/imu-antenna/run/calibration/imu.toml" mount_rpy_deg)
def_antenna=$(key "$top/imu-antenna/run/calibration/pose.toml" gps_antenna_m)
echo "# truth:     axis $true_axis_xyz $true_axis_rpy, IMU $true_imu, antenna $true_antenna"
echo "# estimates: axis $est_axis_xyz $est_axis_rpy, IMU $est_imu, antenna $est_antenna"
echo "# defaults:  axis $def_axis_xyz $def_axis_rpy, IMU $def_imu, antenna $def_antenna"

# scenario AXIS_XYZ AXIS_RPY IMU ANTENNA: the demonstration with the true mounts and the daemons
# told the given ones (the mount keys of [laser], [imu] and [gps] replaced, the rest as printed).
scenario() {
    "$STACK_BIN/ugv-sim" world --print-scenario | awk \
        -v txyz="$true_axis_xyz" -v trpy="$true_axis_rpy" -v timu="$true_imu" -v tant="$true_antenna" \
        -v cxyz="$1" -v crpy="$2" -v cimu="$3" -v cant="$4" '
        /^\[/ { table = $0 }
        table == "[laser]" && /^(configured_)?tilt_axis_(xyz_m|rpy_deg) *=/ { next }
        table == "[imu]" && /^(configured_)?mount_rpy_deg *=/ { next }
        table == "[gps]" && /^(configured_)?antenna_m *=/ { next }
        { print }
        $0 == "[laser]" { print "tilt_axis_xyz_m = " txyz; print "tilt_axis_rpy_deg = " trpy
                          print "configured_tilt_axis_xyz_m = " cxyz; print "configured_tilt_axis_rpy_deg = " crpy }
        $0 == "[imu]" { print "mount_rpy_deg = " timu; print "configured_mount_rpy_deg = " cimu }
        $0 == "[gps]" { print "antenna_m = " tant; print "configured_antenna_m = " cant }'
}

# drive NAME WORLD: the whole stack on the scenario file WORLD to its end, in $top/NAME; then the scores
# (one JSON line a map) in $top/NAME/maps.jsonl.
drive() {
    local name=$1 dir=$top/$1 rc
    mkdir -p "$dir"
    stack_init "$dir" "$STACK_URL"
    stack_start_logger
    if ! stack_start_devices --scenario "$2"; then verdict "run $name" 1 "the simulator did not come up"; stack_stop; return; fi
    stack_start_daemons
    while stack_alive sim-world; do sleep 0.5; done
    stack_stop
    rc=${STACK_EXIT[sim-world]:-1}
    "$STACK_BIN/ugv-eval" compare "$dir/ugv.lcm" --truth "$dir/run/truth.hf" --exclude-edges 0.3 --all \
        >"$dir/maps.jsonl" 2>"$dir/stderr/eval.log"
    local maps
    maps=$(jq -s 'map(select(.rmse_m != null)) | length' "$dir/maps.jsonl" 2>/dev/null || echo 0)
    verdict "run $name" "$([ "$rc" = 0 ] && [ "${maps:-0}" -gt 0 ]; echo $?)" \
        "ugv-sim world exit status $rc; $maps maps scored; $(jq -sc 'map(select(.rmse_m != null)) |
            {last_rmse_m: .[-1].rmse_m, mean_rmse_m: (map(.rmse_m) | add / length), max_rmse_m: (map(.rmse_m) | max)}' "$dir/maps.jsonl" 2>/dev/null)"
}

mkdir -p "$top/scenarios"
scenario "$def_axis_xyz" "$def_axis_rpy" "$def_imu" "$def_antenna" >"$top/scenarios/defaults.toml"
scenario "$est_axis_xyz" "$est_axis_rpy" "$est_imu" "$est_antenna" >"$top/scenarios/estimates.toml"
scenario "$true_axis_xyz" "$true_axis_rpy" "$true_imu" "$true_antenna" >"$top/scenarios/truth.toml"
drive defaults-1 "$top/scenarios/defaults.toml"
for k in $(seq 1 "$runs"); do
    drive "estimates-$k" "$top/scenarios/estimates.toml"
    drive "truth-$k" "$top/scenarios/truth.toml"
done

per_run() {  # per_run CONFIG: last and mean RMSE of each run
    local d
    for d in "$top/$1"-*; do
        jq -rs --arg n "$(basename "$d")" 'map(select(.rmse_m != null)) |
            "\($n): last \(.[-1].rmse_m * 1000 | round / 10) cm, mean \(map(.rmse_m) | add / length * 1000 | round / 10) cm over \(length) maps"' \
            "$d/maps.jsonl" 2>/dev/null
    done
}
for c in defaults estimates truth; do per_run $c | sed 's/^/# /'; done
mean_of() {  # mean_of CONFIG FIELD(1 last, 2 mean): the mean over the runs
    local d s=0 n=0 v
    for d in "$top/$1"-*; do
        v=$(jq -rs --argjson f "$2" 'map(select(.rmse_m != null)) | if length == 0 then empty
            elif $f == 1 then .[-1].rmse_m else map(.rmse_m) | add / length end' "$d/maps.jsonl" 2>/dev/null)
        [ -n "$v" ] && { s=$(awk -v a="$s" -v b="$v" 'BEGIN { print a + b }'); n=$((n + 1)); }
    done
    [ $n -gt 0 ] && awk -v s="$s" -v n="$n" 'BEGIN { printf "%.5f", s / n }' || echo nan
}
el=$(mean_of estimates 1) em=$(mean_of estimates 2) tl=$(mean_of truth 1) tm=$(mean_of truth 2)
dl=$(mean_of defaults 1) dm=$(mean_of defaults 2)
ok=$(awk -v a="$el" -v b="$tl" -v c="$em" -v d="$tm" 'BEGIN {
    x = a - b; y = c - d; if (x < 0) x = -x; if (y < 0) y = -y
    exit !(a == a + 0 && b == b + 0 && x <= 0.005 && y <= 0.005) }'; echo $?)
verdict map "$ok" "RMSE last map / mean over maps: estimates $el / $em m, truth $tl / $tm m (want within 0.005 m); defaults $dl / $dm m"
bench_end
