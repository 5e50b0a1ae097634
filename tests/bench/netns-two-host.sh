#!/usr/bin/env bash
# Bench: the stack on two computers, built from two network namespaces joined by a veth
# pair; about 3 minutes, bounded (the script stops itself after --seconds + 150 s). Root only.
#   sudo tests/bench/netns-two-host.sh [--seconds 60] [--keep]
# Host A runs ugv-sim (the simulated vehicle) and the device daemons plus ugv-nodscan; host B
# runs ugv-pose and ugv-terrain. LCM: udpm://239.255.76.67:7667?ttl=1 with a route for the
# group on each end of the link (10.254.76.1/24 and .2, a private test link that nothing else
# sees; the namespaces and the link are deleted on exit). Phases:
#   1. single host: everything in A; its log (A) is the reference.
#   2. two hosts: lcm-logger on both. Checks: every daemon RUNNING (seen from B), rates on B
#      of what crosses the link, seq contiguous on every channel of both logs (nothing lost
#      across the link, either way), every published message in B's log, and the last map
#      against the single-host run's: `ugv-eval diff --pair last` (cells at the same place in
#      the world) within RMS 0.02 m over the cells both know, and both maps against the
#      world's truth: the two-host RMSE within 0.01 m of the single-host one, its coverage at
#      least 70 % of it. Not 0: these are two real-time runs of the simulator, so the nodding
#      laser samples the ground at other instants (the sparse far scan
#      lines fall in other cells); docs/bench.md gives the measured figures.
#   3. transport alone, exactly: lcm-logplayer on A plays phase 1's POINTS and POSE to a
#      ugv-terrain on B; its maps equal phase 1's, cell for cell (tolerance 0, as in
#      replay-equivalence.sh).
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=60
bench_flags none "$@"
if [ "$(id -u)" -ne 0 ]; then
    echo "netns-two-host: skipped: needs root (ip netns, veth); run it with sudo"
    echo "0 passed, 0 failed"
    exit 77
fi
url="udpm://239.255.76.67:7667?ttl=1&recv_buf_size=${UGV_BENCH_RECV_BUF:-2097152}"
UGV_BENCH_LCM_URL=$url bench_begin netns-two-host 7667
host_a=ugv-bench-a-$$ host_b=ugv-bench-b-$$
in_a="ip netns exec $host_a" in_b="ip netns exec $host_b"

