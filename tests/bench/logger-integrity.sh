#!/usr/bin/env bash
# Bench: nothing is lost between the daemons and lcm-logger, about 45 s.
#   tests/bench/logger-integrity.sh [--seconds 30] [--lms PATH --gps PATH --imu PATH --servo TRANSPORT] [--keep]
# The whole stack through tools/lib/stack.sh (the simulated vehicle, or the real devices
# given) with lcm-logger for --seconds, then stopped: daemons first (each sends a last
# STOPPING status after its last message), the logger last. Checks on the log:
#   seq CHANNEL       seq runs 0, 1, 2, ... with no gap or step back: every message the
#                     publisher sent since it started was recorded (ugv-logstat);
#   published CHANNEL the daemon's own count of published messages in its last status is
#                     in the log (the log may hold more: a device thread can publish while
#                     the status goes out);
#   drops STATUS      the daemon's drop counters are 0 (see BENCH_DROPS in bench.sh).
# LCM: ttl=0 with recv_buf_size=2 MiB (UGV_BENCH_RECV_BUF): a map is ~265 kB, more than
# Debian's default receive buffer (rmem_default 208 kB), see docs/deploy.md.
source "$(dirname "$0")/bench.sh"
BENCH_SECONDS=30
bench_whole_stack logger-integrity 7311 "$@"

sleep "$BENCH_SECONDS"
stop_clean
log_seq_contiguous "$STACK_OUT/ugv.lcm"
log_has_published "$STACK_OUT/ugv.lcm"
log_no_drops "$STACK_OUT/ugv.lcm"
bench_end
