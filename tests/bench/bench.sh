# shellcheck shell=bash
# tests/bench/bench.sh: what every bench scenario shares (sourced by each script). It sources
# tools/lib/stack.sh, makes a work folder and stops the stack on exit.
#
#   bench_begin NAME PORT      work folder /tmp/ugv-bench-NAME-XXXX (kept with UGV_BENCH_KEEP=1,
#                              or in UGV_BENCH_OUT), LCM udpm port PORT (ttl=0) with a receive
#                              buffer of UGV_BENCH_RECV_BUF bytes (2 MiB), or UGV_BENCH_LCM_URL
#   bench_one_device NAME PORT DEVICE ARGS...   flags, bench_begin, the device (real or its
#                              emulator) and its daemon, the `running` check
#   bench_whole_stack NAME PORT ARGS...          flags, bench_begin, bench_start_stack:
#                              lcm-logger, the devices (ugv-sim world for BENCH_SECONDS + 30 s),
#                              all eight daemons
#   check NAME CMD...          runs CMD; prints `ok NAME: <its last output line>` or FAIL
#   verdict NAME OK WHAT       the same for a condition already computed (OK: 0 = pass)
#   expect NAME ARGS...        ugv-expect ARGS (on the bench's URL) as a check
#   expect_bg NAME ARGS...     the same in the background (several channels at once) ...
#   expect_collect             ... and their checks, in the order they were started
#   bench_world_log_flags ARGS...  --out DIR, --keep, --score DIR (BENCH_SCORE_ONLY), --help
#   bench_flags OWN ARGS...    --device PATH (the real device OWN: lms gps imu servo), --lms
#                              PATH, --gps PATH, --imu PATH, --servo TRANSPORT (real devices),
#                              --seconds S (BENCH_SECONDS), --keep (keep the work folder), --help
#   running NAME CH S [ST]     a check: the daemon of status channel CH is RUNNING (or in state
#                              ST) within S s
#   bench_end                  prints `N passed, N failed`; exit status 0 only when all passed
set -uo pipefail
BENCH_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
# shellcheck source=../../tools/lib/stack.sh
source "$BENCH_DIR/../../tools/lib/stack.sh"
BENCH_PASSED=0
BENCH_FAILED=0

# bench_world_log_flags ARGS...: the flags of a bench that runs a scenario on ugv-sim world and
# calibrates or scores its log: --out DIR, --keep, --score DIR (only score the log an earlier
# --out DIR kept: BENCH_SCORE_ONLY=DIR, else empty), --help. Exit 2 without the world simulator.
bench_world_log_flags() {
    BENCH_SCORE_ONLY=
    while [ $# -gt 0 ]; do
        case $1 in
            --out) shift; export UGV_BENCH_OUT=$1 ;;
            --keep) export UGV_BENCH_KEEP=1 ;;
            --score) shift; BENCH_SCORE_ONLY=$(realpath "$1") || exit 2 ;;
            -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
            *) echo "$(basename "$0"): unknown argument $1 (see --help)" >&2; exit 2 ;;
        esac
        shift
    done
    [ -n "$BENCH_SCORE_ONLY" ] && export UGV_BENCH_OUT=$BENCH_SCORE_ONLY
    stack_has_world || { echo "$(basename "$0"): $STACK_BIN/ugv-sim has no world simulator" >&2; exit 2; }
}

bench_flags() {
    local own=$1; shift
    while [ $# -gt 0 ]; do
        case $1 in
            --device) shift; bench_device "$own" "$1" ;;
            --lms|--gps|--imu|--servo) bench_device "${1#--}" "$2"; shift ;;
            --seconds) shift; BENCH_SECONDS=$1 ;;
            --keep) export UGV_BENCH_KEEP=1 ;;
            -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
            *) echo "$(basename "$0"): unknown argument $1 (see --help)" >&2; exit 2 ;;
        esac
        shift
    done
}

bench_device() {  # bench_device NAME PATH: the real device for NAME (the stack's variables)
    case $1 in
        lms) export UGV_LMS_DEVICE=$2 ;; gps) export UGV_GPS_DEVICE=$2 ;;
        imu) export UGV_IMU_DEVICE=$2 ;; servo) export UGV_SERVO_TRANSPORT=$2 ;;
        *) echo "$(basename "$0"): --device: this scenario has no device of its own; use --lms/--gps/--imu/--servo" >&2; exit 2 ;;
    esac
}

bench_begin() {
    local name=$1 port=$2
    BENCH_WORK=${UGV_BENCH_OUT:-$(mktemp -d "/tmp/ugv-bench-$name-XXXXXX")}
    mkdir -p "$BENCH_WORK"
    stack_init "$BENCH_WORK" "${UGV_BENCH_LCM_URL:-udpm://239.255.76.67:$port?ttl=0&recv_buf_size=${UGV_BENCH_RECV_BUF:-2097152}}"
    trap bench_cleanup EXIT
    trap 'echo "$name: interrupted" >&2; exit 130' INT TERM
    echo "# $name: LCM $STACK_URL, work folder $BENCH_WORK"
}

