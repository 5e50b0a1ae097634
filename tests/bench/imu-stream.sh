#!/usr/bin/env bash
# Bench: the MicroStrain 3DM-GX1 and ugv-imu alone, about 25 s.
#   tests/bench/imu-stream.sh [--device /dev/ugv/imu] [--seconds 10] [--keep]
# Default: against `ugv-sim imu --pty` (level, facing north, 50 Hz nominal). A real unit:
# --device PATH or UGV_IMU_DEVICE=PATH, lying still on the bench with its base down (the
# checks assume gravity on +Z within ~30 deg and no rotation); 38400 baud, command 0x31.
# UGV_BENCH_IMU_RATE (MIN:MAX Hz, default 48:53; the default timing gives 50.9 Hz).
# Checks: RUNNING, rate and seq gaps, every sample's content (valid bits of 0x31, gravity,
# no rotation, host-clock stamp), the emulator's attitude, the daemon's error counters, a
# clean stop.
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=10
rate=${UGV_BENCH_IMU_RATE:-48:53}
bench_one_device imu-stream 7303 imu "$@"

since_us=$(( $(date +%s%N) / 1000 - 1000000 ))
expect imu-rate --channel IMU --for "$BENCH_SECONDS" --rate "$rate" --max-gap 0
# 0x31: ORIENTATION | EULER | ANGULAR_RATE | ACCELERATION = 15. Still: |rate| < 0.1 rad/s;
# level enough: specific force on body Z above 8.5 m/s^2 (cos 30 deg x g).
expect imu-content --channel IMU --for 3 --where "valid == 15 && acceleration[2] > 8.5 && acceleration[2] < 11 && \
angular_rate[0] > -0.1 && angular_rate[0] < 0.1 && angular_rate[1] > -0.1 && angular_rate[1] < 0.1 && \
angular_rate[2] > -0.1 && angular_rate[2] < 0.1 && orientation[0] >= 0 && utime > $since_us"
if [ -z "$(stack_given_device imu)" ]; then
    # The emulator: level (noise 0.05 deg) and heading 0 deg NED = north = yaw 90 deg ENU.
    expect imu-attitude --channel IMU --for 2 \
        --where 'roll > -0.01 && roll < 0.01 && pitch > -0.01 && pitch < 0.01 && yaw > 1.56 && yaw < 1.58'
fi
counters_zero errors STATUS_IMU live checksum_errors reconnects silences handshake_failures publish_failures bus_publish_failures
stop_clean
bench_end
