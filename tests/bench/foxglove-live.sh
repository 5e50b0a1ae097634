#!/usr/bin/env bash
# Bench: ugv-foxglove's CPU and its latency from LCM to a client, while an lcm-logplayer
# replay of LOG runs at real speed and one client (tests/foxglove/watch_live.mjs, Foxglove's
# own client library) watches TOPICS (default: the terrain grid and the pose); then its
# resident memory (VmRSS, peak VmHWM):
#   tests/bench/foxglove-live.sh LOG [SECONDS] [TOPIC...]
# With TOPICS = none, no client connects (the bridge's own cost). Prints the CPU as a share
# of one core over the window and, per topic, two latencies: at Foxglove's client's message
# event (node: its event loop and collector included) and at the arrival of a message's last
# byte on the socket of a second client that does nothing else (ugv-test-foxglove-latency,
# C++), the goal's "to the client's socket"; UGV_BENCH_CLIENTS picks them (default
# "node socket"; the CPU figure of one client watching needs one of them alone). Needs the npm packages of tests/foxglove
# installed in build/tests/foxglove-node (test_foxglove_live does it).
# LCM on UGV_BENCH_LCM_PORT (7936), the server on UGV_BENCH_WS_PORT (18762); more config
# lines in UGV_BENCH_FOXGLOVE_KEYS (e.g. 'bus_batch_ms = 10').
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=${UGV_BIN_DIR:-$root/build/bin}
node_dir=${UGV_BUILD_DIR:-$root/build}/tests/foxglove-node
log=$1; seconds=${2:-60}; shift $(( $# >= 2 ? 2 : $# ))
topics=("$@"); [ ${#topics[@]} -eq 0 ] && topics=(TERRAIN_MAP/grid POSE/pose POSE/tf)
clients=${UGV_BENCH_CLIENTS:-node socket}
[ "${topics[0]}" = none ] && clients=none
lcm_port=${UGV_BENCH_LCM_PORT:-7936}; ws_port=${UGV_BENCH_WS_PORT:-18762}
url="udpm://239.255.76.67:$lcm_port?ttl=0&recv_buf_size=4194304"
work=$(mktemp -d); trap 'kill $fg_pid $player_pid 2>/dev/null; rm -rf "$work"' EXIT
printf 'address = "127.0.0.1"\nport = %s\n%s\n' "$ws_port" "${UGV_BENCH_FOXGLOVE_KEYS:-}" >"$work/foxglove.toml"
"$bin/ugv-foxglove" --config "$work/foxglove.toml" --lcm-url "$url" 2>"$work/foxglove.log" & fg_pid=$!
sleep 1
lcm-logplayer --lcm-url="$url" "$log" >/dev/null 2>&1 & player_pid=$!
sleep 2  # the channels advertised
cpu_ticks() { awk '{print $14 + $15}' "/proc/$fg_pid/stat"; }
t0=$(cpu_ticks); s0=$(date +%s.%N)
if [ "${topics[0]}" = none ]; then sleep "$seconds"
else
  pids=()
  for c in $clients; do
    case $c in
      socket) "$bin/ugv-test-foxglove-latency" "ws://127.0.0.1:$ws_port" "$seconds" "${topics[@]}" & pids+=($!) ;;
      node) node "$node_dir/watch_live.mjs" "ws://127.0.0.1:$ws_port" "$seconds" "${topics[@]}" & pids+=($!) ;;
      *) echo "foxglove-live: UGV_BENCH_CLIENTS: unknown client '$c' (node, socket)" >&2; exit 2 ;;
    esac
  done
  for p in "${pids[@]}"; do wait "$p"; done
fi
t1=$(cpu_ticks); s1=$(date +%s.%N)
awk -v t="$((t1 - t0))" -v hz="$(getconf CLK_TCK)" -v s0="$s0" -v s1="$s1" -v c="${topics[*]}" -v n="$clients" \
  'BEGIN { printf "foxglove-live: ugv-foxglove CPU %.2f %% of one core over %.1f s (clients: %s; watching: %s)\n", 100 * t / hz / (s1 - s0), s1 - s0, n, c }'
grep -E '^Vm(RSS|HWM)' "/proc/$fg_pid/status" | tr -s ' \t' ' ' | paste -sd ' ' | sed 's/^/foxglove-live: ugv-foxglove /'
kill -TERM $fg_pid; wait $fg_pid 2>/dev/null || true
tail -n 1 "$work/foxglove.log"
