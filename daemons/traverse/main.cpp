// ugv-traverse: TERRAIN_MAP -> TRAVERSABILITY_MAP + ARCS (the report's figure 20: every cell
// traversable, obstacle, negative obstacle or unknown, and the candidate arcs judged on it).
// One analysis per map, driven by the maps only, so --replay LOG --out LOG is deterministic.
#include "traverse_config.hpp"
#include "traverse_node.hpp"

int main(int argc, char** argv)
{
    // Not batched: a planner waits for ARCS, and the goal for the latency added to each map
    // is 20 ms (docs/traverse.md); a batch adds up to its period. The price: a wake-up per
    // datagram on the group.
    ugv::daemon::Daemon d({.name = "ugv-traverse", .status_channel = "STATUS_TRAVERSE", .processing = true,
                           .bus_batch_ms = 0},
                          argc, argv);
    const ugv::traverse_daemon::TraverseConfig config = ugv::traverse_daemon::read_config(d.config());
    d.start();
    return ugv::traverse_daemon::run(d, config);
}