bench_one_device() {
    local name=$1 port=$2 device=$3; shift 3
    bench_flags "$device" "$@"
    bench_begin "$name" "$port"
    local given
    given=$(stack_given_device "$device")
    if [[ $given == /* ]] && [ ! -e "$given" ]; then verdict device 1 "$given does not exist"; bench_end; exit; fi
    if ! stack_start_device "$device"; then
        verdict device 1 "no device at ${STACK_DEVICE[$device]:-$(stack_given_device "$device")}"
        bench_end; exit
    fi
    stack_start_daemons "$device"
    running running "STATUS_${device^^}" 20
}

bench_whole_stack() {
    bench_flags none "${@:3}"
    bench_begin "$1" "$2"
    bench_start_stack
}

bench_start_stack() {
    local world=()
    # The simulated vehicle drives its path, then stands; it outlives the run either way.
    stack_has_world && world=(--duration "$((BENCH_SECONDS + 30))")
    stack_start_logger
    if ! stack_start_devices "${world[@]}"; then verdict devices 1 "the devices did not come up"; bench_end; exit; fi
    stack_start_daemons
}

bench_cleanup() {
    [ ${#STACK_PIDS[@]} -gt 0 ] && stack_stop
    if [ -z "${UGV_BENCH_KEEP:-}" ] && [ -z "${UGV_BENCH_OUT:-}" ]; then rm -rf "$BENCH_WORK"; fi
}

verdict() {  # verdict NAME STATUS WHAT
    if [ "$2" -eq 0 ]; then
        BENCH_PASSED=$((BENCH_PASSED + 1)); echo "ok   $1: $3"
    else
        BENCH_FAILED=$((BENCH_FAILED + 1)); echo "FAIL $1: $3"
    fi
}

check() {  # check NAME CMD...
    local name=$1 out rc; shift
    out=$("$@" 2>&1); rc=$?
    verdict "$name" "$rc" "$(tail -n 1 <<<"$out")"
}

# shellcheck disable=SC2086  # STACK_PREFIX: words
expect() { local name=$1; shift; check "$name" ${STACK_PREFIX:-} "$STACK_BIN/ugv-expect" --lcm-url "$STACK_URL" "$@"; }

# bench_state_text: a daemon_status_t JSON line on stdin -> "RUNNING" or "DEGRADED (why)".
bench_state_text() {
    jq -r '(["STARTING", "RUNNING", "DEGRADED", "FAULT", "STOPPING"][.fields.state] // "no status")
        + (if (.fields.last_error // "") != "" then " (" + .fields.last_error + ")" else "" end)'
}

running() {  # running NAME CH S [STATE]: RUNNING, or STATE where the scenario allows it
    local t0=$SECONDS state
    if stack_wait_running "$2" "$3" "${4:-1}"; then
        state=$(stack_status_json "$2" | bench_state_text)
        verdict "$1" 0 "$2 $state after $((SECONDS - t0)) s"
    else
        verdict "$1" 1 "$2 not RUNNING within $3 s ($(stack_status_json "$2" | bench_state_text))"
    fi
}

BENCH_BG=()
expect_bg() {
    local name=$1; shift
    # shellcheck disable=SC2086
    ${STACK_PREFIX:-} "$STACK_BIN/ugv-expect" --lcm-url "$STACK_URL" "$@" >"$BENCH_WORK/expect-$name.out" 2>&1 &
    BENCH_BG+=("$name:$!")
}

expect_collect() {
    local entry
    for entry in "${BENCH_BG[@]}"; do
        wait "${entry##*:}"
        verdict "${entry%:*}" $? "$(tail -n 1 "$BENCH_WORK/expect-${entry%:*}.out")"
    done
    BENCH_BG=()
}

# at_least NAME VALUE MIN WHAT: VALUE is a number >= MIN.
at_least() {
    local ok=1
    [[ $2 =~ ^-?[0-9]+$ ]] && [ "$2" -ge "$3" ] && ok=0
    verdict "$1" "$ok" "${4:-$1} = ${2:-missing} (want >= $3)"
}

# counters_zero NAME CH SOURCE COUNTER...: every named counter of a daemon status is 0.
# SOURCE: `live` (the next status on the bus) or a log (its last status, after the stop).
counters_zero() {
    local name=$1 ch=$2 src=$3 json seen=() nonzero=0 c v; shift 3
    [ "$src" = live ] && src=
    json=$(stack_status_json "$ch" "$src")
    for c in "$@"; do
        v=$(stack_counter_in "$json" "$c")
        seen+=("$c=${v:-missing}")
        [ "$v" = 0 ] || nonzero=1
    done
    verdict "$name" "$nonzero" "$ch ${seen[*]}"
}

# What each daemon counts as published, and the channel it goes to (STATUS COUNTER CHANNEL).
BENCH_PUBLISHED="STATUS_LMS published LMS_SCAN
STATUS_GPS fixes_published GPS_FIX
STATUS_GPS velocities_published GPS_VEL
STATUS_IMU published IMU
STATUS_SERVO samples SERVO_STATE
STATUS_NODSCAN scans_out POINTS
STATUS_POSE poses POSE
STATUS_TERRAIN maps_published TERRAIN_MAP
STATUS_TRAVERSE maps_published ARCS"

# The counters of data a daemon dropped or could not publish (STATUS COUNTER...). Input
# faults (CRC errors, resyncs) and start-up waits (points before the first pose) are not drops.
BENCH_DROPS="STATUS_LMS publish_failures bus_publish_failures
STATUS_GPS bus_publish_failures
STATUS_IMU publish_failures bus_publish_failures
STATUS_SERVO tx_failures bus_publish_failures bus_incomplete_messages
STATUS_NODSCAN scans_overflow bus_decode_failures bus_handler_errors bus_publish_failures bus_incomplete_messages
STATUS_POSE late bus_decode_failures bus_handler_errors bus_publish_failures bus_incomplete_messages
STATUS_TERRAIN clouds_malformed clouds_rejected_time poses_rejected_out_of_order bus_decode_failures bus_handler_errors bus_publish_failures bus_incomplete_messages
STATUS_TRAVERSE maps_malformed maps_duplicate update_errors bus_decode_failures bus_handler_errors bus_publish_failures bus_incomplete_messages"

# log_seq_contiguous LOG [LABEL]: a check per channel of the log: seq runs 0, 1, 2, ...
# without a gap or a step back, i.e. every message its publisher sent since it started is in
# the log. LABEL prefixes the check names.
log_seq_contiguous() {
    local log=$1 label=${2:+$2 } line ch count gaps back first
    while read -r line; do
        read -r ch count gaps back < <(jq -r '[.channel, .count, .seq_gaps, .seq_backwards] | join(" ")' <<<"$line")
        [ "$ch" = LCM_SELF_TEST ] && continue
        first=$("$STACK_BIN/ugv-dump" --log "$log" --channel "$ch" --count 1 | jq -r '.fields.seq // "?"')
        verdict "${label}seq $ch" "$([ "$gaps" = 0 ] && [ "$back" = 0 ] && [ "$first" = 0 ]; echo $?)" \
            "$count msgs, first seq $first, $gaps missing, $back steps back"
    done < <("$STACK_BIN/ugv-logstat" "$log" --json)
}

# log_has_published LOG: a check per daemon output: the daemon's last status (STOPPING, sent
# after its last message) counts N published; the log holds at least N on that channel.
log_has_published() {
    local log=$1 st counter ch json n count state
    while read -r st counter ch; do
        json=$(stack_status_json "$st" "$log")
        n=$(stack_counter_in "$json" "$counter")
        state=$(jq -r '.fields.state // "?"' <<<"$json")
        count=$("$STACK_BIN/ugv-logstat" "$log" --channel "$ch" --json | jq -r '.count // 0')
        verdict "published $ch" "$([ -n "$n" ] && [ "$n" -gt 0 ] && [ "$count" -ge "$n" ] && [ "$state" = 4 ]; echo $?)" \
            "$st $counter = ${n:-missing} in its last status (state $state), $count in the log"
    done <<<"$BENCH_PUBLISHED"
}

# log_no_drops LOG: a check per daemon: its drop counters (BENCH_DROPS) are 0 in its last status.
log_no_drops() {
    local st counters
    while read -r st counters; do
        # shellcheck disable=SC2086  # a list of counter names
        counters_zero "drops $st" "$st" "$1" $counters
    done <<<"$BENCH_DROPS"
}

# stop_clean: stops the stack; a check that every process exited 0 on SIGTERM, none killed.
stop_clean() {
    stack_stop
    local bad what="every process exited 0 on SIGTERM"
    bad=$(stack_unclean)
    [ -n "$bad" ] && what="exit status not 0: $bad"
    [ ${#STACK_KILLED[@]} -gt 0 ] && what+="; killed after ${STACK_STOP_WAIT_S} s: ${STACK_KILLED[*]}"
    verdict clean-stop "$([ -z "$bad" ] && [ ${#STACK_KILLED[@]} -eq 0 ]; echo $?)" "$what"
}

# bench_toml_vec FILE KEY: the three numbers of FILE's `KEY = [a, b, c]` line, as "a b c".
bench_toml_vec() { awk -F'[][,= ]+' -v k="$2" '$1 == k { print $2, $3, $4 }' "$1"; }

bench_end() {
    echo "$BENCH_PASSED passed, $BENCH_FAILED failed"
    [ "$BENCH_FAILED" -eq 0 ]
}