netns_cleanup() {
    [ ${#STACK_PIDS[@]} -gt 0 ] && stack_stop
    ip netns del "$host_a" 2>/dev/null
    ip netns del "$host_b" 2>/dev/null
    [ -n "${watchdog:-}" ] && kill "$watchdog" 2>/dev/null
    bench_cleanup
}
trap netns_cleanup EXIT
( sleep $((BENCH_SECONDS + 150)); echo "netns-two-host: time limit reached" >&2; kill -TERM $$ ) &
watchdog=$!

ip netns add "$host_a" && ip netns add "$host_b" &&
    ip link add "ugva$$" netns "$host_a" type veth peer name "ugvb$$" netns "$host_b" &&
    ip -n "$host_a" addr add 10.254.76.1/24 dev "ugva$$" && ip -n "$host_b" addr add 10.254.76.2/24 dev "ugvb$$" &&
    for h in "$host_a:ugva$$" "$host_b:ugvb$$"; do
        ip -n "${h%:*}" link set lo up && ip -n "${h%:*}" link set "${h#*:}" up &&
            ip -n "${h%:*}" route add 239.255.76.67/32 dev "${h#*:}" || exit 1
    done
verdict link $? "$host_a (10.254.76.1) <-> $host_b (10.254.76.2), multicast route on both ends"

# run_until_world_ends: the scenario runs --seconds (or to its end); then the pipeline drains.
run_until_world_ends() {
    local deadline=$((SECONDS + BENCH_SECONDS + 30))
    while stack_alive sim-world && [ $SECONDS -lt $deadline ]; do sleep 0.5; done
    sleep 2
}
world_args=()
stack_has_world && world_args=(--duration "$BENCH_SECONDS")

# ---- 1. single host
stack_init "$BENCH_WORK/single" "$url"
STACK_PREFIX=$in_a stack_start_logger
STACK_PREFIX=$in_a stack_start_devices "${world_args[@]}" || { verdict devices 1 "no devices"; bench_end; exit; }
STACK_PREFIX=$in_a stack_start_daemons
echo "# 1. single host: everything on A"
run_until_world_ends
stack_stop
single=$BENCH_WORK/single/ugv.lcm
single_maps=$("$STACK_BIN/ugv-logstat" "$single" --channel TERRAIN_MAP --json | jq -r '.count // 0')
verdict single-host "$([ "$single_maps" -gt 0 ]; echo $?)" "$single_maps maps"

# ---- 2. two hosts
stack_init "$BENCH_WORK/two" "$url"
STACK_PREFIX=$in_b stack_start_logger
STACK_PREFIX=$in_a stack_spawn lcm-logger-a lcm-logger --lcm-url="$url" -f "$BENCH_WORK/two/host-a.lcm"
STACK_PREFIX=$in_a stack_start_devices "${world_args[@]}" || { verdict devices 1 "no devices"; bench_end; exit; }
STACK_PREFIX=$in_a stack_start_daemons lms gps imu servo nodscan
STACK_PREFIX=$in_b stack_start_daemons pose terrain
echo "# 2. two hosts: devices, ugv-nodscan on A; ugv-pose, ugv-terrain on B"
STACK_PREFIX=$in_b
for d in "${STACK_DAEMONS[@]}"; do running "running ugv-$d (seen from B)" "STATUS_${d^^}" 30; done
expect_bg "on B: POINTS" --channel POINTS --for 10 --rate 35:40 --max-gap 0
expect_bg "on B: IMU" --channel IMU --for 10 --rate 48:53 --max-gap 0
expect_bg "on B: GPS_FIX" --channel GPS_FIX --for 10 --rate 3.5:4.5 --max-gap 0
expect_bg "on B: TERRAIN_MAP" --channel TERRAIN_MAP --for 10 --rate 1.7:2.3 --max-gap 0
expect_collect
unset STACK_PREFIX
run_until_world_ends
stack_stop
log_seq_contiguous "$BENCH_WORK/two/ugv.lcm" "host B:"
log_seq_contiguous "$BENCH_WORK/two/host-a.lcm" "host A:"
log_has_published "$BENCH_WORK/two/ugv.lcm"
check "map vs single host" "$STACK_BIN/ugv-eval" diff "$single" "$BENCH_WORK/two/ugv.lcm" --pair last --max-rms-dz 0.02
if [ -f "$BENCH_WORK/two/run/truth.hf" ]; then
    truth_of() { "$STACK_BIN/ugv-eval" compare "$1/ugv.lcm" --truth "$1/run/truth.hf" | jq -r '"\(.rmse_m) \(.coverage)"'; }
    read -r rmse1 cov1 < <(truth_of "$BENCH_WORK/single")
    read -r rmse2 cov2 < <(truth_of "$BENCH_WORK/two")
    verdict "accuracy vs single host" "$(awk -v a="$rmse1" -v b="$rmse2" -v c="$cov1" -v d="$cov2" \
        'BEGIN { exit !(b <= a + 0.01 && d >= 0.7 * c) }'; echo $?)" \
        "against the truth: single host RMSE $rmse1 m, coverage $cov1; two hosts RMSE $rmse2 m, coverage $cov2 (want RMSE within +0.01 m, coverage >= 70 %)"
fi

# ---- 3. the transport alone: phase 1's inputs from A to a ugv-terrain on B
stack_init "$BENCH_WORK/transport" "$url"
STACK_PREFIX=$in_b stack_start_logger -c 'TERRAIN_MAP'
STACK_PREFIX=$in_b stack_spawn ugv-terrain "$STACK_BIN/ugv-terrain" --config "$BENCH_WORK/single/config/terrain.toml"
sleep 1
$in_a lcm-logplayer -s 2 -e '^(POINTS.*|POSE)$' -l "$url" "$single" >"$BENCH_WORK/transport/stderr/lcm-logplayer.log" 2>&1
sleep 1
stack_stop
check "maps across the link" "$STACK_BIN/ugv-eval" diff "$single" "$BENCH_WORK/transport/ugv.lcm" --pair time \
    --max-dz 0 --max-one-sided 0
bench_end
