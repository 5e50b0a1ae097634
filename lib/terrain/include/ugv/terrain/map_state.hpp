// A terrain map's content and where it lies, as bytes: what ugv-terrain keeps across a
// restart (docs/terrain.md, "Restarts"). The codec sees bytes only; the daemon reads and
// writes the file. Egocentric mode only: the world-aligned mode is for comparison.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ugv/terrain/cell_sums.hpp"
#include "ugv/terrain/cell_tally.hpp"
#include "ugv/terrain/map_config.hpp"

namespace ugv::terrain {

struct SavedCell
{
    uint32_t index = 0;  // unwrapped: i * ny + j
    CellSums sums;
    CellTally tally;
};

struct MapState
{
    // The layout the cells belong to: a map of another layout is not restored.
    int nx = 0, ny = 0;
    double grid_size_m = 0.0;
    StatisticsKind statistics = StatisticsKind::variance_weighted;
    double reference_x_m = 0.0, reference_y_m = 0.0;
    // ENU of the local frame's origin (row 0's reference point) and the yaw of its X axis.
    double anchor_x_m = 0.0, anchor_y_m = 0.0, anchor_yaw_rad = 0.0;
    int64_t utime_us = 0;  // the newest pose when it was taken
    int64_t epoch_us = 0;  // the cells' times (CellTally::newest_ms) count from here
    std::vector<SavedCell> cells;  // the known cells, in increasing index
};

// Little-endian, with a magic, a version and a 64-bit checksum of everything before it.
std::vector<uint8_t> encode_map_state(const MapState& state);
// The state, or nullopt with why set: wrong magic or version, truncated or longer, checksum,
// a cell index out of the layout or out of order, a non-finite or empty cell, a cell without
// a time.
std::optional<MapState> decode_map_state(const uint8_t* data, std::size_t size, std::string& why);
// The largest encoding of a map of nx x ny cells (a reader refuses a larger file unread).
std::size_t max_encoded_size(int nx, int ny);

}  // namespace ugv::terrain
