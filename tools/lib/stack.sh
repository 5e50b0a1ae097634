# shellcheck shell=bash
# tools/lib/stack.sh: start and stop the whole ugv stack from bash (tools/demo, tests/bench).
# Source it, then:
#
#   stack_init OUT [URL]          output folder (config/, run/, stderr/, ugv.lcm) and LCM URL
#   stack_set NAME 'key = value'  an extra config line for daemon NAME (lms gps imu servo
#                                 nodscan pose terrain traverse); top-level keys or whole tables
#   stack_start_logger [ARGS...]  lcm-logger -> OUT/ugv.lcm (ARGS: e.g. -c REGEX)
#   stack_start_devices [ARGS...] the four devices: `ugv-sim world` (ARGS go to it) when ugv-sim
#                                 offers it and no real device is given, else stack_start_device
#                                 for each
#   stack_scenario_models IMU GPS <IN >OUT  a scenario with [imu] / [gps] error_model set
#                                 (ahrs|white, markov|white; "" keeps it); white drops the
#                                 other model's keys (and [imu] angle_sigma_deg: 0.7 again)
#   stack_start_device NAME [ARGS...]  one device: the real one given by its variable (below),
#                                 else its emulator `ugv-sim NAME --pty OUT/run/NAME ARGS`
#   stack_start_daemons [NAME...] daemons (default: STACK_DAEMONS), config OUT/config/NAME.toml;
#                                 with several lasers, lms servo nodscan stand for every
#                                 instance (lms-left lms-right ...), or name one: lms-left
#   stack_start_foxglove          ugv-foxglove (the live view for Foxglove) on
#                                 UGV_FOXGLOVE_ADDRESS:UGV_FOXGLOVE_PORT (127.0.0.1:8765), config
#                                 OUT/config/foxglove.toml; sets and prints STACK_FOXGLOVE_URL
#                                 (ws://ADDRESS:PORT) once it listens, 1 if it did not come up
#   stack_stop                    daemons, then simulators, then the logger: SIGTERM, wait up
#                                 to STACK_STOP_WAIT_S (5) each, SIGKILL and report the rest
#   stack_counter CH NAME [LOG]   a counter of the daemon status on channel CH (STATUS_LMS):
#                                 live (the next status) or, with LOG, the last one in the log
#   stack_counter_in JSON NAME    the same from a status already read with stack_status_json
#   stack_state CH [LOG]          its state (0 STARTING, 1 RUNNING, 2 DEGRADED, 3 FAULT, 4 STOPPING)
#   stack_wait_running CH S [ST]  wait up to S seconds for state RUNNING (or ST); 1 if it never came
# and the pieces they use: stack_spawn NAME CMD... (any process, stopped with the others: by
# its name's group ugv-*, sim-*, lcm-logger*), stack_alive NAME, stack_has_world,
# stack_given_device NAME, stack_status_json CH [LOG], stack_unclean.
#
# Real devices (anything not given is simulated): UGV_LMS_DEVICE, UGV_GPS_DEVICE,
# UGV_IMU_DEVICE (serial ports), UGV_SERVO_TRANSPORT (`socketcan:can0` or `slcan:/dev/ttyACM0@115200`).
# With any of them set, the rest come from the separate emulators (the one-world simulator
# drives all four devices or none).
#
# Several lasers: a scenario with [[laser]] tables (docs/simulator.md) leaves per laser
# run/lms-NAME, run/servo-NAME and calibration/{nodscan,servo}-NAME.toml; stack_start_devices
# then sets STACK_LASERS=(NAME...) and STACK_DAEMONS to the instances: ugv-lms, ugv-servo and
# ugv-nodscan once per laser (daemon names lms-NAME, servo-NAME, nodscan-NAME, run with
# --instance NAME), each on its channels with the suffix _NAME in capitals: LMS_SCAN_LEFT,
# SERVO_STATE_LEFT, SERVO_COMMAND_LEFT, POINTS_LEFT, STATUS_LMS_LEFT (stack_status_channel
# NAME prints a daemon's), sensor_id NAME; ugv-terrain takes every POINTS.* channel.
# stack_set lms '...' applies to every lms instance, stack_set lms-left '...' to one.
#
# After stack_stop: STACK_KILLED (names that had to be killed) and STACK_EXIT[name] (exit
# statuses). STACK_PREFIX (words, e.g. `ip netns exec host-a`) runs the next processes inside
# something; set it for one call: `STACK_PREFIX="ip netns exec a" stack_start_devices`.
# Every process is a child of the sourcing shell: call the start functions directly, never in
# $( ) or a pipeline.

