// A terrain map as a plan view like the report's figure 16: forward is up, left is left,
// elevation from green (low) through yellow to red (high), unknown cells white, the
// vehicle's outline in black, its reference point in blue, and a metre scale. The height
// shown is the cells' mean, or their highest or lowest sample (RenderOptions::layer).
// Optionally the standard deviation as a second panel (light to dark blue).
#pragma once

#include <cmath>
#include <limits>

#include <ugv/terrain_map_t.hpp>

#include "image.hpp"

namespace ugv::render {

// Which height a cell is coloured by: its mean, or its highest or lowest sample.
enum class Layer { mean, max, min };

struct RenderOptions
{
    int cell_px = 3;
    Layer layer = Layer::mean;
    bool variance_panel = false;
    double z_min_m = std::numeric_limits<double>::quiet_NaN();  // NaN: from the data
    double z_max_m = std::numeric_limits<double>::quiet_NaN();
    // > 0: a scale this tall that does not depend on what is in view, so that flat ground
    // has one colour in every picture: from a quarter of it below the ground under the
    // vehicle (the map pose's height: the body origin is on the ground) to three quarters
    // above, leaving room for ditches. Overrides z_min_m/z_max_m.
    double z_span_m = std::numeric_limits<double>::quiet_NaN();
    double vehicle_rear_x_m = -0.5;   // body frame outline of the vehicle
    double vehicle_front_x_m = 2.0;
    double vehicle_width_m = 1.6;
};

// t in [0, 1] -> green, yellow, red (never white: white is unknown).
Rgb elevation_colour(double t);
Rgb deviation_colour(double t);
inline constexpr Rgb kUnknown{255, 255, 255};
inline constexpr Rgb kVehicle{0, 0, 0};
inline constexpr Rgb kReference{0, 60, 255};

// The panel's top-left pixel of cell (i, j) (i forward, j left) at margin (x0, y0).
void cell_pixel(const terrain_map_t& m, int cell_px, int i, int j, int& x, int& y);

Image render_map(const terrain_map_t& m, const RenderOptions& options);

}  // namespace ugv::render
