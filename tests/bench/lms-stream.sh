#!/usr/bin/env bash
# Bench: the SICK LMS 2xx and ugv-lms alone, about 25 s.
#   tests/bench/lms-stream.sh [--device /dev/ugv/lms-front] [--seconds 10] [--keep]
# Default: against `ugv-sim lms --pty` (a level-ish laser over a flat floor 1 m below, pitched
# 10 deg down). A real LMS: --device PATH or UGV_LMS_DEVICE=PATH (the daemon's defaults:
# 500000 baud, 180 deg at 0.5 deg, mm). For a real device at another variant set
# UGV_BENCH_LMS_RATE (MIN:MAX Hz, default 35:40) and UGV_BENCH_LMS_BEAMS (default 361).
# Checks: RUNNING, scan rate and seq gaps over the window, every scan's layout and time stamp,
# (emulator only) the floor where it must be, the daemon's error counters, a clean stop.
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=10
rate=${UGV_BENCH_LMS_RATE:-35:40}
beams=${UGV_BENCH_LMS_BEAMS:-361}
bench_one_device lms-stream 7301 lms "$@"

since_us=$(( $(date +%s%N) / 1000 - 1000000 ))
expect scan-rate --channel LMS_SCAN --for "$BENCH_SECONDS" --rate "$rate" --max-gap 0
# Beam layout and the stamp: host time (the first beam, at most ~0.1 s before arrival), not
# the device's own clock.
expect scan-layout --channel LMS_SCAN --for 2 \
    --where "nranges == $beams && ranges.size() == $beams && flags.size() == $beams && utime > $since_us && scan_period > 0 && time_increment > 0"
if [ -z "$(stack_given_device lms)" ]; then
    # The emulator's floor: 1 m below, plane pitched 10 deg: straight ahead at 1/sin(10 deg).
    expect scan-floor --channel LMS_SCAN --for 2 --where 'ranges[180] > 5.70 && ranges[180] < 5.82'
fi
counters_zero errors STATUS_LMS live crc_errors bad_scans reconnects publish_failures bus_publish_failures
status=$(stack_status_json STATUS_LMS)
scans=$(stack_counter_in "$status" scans)
published=$(stack_counter_in "$status" published)
# The two counters are read while a scan may be between them: equal within one.
verdict published "$([ "${scans:-0}" -gt 0 ] && [ $((scans - ${published:-0})) -le 1 ] && [ $((published - scans)) -le 1 ]; echo $?)" \
    "every decoded scan published (scans ${scans:-?}, published ${published:-?})"
stop_clean
bench_end
