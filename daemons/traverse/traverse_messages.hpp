// terrain_map_t -> the analysis' TerrainGrid; its result -> traversability_map_t and
// candidate_arcs_t.
#pragma once

#include <cstdint>

#include <ugv/candidate_arcs_t.hpp>
#include <ugv/terrain_map_t.hpp>
#include <ugv/traversability_map_t.hpp>

#include "ugv/traverse/traversability.hpp"

namespace ugv::traverse_daemon {

// Copies the map as it is (grid reuses its buffers); the analysis checks it (check_grid), so
// a map whose sizes disagree is counted there, not here.
void to_grid(const terrain_map_t& msg, traverse::TerrainGrid& grid);
// The layers on the map's grid; utime, pose and geometry copied from map, map_seq = map.seq.
void to_message(const traverse::TraversabilityLayers& layers, const terrain_map_t& map, int64_t seq,
                traversability_map_t& out);
// The arcs' verdicts, with the set's length and swept width.
void to_message(const traverse::TraverseResult& result, const traverse::TraverseConfig& config,
                const terrain_map_t& map, int64_t seq, candidate_arcs_t& out);

}  // namespace ugv::traverse_daemon
