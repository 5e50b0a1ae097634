// ugv-foxglove: the LCM channels, live, as the Foxglove WebSocket protocol (foxglove.websocket.v1):
// the same topics, schemas and JSON messages as ugv-mcap's files (docs/foxglove.md).
#include "foxglove_config.hpp"
#include "foxglove_node.hpp"

int main(int argc, char** argv)
{
    // Batched by 5 ms: it bridges every channel, and a wake-up per datagram was a third of
    // its CPU; 5 ms more is well within the 20 ms goal from LCM to a client's socket.
    ugv::daemon::Daemon d({.name = "ugv-foxglove", .status_channel = "STATUS_FOXGLOVE", .bus_batch_ms = 5}, argc, argv);
    const ugv::foxglove_daemon::FoxgloveConfig config = ugv::foxglove_daemon::read_config(d.config());
    d.start();
    return ugv::foxglove_daemon::run(d, config);
}
