// ugv-terrain: POINTS.* + POSE -> TERRAIN_MAP (the report's variance-weighted, wrappable,
// rotating terrain map). Fuses at sensor rate, publishes at publish_hz of message time.
#include "terrain_config.hpp"
#include "terrain_node.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-terrain", .status_channel = "STATUS_TERRAIN", .processing = true,
                           .bus_batch_ms = 50},
                          argc, argv);
    const ugv::terrain_daemon::TerrainConfig config = ugv::terrain_daemon::read_config(d.config());
    d.start();
    return ugv::terrain_daemon::run(d, config);
}
