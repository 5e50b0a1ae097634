#!/usr/bin/env bash
# Bench: the LMS's interlaced beam timing on the demo scenario (docs/lms.md, "Beam timing").
# Four runs of the whole stack on `ugv-sim world`: the emulator's beams measured linearly or
# in interlaced sweeps (--lms-timing), ugv-lms modelling them linearly or interlaced
# (beam_timing). For each run: the last map against the truth (`ugv-eval compare
# --exclude-edges 0.3`, then every cell) and the neighbour zig-zag of the points as
# published (`ugv-eval interlace`), plus the order that zig-zag says fits.
#   tests/bench/lms-interlace.sh [--out DIR] [--seconds S] [--order O] [--score DIR]
# --order O     the emulator's (device's) sweep order at 0.5 deg: 01 (default) or 10; ugv-lms
#               is configured with the same order.
# --score DIR   only score the four logs kept in DIR by an earlier --out DIR.
# Checks:
#   run E/D         the scenario ran to its end and every process exited 0 on SIGTERM;
#   interlaced      with both interlaced, the map's RMSE is at most linear/linear's + 2 mm;
#   wrong-model     linear ugv-lms against the interlacing emulator: a larger zig-zag and RMSE
#                   than interlaced/interlaced;
#   detector        on the interlacing emulator's logs, `ugv-eval interlace` names the order.
source "$(dirname "$0")/bench.sh"
seconds=
order=01
score_only=
while [ $# -gt 0 ]; do
    case $1 in
        --out) shift; export UGV_BENCH_OUT=$1 ;;
        --seconds) shift; seconds=$1 ;;
        --order) shift; order=$1 ;;
        --score) shift; score_only=$(realpath "$1") || exit 2 ;;
        --keep) export UGV_BENCH_KEEP=1 ;;
        -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
        *) echo "lms-interlace.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
    esac
    shift
done
case $order in 01|10) ;; *) echo "lms-interlace.sh: --order: 01 or 10" >&2; exit 2 ;; esac
[ -n "$score_only" ] && export UGV_BENCH_OUT=$score_only
stack_has_world || { echo "lms-interlace.sh: $STACK_BIN/ugv-sim has no world simulator" >&2; exit 2; }

bench_begin lms-interlace 7860
top=$BENCH_WORK
url=$STACK_URL
runs=("linear linear" "linear interlaced" "interlaced linear" "interlaced interlaced")

one_run() {  # one_run EMULATOR DRIVER
    local emu=$1 drv=$2 dir=$top/emu-$1-drv-$2 world
    stack_init "$dir" "$url"
    world=(--lms-timing "$emu" --lms-sweep-order "$order")
    [ -n "$seconds" ] && world+=(--duration "$seconds")
    # As tools/demo: the scenario's terrain reaches past the 8 m of millimetre units.
    stack_set lms 'units = "cm"'
    stack_set lms "beam_timing = \"$drv\""
    stack_set lms "sweep_order = \"$order\""
    stack_set terrain 'publish_hz = 2.0'
    stack_start_logger
    if ! stack_start_devices "${world[@]}"; then verdict "run $emu/$drv" 1 "the simulator did not come up"; return; fi
    stack_start_daemons
    echo "# emulator $emu, ugv-lms $drv: running the demo scenario"
    while stack_alive sim-world; do sleep 0.5; done
    stack_stop
    local unclean sim_rc=${STACK_EXIT[sim-world]:-1}
    unclean=$(stack_unclean)
    verdict "run $emu/$drv" "$([ "$sim_rc" -eq 0 ] && [ -z "$unclean" ] && [ ${#STACK_KILLED[@]} -eq 0 ]; echo $?)" \
        "sim exit $sim_rc; ${unclean:-every process exited 0}${STACK_KILLED[*]:+; killed: ${STACK_KILLED[*]}}"
}

if [ -z "$score_only" ]; then
    for r in "${runs[@]}"; do one_run $r; done
fi

declare -A rmse rmse_all zig fit
printf '\n| emulator | ugv-lms | map RMSE (m), edges out | map RMSE (m), all cells | zig-zag RMS (m) | order that fits |\n'
printf '|---|---|---|---|---|---|\n'
for r in "${runs[@]}"; do
    read -r emu drv <<<"$r"
    dir=$top/emu-$emu-drv-$drv
    log=$dir/ugv.lcm
    [ -f "$log" ] || { verdict "score $emu/$drv" 1 "no log $log"; continue; }
    rmse[$r]=$("$STACK_BIN/ugv-eval" compare "$log" --truth "$dir/run/truth.hf" --exclude-edges 0.3 2>/dev/null | jq -r .rmse_m)
    rmse_all[$r]=$("$STACK_BIN/ugv-eval" compare "$log" --truth "$dir/run/truth.hf" 2>/dev/null | jq -r .rmse_m)
    "$STACK_BIN/ugv-eval" interlace "$log" --json >"$dir/interlace.json" 2>"$dir/stderr/ugv-eval-interlace.log"
    zig[$r]=$(jq -r 'select(.candidate == "as published") | .zigzag_rms_m' "$dir/interlace.json")
    fit[$r]=$(jq -r 'select(.summary) | .fits' "$dir/interlace.json")
    printf '| %s | %s | %.4f | %.4f | %.4f | %s |\n' "$emu" "$drv" "${rmse[$r]:-NaN}" "${rmse_all[$r]:-NaN}" "${zig[$r]:-NaN}" "${fit[$r]:-?}"
done
echo
ll="linear linear" li="interlaced linear" ii="interlaced interlaced"
if [ -n "${rmse[$ii]:-}" ] && [ -n "${rmse[$ll]:-}" ] && [ -n "${rmse[$li]:-}" ]; then
    verdict interlaced "$(awk -v a="${rmse[$ii]}" -v b="${rmse[$ll]}" 'BEGIN { exit !(a <= b + 0.002) }'; echo $?)" \
        "interlaced/interlaced RMSE ${rmse[$ii]} m, linear/linear ${rmse[$ll]} m"
    verdict wrong-model "$(awk -v zw="${zig[$li]}" -v zr="${zig[$ii]}" -v rw="${rmse[$li]}" -v rr="${rmse[$ii]}" \
        'BEGIN { exit !(zw > zr && rw > rr) }'; echo $?)" \
        "linear ugv-lms on the interlacing emulator: zig-zag ${zig[$li]} m (right model ${zig[$ii]}), RMSE ${rmse[$li]} m (${rmse[$ii]})"
    verdict detector "$([ "${fit[$ii]}" = "$order" ] && [ "${fit[$li]}" = "$order" ]; echo $?)" \
        "the order that fits: ${fit[$ii]} and ${fit[$li]} (the emulator's: $order)"
fi
bench_end
