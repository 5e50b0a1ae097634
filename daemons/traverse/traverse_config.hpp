// ugv-traverse's configuration keys (docs/traverse.md, "The daemon", lists each with its
// default and range).
#pragma once

#include <cstdint>
#include <string>

#include "ugv/runtime/config.hpp"
#include "ugv/runtime/stamp_gate.hpp"
#include "ugv/traverse/traversability.hpp"

namespace ugv::traverse_daemon {

struct TraverseConfig
{
    std::string map_channel = "TERRAIN_MAP";  // regex
    std::string traversability_channel = "TRAVERSABILITY_MAP";
    std::string arcs_channel = "ARCS";
    // ARCS may pause this long (maps come at 2 Hz) before the daemon is not RUNNING.
    int64_t health_timeout_us = 2'000'000;
    // Maps stamped beyond these from the bus clock are refused (runtime/stamp_gate.hpp); a
    // map older than [classifier] max_age_s would be all UNKNOWN.
    int64_t max_stamp_ahead_us = 2'000'000;
    runtime::StampSkewLimits stamp_skew;  // max_stamp_skew_s, max_stamp_lag_s: the clock-disagreement flag
    int64_t max_stamp_age_us = 60'000'000;
    traverse::TraverseConfig analysis;
};

// Reads every key (throws runtime::ConfigError, naming the key, for a bad value).
TraverseConfig read_config(runtime::Config& cfg);

}  // namespace ugv::traverse_daemon
