// The two kinds of picture ugv-render draws from a log: each reads the log, decodes the
// messages the checked way (a message that is not one is counted and skipped), draws the
// last map or every Nth and writes the PNG files. Exit statuses for main: 0 done, 1 nothing
// to draw or a file not written, 2 not an LCM log.
#pragma once

#include <string>

#include "map_render.hpp"
#include "traverse_render.hpp"

namespace ugv::render {

struct LogJob
{
    std::string log_path;
    std::string out_path;  // the PNG; with every > 0 a prefix: PREFIX-00001.png ...
    std::string channel;   // of the maps
    int every = 0;         // 0: only the last map
};

// terrain_map_t plan views (map_render).
int render_heights_log(const LogJob& job, const RenderOptions& options);

// traversability_map_t with the candidate_arcs_t of the same terrain map (traverse_render);
// require_arcs: exit 1 when a map drawn had no arcs in the log.
int render_traverse_log(const LogJob& job, const std::string& arcs_channel, bool require_arcs,
                        const TraverseOptions& options);

}  // namespace ugv::render
