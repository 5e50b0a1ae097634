#!/usr/bin/env bash
# Bench: the GPS receiver and ugv-gps alone, about 25 s.
#   tests/bench/gps-fix.sh [--device /dev/ugv/gps] [--seconds 10] [--keep]
# Default: against `ugv-sim gps --pty` (a parked NovAtel OEM4 at 50 N, 110.7 W, SINGLE fixes
# with 1.5 m noise). A real receiver: --device PATH or UGV_GPS_DEVICE=PATH, with its antenna
# under open sky (a fix is checked); the daemon configures it (BESTPOSB + BESTVELB at 4 Hz,
# 9600 baud: its defaults). UGV_BENCH_GPS_RATE (MIN:MAX Hz, default 3.5:4.5) for other logs.
# Checks: RUNNING, fix and velocity rates with no seq gap, every fix's content (a fix, WGS84
# ranges, finite sigmas, stamp = receiver time within 2 s of the host clock), the emulator's
# position, the daemon's error counters, a clean stop.
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=10
rate=${UGV_BENCH_GPS_RATE:-3.5:4.5}
bench_one_device gps-fix 7302 gps "$@"

now_us=$(( $(date +%s%N) / 1000 ))
expect fix-rate --channel GPS_FIX --for "$BENCH_SECONDS" --rate "$rate" --max-gap 0
expect vel-rate --channel GPS_VEL --for 3 --rate "$rate" --max-gap 0
# quality 1..5: SINGLE to RTK_FIXED (0 is no fix, 6 dead reckoning, 7 unknown/entered).
expect fix-content --channel GPS_FIX --for 3 --where "fix_quality >= 1 && fix_quality <= 5 && \
latitude >= -90 && latitude <= 90 && longitude >= -180 && longitude <= 180 && \
sigma_latitude > 0 && sigma_longitude > 0 && sigma_height > 0 && gps_week > 0 && \
utime > $((now_us - 2000000)) && utime < $((now_us + 20000000))"
if [ -z "$(stack_given_device gps)" ]; then
    # The emulator's antenna: 50 N, 110.7 W with SINGLE noise (1.5 m = 1.4e-5 deg of latitude).
    expect fix-position --channel GPS_FIX --for 2 \
        --where 'latitude > 49.9999 && latitude < 50.0001 && longitude > -110.7002 && longitude < -110.6998 && fix_quality == 1'
fi
counters_zero errors STATUS_GPS live crc_errors bad_length malformed reconnects silences configure_failures open_failures bus_publish_failures
stop_clean
bench_end
