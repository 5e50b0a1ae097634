#!/usr/bin/env bash
# Bench: the whole stack on a simulated world, the traversability maps scored against the
# world's truth (docs/traverse.md section 4).
#   tests/bench/traverse-score.sh [WORLD.toml] [--out DIR] [--seconds S] [--keep]
# WORLD: an `ugv-sim world` scenario (default: the built-in one; e.g.
# tools/sim/scenarios/obstacle_course.toml). Starts lcm-logger (every channel), ugv-sim world
# and every daemon of tools/lib/stack.sh's STACK_DAEMONS (ugv-traverse among them when it is
# there), runs the whole scenario (or --seconds S), stops everything, then scores the log with
# `ugv-eval traverse LOG --truth run/truth.hf --all` and prints its summary line. --out DIR
# keeps everything in DIR (ugv.lcm, run/truth.hf, config/, stderr/, traverse-score.jsonl).
# Checks:
#   running NAME   each daemon reports RUNNING within 30 s of its start;
#   scenario       the simulator ran to the end of the scenario (or of --seconds);
#   maps           the log holds TERRAIN_MAP (and TRAVERSABILITY_MAP when ugv-traverse ran);
#   recall, false-obstacles, arcs   (when the log holds traversability maps) the issue-24
#                  goals over all maps: recall >= 0.98 of the truth obstacle cells within
#                  15 m ahead that the laser has seen, false obstacles <= 1 % of the known
#                  traversable cells, arc blocked/free agreement >= 0.95;
#   clean-stop     every process exits 0 on SIGTERM.
source "$(dirname "$0")/bench.sh"
scenario=
seconds=
while [ $# -gt 0 ]; do
    case $1 in
        --out) shift; export UGV_BENCH_OUT=$1 ;;
        --seconds) shift; seconds=$1 ;;
        --keep) export UGV_BENCH_KEEP=1 ;;
        -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
        -*) echo "traverse-score.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
        *) scenario=$(realpath "$1") || exit 2 ;;
    esac
    shift
done
[ -z "$scenario" ] || [ -f "$scenario" ] || { echo "traverse-score.sh: no scenario $scenario" >&2; exit 2; }
stack_has_world || { echo "traverse-score.sh: $STACK_BIN/ugv-sim has no world simulator" >&2; exit 2; }

bench_begin traverse-score 7795
world=()
[ -n "$scenario" ] && world+=(--scenario "$scenario")
[ -n "$seconds" ] && world+=(--duration "$seconds")
# As tools/demo: the scenario's terrain reaches past the 8 m of millimetre units.
stack_set lms 'units = "cm"'
stack_start_logger
if ! stack_start_devices "${world[@]}"; then verdict devices 1 "the simulator did not come up"; bench_end; exit; fi
stack_start_daemons
for d in "${STACK_DAEMONS[@]}"; do running "running ugv-$d" "$(stack_status_channel "$d")" 30; done
echo "# running the scenario ($([ -n "$scenario" ] && basename "$scenario" || echo default))"
while stack_alive sim-world; do sleep 0.5; done
stack_stop
sim_rc=${STACK_EXIT[sim-world]:-1}
verdict scenario "$sim_rc" "ugv-sim world exit status $sim_rc ($(grep -m1 'scenario done' "$STACK_OUT/stderr/sim-world.log" 2>/dev/null))"
unclean=$(stack_unclean)
verdict clean-stop "$([ -z "$unclean" ] && [ ${#STACK_KILLED[@]} -eq 0 ]; echo $?)" \
    "${unclean:-every process exited 0}${STACK_KILLED[*]:+; killed: ${STACK_KILLED[*]}}"

log=$STACK_OUT/ugv.lcm
count() { "$STACK_BIN/ugv-logstat" "$log" 2>/dev/null | awk -v ch="$1" '$1 == ch { print $2; exit }'; }
terrain_maps=$(count TERRAIN_MAP)
trav_maps=$(count TRAVERSABILITY_MAP)
want_trav=0
[[ " ${STACK_DAEMONS[*]} " == *" traverse "* ]] && want_trav=1
verdict maps "$([ "${terrain_maps:-0}" -gt 0 ] && { [ $want_trav -eq 0 ] || [ "${trav_maps:-0}" -gt 0 ]; }; echo $?)" \
    "${terrain_maps:-0} TERRAIN_MAP, ${trav_maps:-0} TRAVERSABILITY_MAP in $log"
if [ "${trav_maps:-0}" -gt 0 ]; then
    "$STACK_BIN/ugv-eval" traverse "$log" --truth "$STACK_OUT/run/truth.hf" --all >"$STACK_OUT/traverse-score.jsonl" 2>"$STACK_OUT/stderr/ugv-eval.log"
    summary=$(grep '"summary"' "$STACK_OUT/traverse-score.jsonl" | tail -n 1)
    echo "# summary: $summary"
    read -r recall sampled_recall false_rate agreement sampled_agreement < <(jq -r '"\(.recall // -1) \(.sampled_recall // -1) \(.false_obstacle_rate // 2) \(.arc_agreement // -1) \(.arc_agreement_sampled // -1)"' <<<"$summary" 2>/dev/null || echo "-1 -1 2 -1 -1")
    verdict recall "$(awk -v v="$recall" 'BEGIN { exit !(v >= 0.98) }'; echo $?)" \
        "recall $recall (want >= 0.98; over the cells whose obstacle the laser sampled: $sampled_recall)"
    verdict false-obstacles "$(awk -v v="$false_rate" 'BEGIN { exit !(v >= 0 && v <= 0.01) }'; echo $?)" \
        "false-obstacle rate $false_rate (want <= 0.01)"
    verdict arcs "$(awk -v v="$agreement" 'BEGIN { exit !(v >= 0.95) }'; echo $?)" \
        "arc agreement $agreement (want >= 0.95; against the obstacles the laser sampled: $sampled_agreement)"
else
    echo "# no TRAVERSABILITY_MAP in the log (no ugv-traverse in the stack): nothing to score"
fi
bench_end
