#!/usr/bin/env bash
# Bench: time back to RUNNING after a device is unplugged and plugged back, for the LMS, the
# GPS, the IMU and the servo, about 3 min.
#   tests/bench/device-recovery.sh [--keep]
# The four emulators (`ugv-sim NAME --pty`) and their daemons run side by side. For each
# device in turn, UGV_BENCH_UNPLUGS (5) times: the emulator is killed (SIGKILL: the pty
# vanishes as a USB adapter would) and its link removed, UGV_BENCH_UNPLUG_S (5) seconds pass, and a fresh
# emulator (a device just powered) is started on the same path. The time back is measured
# from the moment the new device's path exists to the daemon's log line `-> RUNNING` (the log
# is read every 10 ms, so figures are +10 ms at most). Emulators only: a real device would
# have to be unplugged by hand.
# Checks per device: the daemon went DEGRADED and came back every time, never restarted;
# n, p50 and max of the times back against the goal (UGV_BENCH_RECOVERY_GOAL_MS, 2000).
source "$(dirname "$0")/bench.sh"
unplugs=${UGV_BENCH_UNPLUGS:-5}
unplug_s=${UGV_BENCH_UNPLUG_S:-5}
goal_ms=${UGV_BENCH_RECOVERY_GOAL_MS:-2000}
devices=(lms gps imu servo)
bench_flags none "$@"
bench_begin device-recovery 7320

now_ms() { echo $(( $(date +%s%N) / 1000000 )); }
running_lines() { grep -c -- '-> RUNNING' "$STACK_OUT/stderr/ugv-$1.log"; }
degraded_lines() { grep -c -- '-> DEGRADED' "$STACK_OUT/stderr/ugv-$1.log"; }

# device_path NAME: the file whose appearance means the device is back.
device_path() { echo "$STACK_OUT/run/$1"; }

# wait_for S CMD...: CMD every 10 ms until it succeeds; 1 after S seconds.
wait_for() {
    local deadline=$(( $(now_ms) + $1 * 1000 )); shift
    until "$@"; do
        [ "$(now_ms)" -ge "$deadline" ] && return 1
        sleep 0.01
    done
}

more_running() { [ "$(running_lines "$1")" -gt "$2" ]; }

# unplug_and_back NAME: one cycle; sets back_ms to the time back in ms, or empty when the
# daemon never came back. Runs in this shell (it starts the new emulator).
unplug_and_back() {
    local name=$1 sim=sim-$1 before_running before_degraded back
    back_ms=
    before_running=$(running_lines "$name")
    before_degraded=$(degraded_lines "$name")
    kill -KILL "${STACK_PIDS[$sim]}" 2>/dev/null
    wait "${STACK_PIDS[$sim]}" 2>/dev/null
    unset "STACK_PIDS[$sim]"
    # Gone as udev removes an unplugged adapter's node. Left dangling, the link would point at
    # a /dev/pts number the kernel may give to another process's pty, and the daemon would
    # open and probe that.
    rm -f "$(device_path "$name")"
    sleep "$unplug_s"
    [ "$(degraded_lines "$name")" -gt "$before_degraded" ] || echo "# $name: not DEGRADED while unplugged"
    stack_spawn "$sim" "$STACK_BIN/ugv-sim" "$name" --pty "$(device_path "$name")"
    wait_for 10 test -e "$(device_path "$name")" || return
    back=$(now_ms)
    wait_for 30 more_running "$name" "$before_running" || return
    back_ms=$(( $(now_ms) - back ))
}

# percentile P VALUES...: the P-th percentile (nearest rank) of the values.
percentile() {
    local p=$1; shift
    printf '%s\n' "$@" | sort -n | awk -v p="$p" '{ v[NR] = $1 } END { r = int((p * NR + 99) / 100); if (r < 1) r = 1; print v[r] }'
}

for d in "${devices[@]}"; do stack_start_device "$d" || { verdict "device $d" 1 "emulator did not start"; bench_end; exit; }; done
stack_start_daemons "${devices[@]}"
for d in "${devices[@]}"; do running "running $d" "STATUS_${d^^}" 20; done

declare -A daemon_pid=()
for d in "${devices[@]}"; do daemon_pid[$d]=${STACK_PIDS[ugv-$d]}; done

for d in "${devices[@]}"; do
    times=()
    missed=0
    for ((i = 1; i <= unplugs; i++)); do
        unplug_and_back "$d"
        if [ -n "$back_ms" ]; then times+=("$back_ms"); else missed=$((missed + 1)); fi
        echo "# $d unplug $i: back to RUNNING in ${back_ms:-never} ms"
    done
    same=1
    [ "${STACK_PIDS[ugv-$d]}" = "${daemon_pid[$d]}" ] && kill -0 "${daemon_pid[$d]}" 2>/dev/null && same=0
    verdict "alive $d" "$same" "ugv-$d pid ${daemon_pid[$d]} ran through $unplugs unplugs"
    if [ ${#times[@]} -eq 0 ]; then
        verdict "recovery $d" 1 "n=0: never back to RUNNING"
        continue
    fi
    p50=$(percentile 50 "${times[@]}")
    max=$(percentile 100 "${times[@]}")
    verdict "recovery $d" "$([ "$missed" -eq 0 ] && [ "$max" -le "$goal_ms" ]; echo $?)" \
        "n=${#times[@]} p50=${p50} ms max=${max} ms (goal ${goal_ms} ms; all: ${times[*]}; missed $missed)"
done

stop_clean
bench_end
