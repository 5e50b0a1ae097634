#!/usr/bin/env bash
# Bench: the map's coverage after the left turn with one laser and with two (the report's
# tandem configuration), docs/simulator.md "Two lasers".
#   tests/bench/tandem-coverage.sh [--runs N] [--seconds S] [--out DIR] [--keep]
# Runs the stack (tools/lib/stack.sh: lcm-logger, ugv-sim world, ugv-lms, ugv-servo,
# ugv-nodscan per laser, ugv-gps, ugv-imu, ugv-pose, ugv-terrain at 4 Hz) on
# tools/sim/scenarios/tandem.toml N times (default 2), each for S seconds (default 45: the
# turn ends ~35 s in). Each run's log is then mapped again by `ugv-terrain --replay` three
# times, on the same poses: from POINTS_LEFT only, from POINTS_RIGHT only, and from both
# (POINTS_.*), so one laser and two see the same drive, to the message (a live run of each
# would differ by the nod's phase and the machine's load more than by the lasers). On each:
# `ugv-eval coverage`: the known share of the area 2-20 m ahead, 6 m either side, over the
# 5 s from the first map turned 80 deg. Prints one line per map set and the means. Checks:
#   run-N           the scenario ran, every process stopped cleanly, the three replays mapped;
#   two-more        coverage after the turn from both lasers above either one alone, every run.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
export UGV_BIN_DIR=${UGV_BIN_DIR:-$root/build/bin}
# shellcheck source=../../tools/lib/stack.sh
. "$root/tools/lib/stack.sh"
runs=2 seconds=45 out='' keep=0
while [ $# -gt 0 ]; do
    case $1 in
        --runs) shift; runs=$1 ;;
        --seconds) shift; seconds=$1 ;;
        --out) shift; out=$1; keep=1 ;;
        --keep) keep=1 ;;
        -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
        *) echo "tandem-coverage.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
    esac
    shift
done
[[ $runs =~ ^[1-9][0-9]*$ ]] || { echo "tandem-coverage.sh: --runs $runs: not a count" >&2; exit 2; }
if ! [[ $seconds =~ ^[0-9]+$ ]] || [ "$seconds" -lt 38 ]; then echo "tandem-coverage.sh: --seconds $seconds: at least 38 (the turn ends ~35 s in)" >&2; exit 2; fi
stack_has_world || { echo "tandem-coverage.sh: $STACK_BIN/ugv-sim has no world simulator" >&2; exit 2; }
work=${out:-$(mktemp -d /tmp/ugv-bench-tandem-XXXXXX)}
mkdir -p "$work"
[ $keep -eq 1 ] || trap 'rm -rf "$work"' EXIT
pass=0 fail=0
verdict() {  # verdict NAME STATUS WHAT
    if [ "$2" -eq 0 ]; then pass=$((pass + 1)); echo "ok   $1: $3"; else fail=$((fail + 1)); echo "FAIL $1: $3"; fi
}

# run_one DIR: the stack on the tandem scenario, logging what the replays need.
run_one() {
    local dir=$1
    stack_init "$dir" "udpm://239.255.76.67:7940?ttl=0&recv_buf_size=4194304"
    stack_set lms 'units = "cm"'
    stack_set terrain 'publish_hz = 4.0'
    stack_start_logger -c 'POSE|POINTS_.*|TERRAIN_MAP|STATUS_.*'
    stack_start_devices --duration "$seconds" --scenario "$root/tools/sim/scenarios/tandem.toml" || return 1
    stack_start_daemons lms servo nodscan gps imu pose terrain
    while stack_alive sim-world; do sleep 0.5; done
    stack_stop >/dev/null 2>&1
    [ -z "$(stack_unclean)" ] && [ ${#STACK_KILLED[@]} -eq 0 ]
}

# coverage_of DIR NAME REGEX: ugv-terrain --replay of DIR/ugv.lcm from the clouds on REGEX;
# prints the coverage summary (JSON).
coverage_of() {
    local dir=$1 name=$2 regex=$3
    printf 'publish_hz = 4.0\npoints_channel = "%s"\nmap_file = ""\n' "$regex" >"$dir/terrain-$name.toml"
    "$STACK_BIN/ugv-terrain" --config "$dir/terrain-$name.toml" --replay "$dir/ugv.lcm" --out "$dir/map-$name.lcm" \
        >"$dir/stderr/replay-$name.log" 2>&1 || return 1
    "$STACK_BIN/ugv-eval" coverage "$dir/map-$name.lcm" --ahead 2,20 --half-width 6 --turn 80 --window 5
}

declare -a left=() right=() both=()
echo "# $runs run(s) of the tandem, ${seconds} s each; load: $(cut -d' ' -f1-3 /proc/loadavg)"
worse=0
for ((i = 1; i <= runs; i++)); do
    dir=$work/run-$i
    run_one "$dir"
    rc=$?
    l=$(coverage_of "$dir" left POINTS_LEFT) r=$(coverage_of "$dir" right POINTS_RIGHT) b=$(coverage_of "$dir" both 'POINTS_.*')
    cl=$(jq -r '.mean_coverage // empty' <<<"$l" 2>/dev/null) cr=$(jq -r '.mean_coverage // empty' <<<"$r" 2>/dev/null)
    cb=$(jq -r '.mean_coverage // empty' <<<"$b" 2>/dev/null)
    verdict "run-$i" "$([ $rc -eq 0 ] && [ -n "$cl" ] && [ -n "$cr" ] && [ -n "$cb" ]; echo $?)" \
        "coverage after the turn: left ${cl:-none}, right ${cr:-none}, both ${cb:-none} (see $dir)"
    for x in "left $l" "right $r" "both $b"; do echo "#   ${x%% *}: ${x#* }"; done
    left+=("${cl:-0}") right+=("${cr:-0}") both+=("${cb:-0}")
    awk -v l="${cl:-0}" -v r="${cr:-0}" -v b="${cb:-0}" 'BEGIN { exit !(b > l && b > r) }' || worse=$((worse + 1))
done
mean() { printf '%s\n' "$@" | awk '{ s += $1 } END { printf "%.3f", s / NR }'; }
verdict two-more "$worse" "mean coverage after the turn: left $(mean "${left[@]}"), right $(mean "${right[@]}"), both $(mean "${both[@]}") over $runs run(s)"
echo "$pass passed, $fail failed"
[ $keep -eq 1 ] && echo "# kept: $work"
[ "$fail" -eq 0 ]
