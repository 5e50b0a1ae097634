// The classifier's hottest loops, each in two versions chosen at run time: 8 lanes (AVX2,
// when the CPU has it and allow_avx2 has not turned it off) and 4 lanes (SSE2, the x86-64
// baseline). Both give the same values to the bit: the same IEEE operations in the same
// order per value, no fused multiply-add (the AVX2 versions do not enable FMA).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "ugv/traverse/cell_classifier.hpp"

namespace ugv::traverse::kernels {

// The widest version's floats per vector: the slope's per-cell rows and a local ground
// window's rows of points are padded to whole vectors of it, so that either version covers
// them without a remainder loop.
constexpr std::size_t kPadLanes = 8;

// Whether the AVX2 versions run (the CPU has AVX2 and POPCNT, and allow_avx2 allows them).
bool use_avx2();

// How many of v[0, n) are below t (NaN is not).
std::size_t count_below(const float* v, std::size_t n, float t);

// The values of v[0, n) in [lo, hi), in v's order, into buf (which holds n floats);
// returns how many.
std::size_t gather_in(const float* v, std::size_t n, float lo, float hi, float* buf);

// The slope's inputs for a row of n cells: a cell counts when known and traversable; lw :=
// 1 where it counts, else 0; lz := mean - z0 where it counts, else 0; lo := 1 where known
// and not counting (an obstacle), else 0.
void slope_row_inputs(std::size_t n, const uint8_t* known, const CellClass* cell_class, const float* mean, float z0,
                      float* lw, float* lz, float* lo);

// The slope's row pass for one row: over the 2 hp + 1 column offsets d, in order, the sums
// of the weights w, w d, w d^2, the heights w z, w z d and the obstacle flags o, a vector
// of cells at a time in registers. lw, lz, lo: the row padded with hp zeros on each side and
// to wv (a multiple of kPadLanes). Each sum starts at +0 and adds the taps in the order of
// d, as a plain loop would (a padded tap adds +-0, which changes no sum: none is ever -0).
void slope_row_sums(const float* lw, const float* lz, const float* lo, int hp, std::size_t wv, float* rw, float* rwq,
                    float* rwqq, float* rwz, float* rwzq, float* ro);

// The slope's column pass for one row of windows (the cells [j_from, j_to), multiples of
// kPadLanes): the row sums of the window's rows (rows[r] points at row r's six sums, wv
// apart; fds[r] its offset), added in order of the rows into the plane's ten moments (wv
// apart in m), a vector of cells at a time in registers.
void slope_column_sums(const float* const* rows, const float* fds, int nrows, std::size_t wv, std::size_t j_from,
                       std::size_t j_to, float* m);

// The slope's tangent for the cells [jlo, jhi) of a row of windows: m holds the windows'
// ten moments (s0, sp, spp, sq, sqq, spq, sz, szp, szq, so), w4 apart; the plane's gradient
// from the centred moments (in double) and the tangent of its steepest angle over
// resolution_m, NaN with fewer than min_cells cells or cells (nearly) on a line.
void slope_tangents(const float* m, std::size_t w4, int jlo, int jhi, double min_cells, double resolution_m,
                    float* tangent);

// Step 1's supported extremes for the cells [0, n): where measured[k], top and bottom :=
// the max (min) when min_support samples stand near it (n var / d^2, d its distance from the
// mean, in double; the extreme itself within 1e-4 of the mean), else the mean; roughness :=
// sqrt(variance) and span := max - min (a variance that is not finite counts as 0); NaN
// where not measured.
void supported_extremes(std::size_t n, const float* mean, const float* highest, const float* lowest,
                        const float* variance, const int32_t* count, const uint8_t* measured, double min_support,
                        float* top, float* bottom, float* roughness, float* span);

// The local ground's column sums: for q in [0, n), c1[q] += known[q], cp[q] += dp known[q],
// cpp[q] += dp dp known[q] (known: 1 or 0).
void add_row_moments(std::size_t n, const float* known, float dp, float* c1, float* cp, float* cpp);

// Step 1's certainty: for a cell seen (a count above 0, a finite mean, not only other
// cells' spread shares: count >= 2 with max = min = mean), certainty := of(age) where age
// is finite (age may be null: none), else 1, and measured := certainty > 0; the certainty
// of a cell not seen is left as it is, measured := 0. of is called once per run of cells of
// one age (cells fused from one cloud share it).
using CertaintyOf = std::function<double(float age)>;
void certainties(std::size_t n, const int32_t* count, const float* mean, const float* highest, const float* lowest,
                 const float* age, const CertaintyOf& of, float* certainty, uint8_t* measured);

// A local ground window's points: nr rows, row r of them at first_row + r row_stride (its
// row offset p0 + 2 r), rs lanes each (a multiple of kPadLanes; lane_known[t] is -1 for
// a lane that holds a column, else 0). v := the points less zref, rs apart, NaN where
// unknown or past the row's columns; per lane t, sum_z[t] and sum_pz[t] := the sums over
// the rows of the known heights and of the heights times p (in double). Returns the largest
// |height|.
float window_points(const float* first_row, std::size_t row_stride, int nr, int p0, std::size_t rs,
                    const int32_t* lane_known, float zref, float* v, double* sum_z, double* sum_pz);

// A window's points v (as window_points left them, fq[t] lane t's column offset) levelled
// along the plane z = a + gp p + gq q: lev := v + (zref - (gp p + gq q)) (NaN stays NaN);
// below := how many of lev are below level; per kPadLanes points, flags (bit t for point
// t) := |v - (a + gp p + gq q)| is above band or within tol of it. Returns the flags' OR.
struct WindowPlane
{
    float a, gp, gq, zref, level, band, tol;
};
unsigned level_window(const float* v, int nr, int p0, std::size_t rs, const float* fq, const WindowPlane& plane,
                      float* lev, uint8_t* flags, std::size_t& below);

// Step 2's steps and drops: step := max(0, top - lowest), drop := max(0, highest - bottom)
// where top is not NaN (a known cell), else NaN.
void steps_and_drops(std::size_t n, const float* top, const float* bottom, const float* lowest, const float* highest,
                     float* step, float* drop);

// Step 3's levels: known := whether top is not NaN; level := the mean, but the bottom under
// a mean raised (mean = highest > lowest), the top over a mean lowered (mean = lowest <
// highest), for a known cell; an unknown cell keeps its mean.
void cell_levels(std::size_t n, const float* top, const float* bottom, const float* mean, const float* highest,
                 const float* lowest, uint8_t* known, float* level);

// Step 4's height flags: high_bit where top - ground >= max_step, low_bit where ground -
// bottom >= max_drop (false where any is NaN); where top - bottom >= max_step (a face
// within the cell), also the bit of the farther extreme's side if the mean lies face_step
// or more from the ground on that side; face := 1 where step >= max_step and not
// mean - lowest_level < face_step (the vertical faces' candidates), else 0.
struct HeightLimits
{
    float max_step, max_drop, face_step;
    uint8_t high_bit, low_bit;
};
void height_flags(std::size_t n, const float* top, const float* bottom, const float* ground, const float* step,
                  const float* mean, const float* lowest_level, const HeightLimits& limits, uint8_t* edge,
                  uint8_t* face);

// Step 5 for the cells [0, n): a traversable cell without near_bit in flags[k] whose slope is
// above max_slope_deg becomes an obstacle; a known cell's cost is 1 unless traversable,
// else min(1, the largest of step/max_step, drop/max_drop, roughness/max_roughness and
// slope/max_slope) in double (a NaN slope left out); NaN where unknown.
struct CostLimits
{
    double max_step_m, max_drop_m, max_roughness_m, max_slope_deg;
};
void slope_class_and_cost(std::size_t n, const float* step, const float* drop, const float* roughness,
                          const float* slope_deg, const uint8_t* flags, uint8_t near_bit, const CostLimits& limits,
                          CellClass* cell_class, float* cost);

}  // namespace ugv::traverse::kernels
