// ugv-foxglove's configuration keys (docs/foxglove.md, "The live bridge", lists each with its
// default and range).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "ugv/runtime/config.hpp"

namespace ugv::foxglove_daemon {

struct FoxgloveConfig
{
    std::string channels = ".*";  // regex of the LCM channels bridged
    std::string no_raw;           // regex: channels whose own JSON topic is left out (as ugv-mcap --no-raw)
    std::string address = "127.0.0.1";
    int port = 8765;
    int max_clients = 4;
    // Per client: bytes of messages waiting to be written beyond which new ones are dropped.
    std::size_t client_queue_bytes = 4u << 20;
    // The daemon's own status (the template's key, read here too): looped back by the bus,
    // it is bridged but does not count as input flowing.
    std::string status_channel = "STATUS_FOXGLOVE";
    // LCM input may pause this long before the daemon is not RUNNING.
    int64_t health_timeout_us = 5'000'000;
};

// Reads every key (throws runtime::ConfigError, naming the key, for a bad value).
FoxgloveConfig read_config(runtime::Config& cfg);

}  // namespace ugv::foxglove_daemon
