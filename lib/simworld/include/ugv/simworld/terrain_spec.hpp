// The scenario's terrain as primitives, and its rasterisation into the truth height field.
// Heights are relative to ground_z_m (world ENU up); x/y in the world frame, m.
#pragma once

#include <cstdint>
#include <vector>

#include "ugv/simworld/height_field.hpp"

namespace ugv::simworld {

struct Rect
{
    double x0_m, y0_m, x1_m, y1_m;  // corners, x0 < x1, y0 < y1
    bool contains(double x, double y) const { return x >= x0_m && x < x1_m && y >= y0_m && y < y1_m; }
};

struct BoxSpec  // a flat-topped obstacle, height_m above the ground
{
    Rect area;
    double height_m;
};

struct WallSpec  // a straight wall between two points
{
    double x0_m, y0_m, x1_m, y1_m;
    double thickness_m;
    double height_m;
};

enum class Direction { east, west, north, south };

struct RampSpec  // rises linearly from the ground at one edge to rise_m at the opposite edge
{
    Rect area;
    double rise_m;
    Direction rises_towards;
};

struct DitchSpec  // a flat-bottomed cut depth_m below the ground
{
    Rect area;
    double depth_m;
};

struct TerrainSpec
{
    double ground_z_m = 0.0;
    double roughness_m = 0.0;             // amplitude of smooth seeded bumps (0 = none)
    double roughness_wavelength_m = 2.0;  // their spacing
    uint32_t seed = 1;
    std::vector<BoxSpec> boxes;
    std::vector<WallSpec> walls;
    std::vector<RampSpec> ramps;
    std::vector<DitchSpec> ditches;
};

// The field covering area at resolution_m; a column's height is the terrain at its centre.
HeightField rasterize(const TerrainSpec& spec, const Rect& area, double resolution_m);

// The smooth seeded roughness alone at (x, y): value noise on a lattice of the wavelength,
// bilinear with smoothstep, in [-roughness_m, roughness_m].
double roughness_at(const TerrainSpec& spec, double x_m, double y_m);

}  // namespace ugv::simworld