STACK_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
STACK_BIN=${UGV_BIN_DIR:-$STACK_ROOT/build/bin}
STACK_STOP_WAIT_S=${STACK_STOP_WAIT_S:-5}
STACK_ONE_LASER_DAEMONS=(lms gps imu servo nodscan pose terrain traverse)
STACK_DAEMONS=("${STACK_ONE_LASER_DAEMONS[@]}")
declare -A STACK_PIDS=() STACK_EXTRA=() STACK_DEVICE=() STACK_EXIT=()
STACK_KILLED=() STACK_LASERS=()
export STACK_SIM=none   # none | world | emulators: what the devices are (for the scripts)

stack_init() {  # stack_init OUT [URL]: a new stack (forgets the previous one's settings)
    STACK_OUT=$1
    STACK_EXTRA=() STACK_DEVICE=() STACK_EXIT=() STACK_KILLED=() STACK_SIM=none STACK_LASERS=()
    STACK_DAEMONS=("${STACK_ONE_LASER_DAEMONS[@]}")
    STACK_URL=${2:-${LCM_DEFAULT_URL:-udpm://239.255.76.67:7667?ttl=0}}
    export LCM_DEFAULT_URL=$STACK_URL
    mkdir -p "$STACK_OUT/config" "$STACK_OUT/run" "$STACK_OUT/stderr"
}

stack_set() { STACK_EXTRA[$1]+="$2"$'\n'; }

# stack_spawn NAME CMD...: one background process, its output in OUT/stderr/NAME.log.
stack_spawn() {
    local name=$1; shift
    # shellcheck disable=SC2086  # STACK_PREFIX is a list of words on purpose
    ${STACK_PREFIX:-} "$@" >"$STACK_OUT/stderr/$name.log" 2>&1 &
    STACK_PIDS[$name]=$!
}

stack_alive() { [ -n "${STACK_PIDS[$1]:-}" ] && kill -0 "${STACK_PIDS[$1]}" 2>/dev/null; }

# lcm-logger with libugv-lcm-queue.so preloaded (as ugv-logger.service runs it): without it,
# liblcm's 30-message subscription queue drops what arrives while the logger's main loop is
# not scheduled (tools/lcm_queue). Found next to the binaries (build/lib) or installed.
stack_lcm_queue_lib() {
    local f
    for f in "$STACK_BIN/../lib/libugv-lcm-queue.so" /usr/lib/ugv/libugv-lcm-queue.so; do
        [ -f "$f" ] && { echo "$f"; return 0; }
    done
    return 1
}

stack_start_logger() {
    local preload
    preload=$(stack_lcm_queue_lib) || echo "stack: libugv-lcm-queue.so not found: lcm-logger may drop messages after a stall" >&2
    LD_PRELOAD=${preload:-} stack_spawn lcm-logger lcm-logger --lcm-url="$STACK_URL" -f "$@" "$STACK_OUT/ugv.lcm"
}

stack_has_world() { "$STACK_BIN/ugv-sim" --help 2>/dev/null | grep -q '^  world '; }

# stack_wait_paths S PATH...: wait up to S seconds until every path exists.
stack_wait_paths() {
    local deadline=$((SECONDS + $1)) p; shift
    for p in "$@"; do
        while [ ! -e "$p" ]; do
            [ $SECONDS -ge $deadline ] && { echo "stack: $p did not appear" >&2; return 1; }
            sleep 0.1
        done
    done
}

# stack_given_device NAME: the real device given for NAME (lms gps imu servo), or nothing.
stack_given_device() {
    case $1 in
        lms) echo "${UGV_LMS_DEVICE:-}" ;; gps) echo "${UGV_GPS_DEVICE:-}" ;;
        imu) echo "${UGV_IMU_DEVICE:-}" ;; servo) echo "${UGV_SERVO_TRANSPORT:-}" ;;
    esac
}

# stack_start_device NAME [ARGS...]: one device: the real one when given, else its emulator
# `ugv-sim NAME --pty OUT/run/NAME ARGS`.
stack_start_device() {
    local name=$1 pty=$STACK_OUT/run/$1 real; shift
    real=$(stack_given_device "$name")
    if [ -z "$real" ]; then
        stack_spawn "sim-$name" "$STACK_BIN/ugv-sim" "$name" --pty "$pty" "$@"
        STACK_SIM=emulators
        real=$pty
        stack_wait_paths 10 "$pty" || return 1
        [ "$name" = servo ] && real="slcan:$pty@115200"
    fi
    STACK_DEVICE[$name]=$real
}

