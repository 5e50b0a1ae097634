// A traversability map with its candidate arcs as a plan view like the report's figure 20:
// forward up, left left; traversable cells pale to dark green by cost, obstacles black,
// negative obstacles purple, unknown grey; free arcs solid blue up to their length; blocked
// arcs dashed red up to their clear distance, then on along the vehicle's heading to its
// front bumper with a cross there (where the footprint meets the obstacle); the best arc
// thick magenta; the vehicle's outline; a legend beside the map.
#pragma once

#include <ugv/candidate_arcs_t.hpp>
#include <ugv/traversability_map_t.hpp>

#include "image.hpp"

namespace ugv::render {

struct TraverseOptions
{
    int cell_px = 3;
    double vehicle_rear_x_m = -0.5;  // body frame outline of the vehicle
    double vehicle_front_x_m = 2.0;  // also where a blocked arc's cross goes
    double vehicle_width_m = 1.6;
};

inline constexpr Rgb kTraversableEasy{215, 240, 205};  // cost 0
inline constexpr Rgb kTraversableHard{95, 150, 50};    // cost 1
inline constexpr Rgb kObstacle{25, 25, 25};
inline constexpr Rgb kNegativeObstacle{135, 50, 190};
inline constexpr Rgb kUnknownCell{185, 185, 185};
inline constexpr Rgb kFreeArc{0, 100, 255};
inline constexpr Rgb kBlockedArc{235, 40, 0};  // dashes, and the cross at the hit
inline constexpr Rgb kBestArc{255, 0, 200};
inline constexpr Rgb kOutline{0, 0, 0};
inline constexpr int kTraverseMargin = 10;
inline constexpr int kLegendWidth = 200;  // right of the map
inline constexpr int kLegendHeight = 300;

Rgb traversable_colour(double cost);  // cost in [0, 1]; NaN as 0
Rgb class_colour(int8_t cell_class, float cost);

// Whether the message can be drawn: sizes agree (ncells = nx * ny, every layer ncells long;
// narcs and every per-arc array), at most 2000 cells a side, a resolution of at least 1 mm,
// finite geometry, best in -1 .. narcs - 1, a positive length.
bool drawable(const traversability_map_t& m);
bool drawable(const candidate_arcs_t& a);
// Arcs belong to a map when both were computed from the same terrain map (map_seq, utime).
bool same_terrain_map(const traversability_map_t& m, const candidate_arcs_t& a);

// The top-left pixel of cell (i, j) (i forward, j left).
void traverse_cell_pixel(const traversability_map_t& m, int cell_px, int i, int j, int& x, int& y);
// The pixel of the point s metres along an arc of the given curvature (1/m, + left) from the
// body origin heading +X, in the map's axes (the body's turned by -residual_yaw).
void arc_pixel(const traversability_map_t& m, int cell_px, double curvature, double s_m, int& x, int& y);

// The picture; arcs are drawn only when they are of the same terrain map (else the legend
// says there are none for it). Width 2 * margin + ny * cell_px + legend width, height the
// larger of the map's and the legend's plus the margins; cell_px is lowered to keep the map
// within 8000 pixels a side.
Image render_traverse(const traversability_map_t& m, const candidate_arcs_t* arcs, const TraverseOptions& options);

}  // namespace ugv::render
