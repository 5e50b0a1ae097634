// ugv-terrain's configuration keys (docs/terrain.md lists each with its range).
#pragma once

#include <cstdint>
#include <string>

#include "ugv/runtime/config.hpp"
#include "ugv/runtime/stamp_gate.hpp"
#include "ugv/terrain/map_config.hpp"

namespace ugv::terrain_daemon {

struct TerrainConfig
{
    std::string points_channel = "POINTS.*";  // regex: every nodscan instance
    std::string pose_channel = "POSE";
    std::string map_channel = "TERRAIN_MAP";
    double publish_hz = 2.0;                   // on message time
    int64_t max_point_wait_us = 500'000;         // how long a cloud waits for a pose after it
    int64_t health_timeout_us = 2'000'000;
    // Restarts: where the map is kept ("" = not kept) and how often it is saved (wall time).
    std::string map_file;
    int64_t map_save_period_us = 10'000'000;
    // Inputs stamped further ahead of the bus clock are refused; older than the pose history
    // behind it, too (runtime/stamp_gate.hpp).
    int64_t max_stamp_ahead_us = 2'000'000;
    runtime::StampSkewLimits stamp_skew;  // max_stamp_skew_s, max_stamp_lag_s: the clock-disagreement flag
    terrain::MapConfig map;
};

// Reads every key (throws runtime::ConfigError, naming the key, for a bad value).
TerrainConfig read_config(runtime::Config& cfg);

}  // namespace ugv::terrain_daemon