stack_start_devices() {
    local run=$STACK_OUT/run d
    if [ -z "${UGV_LMS_DEVICE:-}${UGV_GPS_DEVICE:-}${UGV_IMU_DEVICE:-}${UGV_SERVO_TRANSPORT:-}" ] && stack_has_world; then
        STACK_SIM=world
        stack_spawn sim-world "$STACK_BIN/ugv-sim" world --run-dir "$run" --lcm-url "$STACK_URL" "$@"
        for d in lms gps imu; do STACK_DEVICE[$d]=$run/$d; done
        STACK_DEVICE[servo]="slcan:$run/servo@115200"
        stack_wait_paths 15 "$run/ready" || return 1
        stack_find_lasers "$run"
        return
    fi
    for d in lms gps imu servo; do stack_start_device "$d" || return 1; done
}

stack_scenario_models() {
    awk -v imu="$1" -v gps="$2" '
        /^\[/ { table = $0; done = 0 }
        { model = table == "[imu]" ? imu : table == "[gps]" ? gps : "" }
        model != "" && /^error_model *=/ { next }
        model == "white" && table == "[imu]" && /^(tilt_time_constant_s|gyro_bias_walk_dps_per_sqrt_s|mag_disturbance_deg|angle_sigma_deg) *=/ { next }
        model == "white" && table == "[gps]" && /^(rtk_fixed|rtk_float|dgps|sbas|single)_(sigma_m|time_constant_s) *=/ { next }
        { print }
        model != "" && /^\[/ && !done { print "error_model = \"" model "\""; done = 1 }'
}


# stack_find_lasers RUN: the named lasers of the world's run folder (calibration/nodscan-NAME.toml),
# their devices and daemon instances; none (one laser of a scenario without [[laser]]): as before.
stack_find_lasers() {
    local run=$1 f n d
    STACK_LASERS=()
    for f in "$run"/calibration/nodscan-*.toml; do
        [ -e "$f" ] || continue
        n=${f##*/nodscan-}; STACK_LASERS+=("${n%.toml}")
    done
    [ ${#STACK_LASERS[@]} -eq 0 ] && return 0
    STACK_DAEMONS=()
    for d in lms gps imu servo nodscan pose terrain traverse; do
        case $d in
            lms|servo|nodscan) for n in "${STACK_LASERS[@]}"; do STACK_DAEMONS+=("$d-$n"); done ;;
            *) STACK_DAEMONS+=("$d") ;;
        esac
    done
    for n in "${STACK_LASERS[@]}"; do
        STACK_DEVICE[lms-$n]=$run/lms-$n
        STACK_DEVICE[servo-$n]="slcan:$run/servo-$n@115200"
    done
}

# stack_status_channel NAME: the status channel of daemon NAME (lms, lms-left, pose ...).
stack_status_channel() {
    local name=$1 base=${1%%-*} inst=
    [ "$name" != "$base" ] && inst=_${name#*-}
    echo "STATUS_${base^^}${inst^^}"
}

# The keys that put one instance of a laser's daemon on that laser's channels.
stack_instance_keys() {
    local base=$1 n=$2 s=_${2^^}
    printf 'status_channel = "%s"\n' "$(stack_status_channel "$base-$n")"
    case $base in
        lms) printf 'sensor_id = "%s"\nchannel = "LMS_SCAN%s"\nraw_channel = "RAW_LMS%s"\n' "$n" "$s" "$s" ;;
        servo) printf 'channel = "SERVO_STATE%s"\ncommand_channel = "SERVO_COMMAND%s"\n' "$s" "$s" ;;
        nodscan) printf 'sensor_id = "%s"\nscan_channel = "LMS_SCAN%s"\nservo_channel = "SERVO_STATE%s"\nchannel = "POINTS%s"\n' \
                        "$n" "$s" "$s" "$s" ;;
    esac
}

# The config of one daemon: its device, the script's extra lines, then the simulator's
# calibration for it (tables, so they go last; a servo's and the IMU's have top-level keys
# only and go before the extra lines, which may end with a table). An instance (lms-left)
# gets its channel keys first and the extra lines of its base name (lms) before its own.
stack_write_config() {
    local name=$1 cfg=$STACK_OUT/config/$1.toml calib=$STACK_OUT/run/calibration/$1.toml base=${1%%-*} top=
    [ -f "$calib" ] || calib=
    case $base in servo|imu) top=$calib; calib= ;; esac
    {
        case $base in
            lms|gps|imu) printf 'device = "%s"\n' "${STACK_DEVICE[$name]:-}" ;;
            servo) printf 'transport = "%s"\n' "${STACK_DEVICE[$name]}" ;;
        esac
        [ "$name" != "$base" ] && stack_instance_keys "$base" "${name#*-}"
        [ -n "$top" ] && cat "$top"
        [ "$name" != "$base" ] && printf '%s' "${STACK_EXTRA[$base]:-}"
        printf '%s' "${STACK_EXTRA[$name]:-}"
        if [ -n "$calib" ]; then cat "$calib"; fi
    } >"$cfg"
}

