#!/usr/bin/env bash
# ugv-spy under Xvfb while the simulated vehicle runs (ugv-sim world and every daemon, from
# tools/lib/stack.sh): the "LCM Spy" window comes up, lcm-spy
# loads our 14 types from the jar, and a screenshot is kept in build/test-artifacts/ugv-spy.png
# (look at it: the Type column names our types; an unknown type would show "?").
set -uo pipefail
build=$1 src=$2
for t in Xvfb xwd xwininfo java; do command -v $t >/dev/null || { echo "SKIPPED: $t is not installed"; exit 77; }; done
work=$(mktemp -d /tmp/ugv-spy-XXXXXX)
export UGV_BIN_DIR=$build/bin
# shellcheck source=../../../tools/lib/stack.sh
. "$src/tools/lib/stack.sh"
pids=()
cleanup() { stack_stop >/dev/null 2>&1; for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done; wait 2>/dev/null; rm -rf "$work"; }
trap cleanup EXIT
pass=0 fail=0
check() { if [ "$1" = ok ]; then pass=$((pass+1)); echo "ok   $2"; else fail=$((fail+1)); echo "FAIL $2"; fi; }

display=:$((90 + RANDOM % 400))
Xvfb "$display" -screen 0 1024x700x24 -nolisten tcp >"$work/xvfb.log" 2>&1 & pids+=($!)
url="udpm://239.255.76.67:7642?ttl=0"
stack_init "$work/stack" "$url"
stack_set lms 'units = "cm"'
stack_start_devices --duration 60 || { echo "FAIL the simulator did not come up"; exit 1; }
stack_start_daemons
sleep 1
DISPLAY=$display "$build/bin/ugv-spy" --lcm-url "$url" >"$work/spy.out" 2>&1 & pids+=($!)
up=no
for _ in $(seq 60); do
  DISPLAY=$display xwininfo -root -tree 2>/dev/null | grep -q '"LCM Spy"' && { up=ok; break; }
  sleep 0.5
done
check $up "the LCM Spy window came up"
sleep 3   # let a few messages arrive and the table fill
grep -q "Found 14 LCM types" "$work/spy.out" && check ok "lcm-spy loaded our 14 types from ugv_lcmtypes.jar" \
  || check no "lcm-spy did not report our 14 types: $(head -3 "$work/spy.out" | tr '\n' ' ')"
mkdir -p "$build/test-artifacts"
if DISPLAY=$display xwd -root -silent >"$work/spy.xwd" && python3 "$src/tools/spy/xwd2png.py" "$work/spy.xwd" "$build/test-artifacts/ugv-spy.png"; then
  check ok "screenshot kept: $build/test-artifacts/ugv-spy.png"
else check no "screenshot failed"; fi
grep -qi exception "$work/spy.out" && check no "lcm-spy printed an exception: $(grep -i -m1 exception "$work/spy.out")" \
  || check ok "no exception from lcm-spy"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