stack_start_foxglove() {
    local address=${UGV_FOXGLOVE_ADDRESS:-127.0.0.1} port=${UGV_FOXGLOVE_PORT:-8765}
    STACK_EXTRA[foxglove]+="address = \"$address\""$'\n'"port = $port"$'\n'
    stack_write_config foxglove
    stack_spawn ugv-foxglove "$STACK_BIN/ugv-foxglove" --config "$STACK_OUT/config/foxglove.toml"
    local tries=0
    until grep -q 'serving ' "$STACK_OUT/stderr/ugv-foxglove.log" 2>/dev/null; do
        stack_alive ugv-foxglove && [ $tries -lt 100 ] || return 1
        sleep 0.1; tries=$((tries + 1))
    done
    STACK_FOXGLOVE_URL=ws://$address:$port
    echo "ugv-foxglove: $STACK_FOXGLOVE_URL"
}

stack_start_daemons() {
    local names=() name n args
    [ $# -eq 0 ] && set -- "${STACK_DAEMONS[@]}"
    for name in "$@"; do
        case $name in
            lms|servo|nodscan) if [ ${#STACK_LASERS[@]} -gt 0 ]; then
                                   for n in "${STACK_LASERS[@]}"; do names+=("$name-$n"); done
                                   continue
                               fi ;;
        esac
        names+=("$name")
    done
    for name in "${names[@]}"; do
        stack_write_config "$name"
        args=()
        [ "$name" != "${name%%-*}" ] && args=(--instance "${name#*-}")
        stack_spawn "ugv-$name" "$STACK_BIN/ugv-${name%%-*}" --config "$STACK_OUT/config/$name.toml" "${args[@]}"
    done
}

# stack_stop_group PATTERN: SIGTERM to every process whose name matches, then a bounded wait.
# shellcheck disable=SC2053  # PATTERN is a glob on purpose
stack_stop_group() {
    local pattern=$1 name pid deadline
    for name in "${!STACK_PIDS[@]}"; do
        [[ $name == $pattern ]] && kill -TERM "${STACK_PIDS[$name]}" 2>/dev/null
    done
    deadline=$((SECONDS + STACK_STOP_WAIT_S))
    for name in "${!STACK_PIDS[@]}"; do
        [[ $name == $pattern ]] || continue
        pid=${STACK_PIDS[$name]}
        while kill -0 "$pid" 2>/dev/null && [ $SECONDS -lt $deadline ]; do sleep 0.1; done
        if kill -0 "$pid" 2>/dev/null; then
            kill -KILL "$pid" 2>/dev/null
            STACK_KILLED+=("$name")
            echo "stack: $name did not stop within ${STACK_STOP_WAIT_S} s (killed)" >&2
        fi
        wait "$pid" 2>/dev/null
        STACK_EXIT[$name]=$?
        unset "STACK_PIDS[$name]"
    done
}

stack_stop() {
    stack_stop_group 'ugv-*'
    stack_stop_group 'sim-*'
    sleep 0.5   # the daemons' last status messages reach the logger
    stack_stop_group 'lcm-logger*'
}

# stack_unclean: the processes stopped so far that did not exit 0, as NAME:STATUS words.
stack_unclean() {
    local name bad=()
    for name in "${!STACK_EXIT[@]}"; do
        [ "${STACK_EXIT[$name]}" -eq 0 ] || bad+=("$name:${STACK_EXIT[$name]}")
    done
    echo "${bad[*]}"
}

# stack_status_json CH [LOG]: one daemon_status_t as JSON (the next live one, or the log's last).
stack_status_json() {
    if [ -n "${2:-}" ]; then
        "$STACK_BIN/ugv-dump" --log "$2" --channel "$1" | tail -n 1
    else
        # shellcheck disable=SC2086
        ${STACK_PREFIX:-} "$STACK_BIN/ugv-dump" --lcm-url "$STACK_URL" --channel "$1" --count 1 --timeout 3
    fi
}

stack_counter() {  # prints the value, or nothing when the status or the counter is missing
    stack_counter_in "$(stack_status_json "$1" "${3:-}")" "$2"
}

# stack_counter_in JSON NAME: a counter of a status already read (several from one message).
stack_counter_in() {
    jq -r --arg n "$2" '.fields | [.counter_names, .counter_values] | transpose | map(select(.[0] == $n)) | .[0][1] // empty' <<<"$1"
}

stack_state() { stack_status_json "$1" "${2:-}" | jq -r '.fields.state // empty'; }

stack_wait_running() {  # stack_wait_running CH S [STATE]: RUNNING (1) or the given state
    local deadline=$((SECONDS + $2)) state
    while [ $SECONDS -lt $deadline ]; do
        state=$(stack_state "$1")
        [ "$state" = 1 ] || [ "$state" = "${3:-1}" ] && return 0
    done
    return 1
}
