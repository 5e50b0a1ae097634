#include "ugv/traverse/cell_classifier.hpp"

#include "classifier_kernels.hpp"
#include "drop_across_unknown.hpp"
#include "local_ground.hpp"
#include "ugv/simd/float4.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace ugv::traverse {

namespace {

using namespace simd;
using F4 = Float4;
using I4 = Int4;
using kernels::count_below;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
// Bits of a cell's flags: its top max_step above the local ground (or a vertical face up
// from a neighbour), its bottom max_drop below it, an obstacle within the slope window (the
// plane there says nothing about the slope).
constexpr uint8_t kHigh = 1, kLow = 2, kObstacleNear = 4;
// How near (in cells) a cell of few samples needs an obstacle of its own kind to be one.
constexpr int kFewSupportCells = 2;
static_assert(kGroundStride == 3, "the lattice squares' flags are taken three cells at a time");

int half_width(double radius_m, double resolution_m) { return ground_half_width(radius_m, resolution_m); }

// The least float at or above x: for a float f, f >= float_at_least(x) iff double(f) >= x.
float float_at_least(double x)
{
    const float f = static_cast<float>(x);
    return static_cast<double>(f) < x ? std::nextafter(f, kInf) : f;
}

// What a stable sort of x[0, m) (m <= 12, no NaN) would put at r, or the first value (in
// x's order) equal to it (+0 and -0): the first x[a] with r in [less_a, less_a + equal_a)
// (the values there are all equal). Without a branch on the data (the sorts' data-dependent
// branches were most of the percentile's time): each x[b] compared with all, NaN in the
// unused lanes compares false.
float rank_of_few(const float* x, std::size_t m, std::size_t r)
{
    float pad[12];
    for (std::size_t e = 0; e < 12; ++e) pad[e] = e < m ? x[e] : kNaN;
    const F4 a[3] = {load4(pad), load4(pad + 4), load4(pad + 8)};
    I4 less[3] = {}, equal[3] = {};
    for (int b = 0; b < 12; ++b) {
        const F4 xb = {pad[b], pad[b], pad[b], pad[b]};
        for (int j = 0; j < 3; ++j) {
            less[j] -= xb < a[j];
            equal[j] -= xb == a[j];
        }
    }
    const int32_t ri = static_cast<int32_t>(r);
    const I4 r4 = {ri, ri, ri, ri};
    unsigned lanes = 0;  // bit a: x[a] is of rank r
    for (int j = 0; j < 3; ++j) lanes |= lane_bits((less[j] <= r4) & (r4 < less[j] + equal[j])) << (4 * j);
    return lanes != 0 ? pad[__builtin_ctz(lanes)] : 0.0f;  // never 0 lanes (r < m): kept as a guard
}

// The value of rank k (from 0) among the `finite` values of v[0, n) that are not NaN (NaN
// marks a hole): what std::nth_element would put at k were the holes left out. A bracket
// [lo, hi) that holds it (count_below(lo) <= k < count_below(hi)) is found from guess
// (below_guess = count_below(guess), which the caller counted) in steps that grow from
// `step`, then narrowed at the level the counts point to until it holds few values; those
// are gathered (kernels::gather_in) and the one of rank k among them picked by rank_of_few
// (the first of equal values in v's order, as a stable sort would). buf holds n values.
float select_rank(const float* v, std::size_t n, std::size_t finite, std::size_t k, float guess, std::size_t below_guess,
                  float step, float* __restrict buf)
{
    constexpr std::size_t kFew = 12;
    float lo = -kInf, hi = kInf;
    std::size_t below_lo = 0, below_hi = finite;
    float t = guess;
    for (int iter = 0; iter < 64 && below_hi - below_lo > kFew; ++iter) {
        const std::size_t c = iter == 0 ? below_guess : count_below(v, n, t);
        if (c <= k) {
            lo = t;
            below_lo = c;
        } else {
            hi = t;
            below_hi = c;
        }
        if (std::isfinite(lo) && std::isfinite(hi)) {
            // Where rank k + 1/2 would lie were the values in the bracket evenly spread,
            // kept off its ends so that each count narrows it.
            const float f = (static_cast<float>(k - below_lo) + 0.5f) / static_cast<float>(below_hi - below_lo);
            t = lo + std::clamp(f, 0.05f, 0.95f) * (hi - lo);
            if (!(t > lo && t < hi)) t = lo + 0.5f * (hi - lo);
            if (!(t > lo && t < hi)) break;  // no float between them: one value
        } else {
            t = std::isfinite(lo) ? lo + step : hi - step;
            step *= 2.0f;
        }
    }
    // The values in [lo, hi), in v's order; rank k - below_lo among them.
    const std::size_t m = kernels::gather_in(v, n, lo, hi, buf);
    const std::size_t r = k - below_lo;
    if (m != below_hi - below_lo || r >= m) {  // never seen (the counts say otherwise), kept as a guard
        std::vector<float> copy;
        for (std::size_t e = 0; e < n; ++e)
            if (!std::isnan(v[e])) copy.push_back(v[e]);
        std::nth_element(copy.begin(), copy.begin() + static_cast<std::ptrdiff_t>(k), copy.end());
        return copy[k];
    }
    if (m > 2 * kFew) {  // not narrowed (values with no float between them): a partial selection
        std::nth_element(buf, buf + r, buf + m);
        return buf[r];
    }
    if (m > kFew) {  // stable: equal values keep their order
        for (std::size_t a = 1; a < m; ++a) {
            const float x = buf[a];
            std::size_t b = a;
            for (; b > 0 && x < buf[b - 1]; --b) buf[b] = buf[b - 1];
            buf[b] = x;
        }
        std::size_t first = r;  // the first of a run of equal values (+0 and -0)
        while (first > 0 && buf[first - 1] == buf[r]) --first;
        return buf[first];
    }
    return rank_of_few(buf, m, r);
}

// out[k] = min (or max) of in(k) over the square window of half-width h around k; cells
// outside the grid are skipped (in gives no NaN, so the order of the picks does not
// matter). Separable: each row padded with h identities on each side (no edge cases) and
// its windows taken four cells at a time in registers, then the columns likewise.
template <bool kMin, class Value>
void window_extreme(Value in, int nx, int ny, int h, std::vector<float>& tmp, std::vector<float>& out)
{
    const float identity = kMin ? kInf : -kInf;
    const auto pick = [](F4 a, F4 b) {
#if defined(__SSE2__)
        return kMin ? (F4)_mm_min_ps((__m128)b, (__m128)a) : (F4)_mm_max_ps((__m128)b, (__m128)a);  // b < a ? b : a
#else
        return kMin ? (b < a ? b : a) : (b > a ? b : a);
#endif
    };
    const std::size_t w = static_cast<std::size_t>(ny), w4 = (w + 3) / 4 * 4, hh = static_cast<std::size_t>(h);
    // tmp: the padded row, then the rows' windows at a stride of whole vectors.
    const std::size_t pad_len = w4 + 2 * hh;
    tmp.resize(pad_len + static_cast<std::size_t>(nx) * w4);
    out.resize(static_cast<std::size_t>(nx) * w);
    float* __restrict pad = tmp.data();
    float* __restrict rows = tmp.data() + pad_len;
    std::fill(pad, pad + pad_len, identity);
    for (int i = 0; i < nx; ++i) {
        for (std::size_t j = 0; j < w; ++j) pad[hh + j] = in(i * w + j);
        float* r = rows + static_cast<std::size_t>(i) * w4;
        if (hh == 1) {  // the default: unrolled
            for (std::size_t j = 0; j < w4; j += 4)
                store4(r + j, pick(pick(load4(pad + j), load4(pad + j + 1)), load4(pad + j + 2)));
            continue;
        }
        for (std::size_t j = 0; j < w4; j += 4) {
            F4 acc = load4(pad + j);
            for (std::size_t d = 1; d <= 2 * hh; ++d) acc = pick(acc, load4(pad + j + d));
            store4(r + j, acc);
        }
    }
    for (int i = 0; i < nx; ++i) {
        const int plo = std::max(0, i - h), phi = std::min(nx - 1, i + h);
        float* o = &out[i * w];
        const float* first = rows + static_cast<std::size_t>(plo) * w4;
        for (std::size_t j = 0; j < w4; j += 4) {
            F4 acc = load4(first + j);
            if (phi - plo == 2)  // the default's inner rows: unrolled
                acc = pick(pick(acc, load4(first + w4 + j)), load4(first + 2 * w4 + j));
            else
                for (int p = plo + 1; p <= phi; ++p) acc = pick(acc, load4(rows + static_cast<std::size_t>(p) * w4 + j));
            if (j + 4 <= w)
                store4(o + j, acc);
            else
                for (std::size_t e = j; e < w; ++e) o[e] = acc[e - j];
        }
    }
}

}  // namespace

void TraversabilityLayers::reset(int nx_, int ny_)
{
    nx = nx_;
    ny = ny_;
    const std::size_t n = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
    cell_class.assign(n, CellClass::unknown);
    for (auto* v : {&cost, &step_m, &drop_m, &slope_deg, &roughness_m, &span_m, &ground_m}) v->assign(n, kNaN);
    certainty.assign(n, 0.0f);
}

CellClassifier::CellClassifier(const ClassifierConfig& c) : config_(c)
{
    auto positive = [](double v, const char* what) {
        if (!(std::isfinite(v) && v > 0)) throw std::invalid_argument(std::string(what) + " must be finite and positive");
    };
    positive(c.max_step_m, "max_step_m");
    positive(c.max_drop_m, "max_drop_m");
    positive(c.step_radius_m, "step_radius_m");
    positive(c.face_mean_step_m, "face_mean_step_m");
    positive(c.slope_radius_m, "slope_radius_m");
    positive(c.ground_radius_m, "ground_radius_m");
    positive(c.shadow_radius_m, "shadow_radius_m");
    positive(c.max_roughness_m, "max_roughness_m");
    positive(c.max_age_s, "max_age_s");
    positive(c.max_driven_m, "max_driven_m");
    if (!(c.max_slope_deg > 0 && c.max_slope_deg < 90)) throw std::invalid_argument("max_slope_deg must be in (0, 90)");
    if (!(c.min_support_samples >= 1 && c.min_support_samples <= 1000))
        throw std::invalid_argument("min_support_samples must be in [1, 1000]");
}

void CellClassifier::local_ground(const TerrainGrid& g, double radius_m, double max_step_m, std::vector<float>& ground)
{
    // local_ground_reference, lattice point by lattice point, is the specification. Here only
    // the lattice points some known cell reads are computed; the window's geometry (the
    // moments of its known cells' offsets) comes from sums along the columns of a lattice
    // row's window rows, then along the window's columns; the heights' moments from the
    // window's points in rows of vectors of 4, unknown points as NaN (the same floats as the
    // reference's, summed in double: integer offsets times floats, exact in any order); the
    // outlier test in float where its error cannot change the verdict, else in double as the
    // reference; the second plane's by subtracting the points off the first; the percentile
    // by counting.
    const int nx = g.nx, ny = g.ny, h = ground_half_width(radius_m, g.resolution_m);
    const int lx = (nx - 1) / kGroundStride + 1, ly = (ny - 1) / kGroundStride + 1;
    const std::size_t n = g.cells(), w = static_cast<std::size_t>(ny), half = (w + 1) / 2;
    const std::size_t lattice_points = static_cast<std::size_t>(lx) * static_cast<std::size_t>(ly);
    lattice_.assign(lattice_points, kNaN);
    lattice_slope_.assign(lattice_points, {0.0f, 0.0f});
    // The lattice squares that hold a known cell, and the lattice points they read (their
    // corners: a + 1 is clamped to the last lattice row, so a square's corners are a or a + 1).
    square_known_.assign(lattice_points, 0);
    for (int i = 0; i < nx; ++i) {
        uint8_t* sq = &square_known_[static_cast<std::size_t>(i / kGroundStride) * ly];
        const uint8_t* kr = &known_[i * w];
        std::size_t j = 0;
        for (; j + kGroundStride <= w; j += kGroundStride) sq[j / kGroundStride] |= kr[j] | kr[j + 1] | kr[j + 2];
        for (; j < w; ++j) sq[j / kGroundStride] |= kr[j];
    }
    needed_.assign(lattice_points, 0);
    for (int a = 0; a < lx; ++a)
        for (int b = 0; b < ly; ++b)
            if (square_known_[static_cast<std::size_t>(a) * ly + b])
                for (int da = 0; da < 2; ++da)
                    for (int db = 0; db < 2; ++db)
                        needed_[static_cast<std::size_t>(std::min(a + da, lx - 1)) * ly + std::min(b + db, ly - 1)] = 1;
    // Known cells as 1; the means split by column parity (NaN where unknown) so that a
    // window's every other column is contiguous.
    known_f_.resize(n);
    // + kPadLanes: a window row's last vector.
    parity_means_.resize(2 * static_cast<std::size_t>(nx) * half + kernels::kPadLanes);
    std::fill(parity_means_.end() - kernels::kPadLanes, parity_means_.end(), kNaN);
    for (std::size_t k = 0; k < n; ++k) known_f_[k] = ground_points_[k] ? 1.0f : 0.0f;
    for (int i = 0; i < nx; ++i) {
        float* even = &parity_means_[static_cast<std::size_t>(i) * half];
        float* odd = &parity_means_[(static_cast<std::size_t>(nx) + i) * half];
        const float* mr = &g.mean_z_m[i * w];
        const uint8_t* kr = &ground_points_[i * w];
        for (std::size_t e = 0; e < (w + 1) / 2; ++e) even[e] = kr[2 * e] ? mr[2 * e] : kNaN;
        for (std::size_t e = 0; e < w / 2; ++e) odd[e] = kr[2 * e + 1] ? mr[2 * e + 1] : kNaN;
        if (w & 1) odd[w / 2] = kNaN;
    }
    // A window's points: up to h + 1 rows of h + 1, each row padded to whole vectors.
    constexpr std::size_t kL = kernels::kPadLanes;
    const std::size_t max_rs = (static_cast<std::size_t>(h) + kL) / kL * kL;
    const std::size_t max_points = (static_cast<std::size_t>(h) + 1) * max_rs;
    win_v_.resize(max_points);
    win_lev_.resize(max_points);
    win_flags_.resize(max_points / kL);
    win_sel_.resize(max_points);
    win_q_.resize(max_rs);
    lane_known_.resize(max_rs);
    lane_z_.resize(max_rs);
    lane_pz_.resize(max_rs);
    column_sums_.resize(3 * w);
    float *c1 = &column_sums_[0], *cp = &column_sums_[w], *cpp = &column_sums_[2 * w];
    const double band = static_cast<float>(0.5 * max_step_m);
    for (int a = 0; a < lx; ++a) {
        const uint8_t* need = &needed_[static_cast<std::size_t>(a) * ly];
        if (std::find(need, need + ly, 1) == need + ly) continue;
        const int i = a * kGroundStride, plo = std::max(0, i - h), phi = std::min(nx - 1, i + h);
        // Down the window's rows (every other), for every column: the sums of 1, p, pp (small
        // integers: exact in float).
        std::fill(column_sums_.begin(), column_sums_.end(), 0.0f);
        for (int p = plo; p <= phi; p += 2) {
            const float dp = static_cast<float>(p - i);
            kernels::add_row_moments(w, &known_f_[p * w], dp, c1, cp, cpp);
        }
        for (int b = 0; b < ly; ++b) {
            if (!need[b]) continue;
            const int j = b * kGroundStride, qlo = std::max(0, j - h), qhi = std::min(ny - 1, j + h);
            PlaneMoments m;
            for (int q = qlo; q <= qhi; q += 2) {
                const double dq = q - j;
                m.s0 += c1[q];
                m.sp += cp[q];
                m.spp += cpp[q];
                m.sq += dq * c1[q];
                m.sqq += dq * dq * c1[q];
                m.spq += dq * cp[q];
            }
            if (m.s0 < 3) continue;
            const float zc = g.mean_z_m[static_cast<std::size_t>(i) * w + j];
            const float zref = std::isnan(zc) ? 0.0f : zc;
            // The window's points relative to zref: nr rows of rs lanes (the row's nq points,
            // then NaN; NaN also where unknown). count of them are known (the geometry's s0).
            const int nr = (phi - plo) / 2 + 1, nq = (qhi - qlo) / 2 + 1;
            const std::size_t rs = (static_cast<std::size_t>(nq) + kL - 1) / kL * kL;
            const std::size_t count = static_cast<std::size_t>(m.s0);
            float* __restrict v = win_v_.data();
            float* __restrict lev = win_lev_.data();
            float* __restrict fq = win_q_.data();
            for (std::size_t t = 0; t < rs; ++t) {
                const bool column = t < static_cast<std::size_t>(nq);
                fq[t] = column ? static_cast<float>(qlo + 2 * static_cast<int>(t) - j) : 0.0f;
                lane_known_[t] = column ? -1 : 0;
            }
            // The points, and their heights' moments per lane of the window's columns
            // (classifier_kernels), then across them. The sums are exact (floats times small
            // integers, in double), so their order does not matter. Also the largest
            // |height|, for the float outlier test's error bound.
            const float* first_row = &parity_means_[((qlo & 1) * nx + plo) * half + qlo / 2];
            const float largest = kernels::window_points(first_row, 2 * half, nr, plo - i, rs, lane_known_.data(), zref,
                                                         v, lane_z_.data(), lane_pz_.data());
            for (std::size_t t = 0; t < rs; ++t) {
                m.sz += lane_z_[t];
                m.spz += lane_pz_[t];
                m.sqz += static_cast<double>(fq[t]) * lane_z_[t];
            }
            const PlaneFit first = plane_from_moments(m, nullptr);
            // The second plane: without the points more than band off the first (unknown ones
            // compare false). Tested in float, in the same pass that levels the points along
            // the first plane and counts those below its level (without such points the second
            // plane is the first): the float distance is within tol of the double one the
            // reference compares (a few roundings of values below `bound`), so only a point
            // within tol of the band needs the reference's double test.
            const float bound = largest + std::abs(first.a) +
                                static_cast<float>(h) * (std::abs(first.gp) + std::abs(first.gq)) +
                                static_cast<float>(band);
            const float tol = bound * 0x1p-18f;
            uint8_t* __restrict flags = win_flags_.data();  // per kL points: those off or near the band
            std::size_t below_level = 0;
            const unsigned any_flag = kernels::level_window(
                v, nr, plo - i, rs, fq,
                {first.a, first.gp, first.gq, zref, first.a + zref, static_cast<float>(band), tol}, lev, flags,
                below_level);
            bool subtracted = false;
            if (any_flag) {  // the flagged points tested as the reference, in its order
                const double fa = first.a, fgp = first.gp, fgq = first.gq;
                for (std::size_t vec = 0; vec < static_cast<std::size_t>(nr) * rs / kL; ++vec)
                    for (unsigned lanes = flags[vec]; lanes != 0; lanes &= lanes - 1) {
                        const std::size_t at = vec * kL + static_cast<std::size_t>(__builtin_ctz(lanes));
                        const int r = static_cast<int>(at / rs);
                        const double p = static_cast<float>(plo + 2 * r - i), q = fq[at % rs];
                        const double x = v[at];
                        if (!(std::abs(x - (fa + fgp * p + fgq * q)) > band)) continue;
                        subtracted = true;
                        m.s0 -= 1;
                        m.sp -= p;
                        m.sq -= q;
                        m.spp -= p * p;
                        m.sqq -= q * q;
                        m.spq -= p * q;
                        m.sz -= x;
                        m.spz -= p * x;
                        m.sqz -= q * x;
                    }
            }
            PlaneFit fit = first;
            if (subtracted) {
                // Levelled again along the second plane (each point less its slope; unknown
                // points stay NaN), counted again below its level (the flags are not used).
                fit = plane_from_moments(m, &first);
                kernels::level_window(v, nr, plo - i, rs, fq, {fit.a, fit.gp, fit.gq, zref, fit.a + zref, 0.0f, 0.0f},
                                      lev, flags, below_level);
            }
            const std::size_t points = static_cast<std::size_t>(nr) * rs;
            lattice_[static_cast<std::size_t>(a) * ly + b] = select_rank(lev, points, count, ground_rank(count),
                                                                         fit.a + zref, below_level, 0.01f, win_sel_.data());
            lattice_slope_[static_cast<std::size_t>(a) * ly + b] = {fit.gp, fit.gq};
        }
    }
    interpolate_ground_squares(g, known_, square_known_, lattice_, lattice_slope_, ground);
}

void CellClassifier::classify(const TerrainGrid& g, const Odometer& odometer, TraversabilityLayers& out)
{
    const int nx = g.nx, ny = g.ny;
    const std::size_t n = g.cells();
    const ClassifierConfig& c = config_;
    out.reset(nx, ny);
    top_.resize(n);  // both written in step 1
    bottom_.resize(n);

    // 1. What is known, how certain, and each known cell's supported top and bottom.
    const kernels::CertaintyOf certainty_of = [&](float age) {
        return std::max(0.0, 1.0 - age / c.max_age_s) * std::max(0.0, 1.0 - odometer.driven_since(age) / c.max_driven_m);
    };
    // Measured and not decayed (a certainty of 0: UNKNOWN). Only other cells' spread shares
    // (section 3.5), no sample measured in the cell: the terrain map then shows max = min =
    // mean, and nothing was seen there.
    measured_.resize(n);
    kernels::certainties(n, g.count.data(), g.mean_z_m.data(), g.max_z_m.data(), g.min_z_m.data(),
                         g.age_s.size() == n ? g.age_s.data() : nullptr, certainty_of, out.certainty.data(),
                         measured_.data());
    // The highest sample of a cell when enough samples stand near it, else the mean: one
    // stray return does not make a cell tall. Samples near the extreme, estimated from the
    // (weighted) variance: a fraction p of the samples at distance d from the mean gives a
    // variance of about p d^2, so p n ~ n var / d^2 (a face spread evenly gives n/3).
    kernels::supported_extremes(n, g.mean_z_m.data(), g.max_z_m.data(), g.min_z_m.data(), g.variance_z_m2.data(),
                                g.count.data(), measured_.data(), c.min_support_samples, top_.data(), bottom_.data(),
                                out.roughness_m.data(), out.span_m.data());

    // 2. Steps and drops against the cells within step_radius (the cell itself included):
    // step = own top - lowest bottom around; drop = highest mean around - own bottom.
    const int hs = half_width(c.step_radius_m, g.resolution_m);
    {
        const float *top = top_.data(), *bottom = bottom_.data(), *mean = g.mean_z_m.data();
        window_extreme<true>([=](std::size_t k) { return std::isnan(bottom[k]) ? kInf : bottom[k]; }, nx, ny, hs,
                             window_, lowest_);
        window_extreme<false>([=](std::size_t k) { return std::isnan(top[k]) ? -kInf : mean[k]; }, nx, ny, hs,
                              window_, highest_);
    }
    // NaN where unknown (a known cell has a top and a bottom, and the windows around it are
    // finite).
    kernels::steps_and_drops(n, top_.data(), bottom_.data(), lowest_.data(), highest_.data(), out.step_m.data(),
                             out.drop_m.data());

    // 3. Height classes. A cell is an obstacle when its top stands max_step above the local
    // ground, a negative obstacle when its bottom lies max_drop below it. The local ground
    // is taken on a lattice of every third cell: the 40th percentile of the levels within
    // ground_radius (every other cell) once the slope of the plane through them is taken
    // out, so a box or ditch narrower than the radius is the minority and a slope is its own
    // ground, also where the window is cut by the map's edge or by unknown cells. (Below the
    // median: a wall seen only at its foot, in a line of well-sampled cells at the edge of
    // what is known, would otherwise raise its own ground.)
    known_.resize(n);
    // Over the cells' levels: the mean, unless it lies outside the cell's own samples (the
    // terrain map then publishes it as the max or the min). Then other cells' spread shares
    // moved it (docs/terrain.md, section 3.5: a wall's samples at range raise the means of
    // the ground cells before it, never their lowest samples), and the level is the measured
    // extreme on the other side: the bottom under a mean raised, the top over a mean lowered.
    levels_.resolution_m = g.resolution_m;
    levels_.nx = nx;
    levels_.ny = ny;
    levels_.mean_z_m.resize(n);
    // Unknown cells keep their mean.
    kernels::cell_levels(n, top_.data(), bottom_.data(), g.mean_z_m.data(), g.max_z_m.data(), g.min_z_m.data(),
                         known_.data(), levels_.mean_z_m.data());
    // The ground is fitted to the known cells that hold no step: a cell whose supported top
    // and bottom lie max_step apart is no ground level. A wall's foot at the edge of what is
    // known would tilt the plane up to the wall, and lift the ground under the cells behind
    // its face.
    ground_points_.resize(n);
    {
        const float max_step = float_at_least(c.max_step_m);
        const uint8_t* known = known_.data();
        const float *top = top_.data(), *bottom = bottom_.data();
        uint8_t* points = ground_points_.data();
        for (std::size_t k = 0; k < n; ++k) points[k] = static_cast<uint8_t>(known[k] & !(top[k] - bottom[k] >= max_step));
    }
    local_ground(levels_, c.ground_radius_m, c.max_step_m, out.ground_m);
    // The lowest level within step_radius, for the vertical faces below.
    {
        const uint8_t* known = known_.data();
        const float* level = levels_.mean_z_m.data();
        window_extreme<true>([=](std::size_t k) { return known[k] ? level[k] : kInf; }, nx, ny, hs, window_,
                             lowest_level_);
    }
    // The height flags without a branch (an unknown cell or ground compares false), the
    // limits as the least floats at or above them (the same verdicts as the comparisons in
    // double).
    // A vertical face up from a neighbour is an obstacle whatever the local ground (a ramp's
    // side, a wide ditch's rim), unless a drop lies beside it: the face is then a ditch's
    // wall, and the cell a negative obstacle if its own samples reach face_mean_step down
    // from its top (it holds the wall's top), else left alone (level ground beside the
    // edge). Marked after the visits, so that each reads kLow as height_flags left it. The
    // means must step too (the cell's mean over the lowest level around): the spread of
    // passes seen with different pose errors moves a cell's extremes, not its mean.
    // The candidates flagged in the same pass (step is NaN where unknown and compares false),
    // then visited by memchr: they are few.
    edge_.resize(n);
    face_.resize(n);
    const kernels::HeightLimits limits{float_at_least(c.max_step_m), float_at_least(c.max_drop_m),
                                       float_at_least(c.face_mean_step_m), kHigh, kLow};
    kernels::height_flags(n, top_.data(), bottom_.data(), out.ground_m.data(), out.step_m.data(), g.mean_z_m.data(),
                          lowest_level_.data(), limits, edge_.data(), face_.data());
    for (const uint8_t *f = face_.data(), *end = face_.data() + n;
         (f = static_cast<const uint8_t*>(std::memchr(f, 1, static_cast<std::size_t>(end - f)))) != nullptr; ++f) {
        const std::size_t k = static_cast<std::size_t>(f - face_.data());
        const int i = static_cast<int>(k / static_cast<std::size_t>(ny)), j = static_cast<int>(k % static_cast<std::size_t>(ny));
        bool drop_beside = false;
        for (int p = std::max(0, i - hs); p <= std::min(nx - 1, i + hs) && !drop_beside; ++p)
            for (int q = std::max(0, j - hs); q <= std::min(ny - 1, j + hs); ++q)
                if (edge_[static_cast<std::size_t>(p) * ny + q] & kLow) drop_beside = true;
        if (!drop_beside)
            edge_[k] |= kHigh;
        else if (top_[k] - bottom_[k] >= limits.face_step)
            rims_.push_back(k);
    }
    for (const std::size_t k : rims_) edge_[k] |= kLow;
    rims_.clear();
    // A drop whose face lies in its rim's shadow, across unknown cells within shadow_radius
    // (drop_across_unknown.hpp). Obstacles already are skipped.
    {
        const double r = c.shadow_radius_m;
        const float* top = top_.data();
        window_extreme<true>([=](std::size_t k) { return std::isnan(top[k]) ? kInf : top[k]; }, nx, ny,
                             half_width(r, g.resolution_m), window_, lowest_top_);
        if (!drops_ || !drops_->built_for(r, g.resolution_m))
            drops_ = std::make_shared<const DropsAcrossUnknown>(r, g.resolution_m);
        drops_->mark(g, top_, bottom_, lowest_top_, c.max_drop_m, c.max_slope_deg, kLow, kHigh, edge_, out.drop_m);
    }
    // A cell of fewer samples than min_support_samples is an obstacle only if a cell within
    // two is too: one stray return alone is not. Two, not one: behind a face the terrain
    // map's cells often hold only spread shares (unknown here), so a sample of the face
    // that lands behind it lies two cells from the face's obstacle.
    auto neighbour_has = [&](int i, int j, uint8_t bit) {
        for (int p = std::max(0, i - kFewSupportCells); p <= std::min(nx - 1, i + kFewSupportCells); ++p)
            for (int q = std::max(0, j - kFewSupportCells); q <= std::min(ny - 1, j + kFewSupportCells); ++q)
                if ((p != i || q != j) && (edge_[static_cast<std::size_t>(p) * ny + q] & bit)) return true;
        return false;
    };
    auto height_class = [&](std::size_t k) {
        if (!(edge_[k] & (kHigh | kLow))) return;  // only known cells have them
        const int i = static_cast<int>(k / static_cast<std::size_t>(ny));
        const int j = static_cast<int>(k % static_cast<std::size_t>(ny));
        CellClass cls = CellClass::traversable;
        const bool few = g.count[k] < c.min_support_samples;
        if ((edge_[k] & kHigh) && !(few && !neighbour_has(i, j, kHigh)))
            cls = CellClass::obstacle;
        else if ((edge_[k] & kLow) && !(few && !neighbour_has(i, j, kLow)))
            cls = CellClass::negative_obstacle;
        out.cell_class[k] = cls;
    };
    // Known cells traversable, the others unknown: known_ is 1 or 0, the classes' values.
    static_assert(static_cast<uint8_t>(CellClass::traversable) == 1 && static_cast<uint8_t>(CellClass::unknown) == 0);
    std::memcpy(out.cell_class.data(), known_.data(), n);
    // Then the few cells with a height flag, found eight flags at a time (edge_ holds only
    // kHigh and kLow so far).
    std::size_t k0 = 0;
    for (; k0 + 8 <= n; k0 += 8) {
        uint64_t eight;
        std::memcpy(&eight, &edge_[k0], sizeof eight);
        if (eight != 0)
            for (std::size_t k = k0; k < k0 + 8; ++k) height_class(k);
    }
    for (; k0 < n; ++k0) height_class(k0);

    // 4. Slope: the plane fitted to the means of the cells within slope_radius that are not
    // step obstacles (a box would tilt the ground beside it). Separable: along each row,
    // over the window's columns, the sums of w, w dq, w dq^2, w z, w z dq (w = 1 for a cell
    // that counts, dq its column offset, z its height relative to the vehicle); then down
    // the window's rows the plane's centred moments, and the obstacles in the window.
    // slope_reference() is the same fit written window by window.
    const int hp = half_width(c.slope_radius_m, g.resolution_m);
    enum { W, WQ, WQQ, WZ, WZQ, OBST, kRowSums };
    constexpr std::size_t kL = kernels::kPadLanes;
    const std::size_t w = static_cast<std::size_t>(ny), wv = (w + kL - 1) / kL * kL, hw = static_cast<std::size_t>(hp);
    // Row sums for the 2 hp + 1 rows a window spans, in a ring (row p in slot p mod span),
    // each computed as the column pass first needs it; rows at a stride of whole vectors.
    const int span = 2 * hp + 1;
    row_sums_.resize(static_cast<std::size_t>(span) * kRowSums * wv);
    auto rows = [&](int p) { return &row_sums_[static_cast<std::size_t>(p % span) * kRowSums * wv]; };
    const float z0 = static_cast<float>(g.position_m.z());
    // A row's weights, heights and obstacle flags, padded with hp zeros on each side.
    line_w_.assign(wv + 2 * hw, 0.0f);
    line_z_.assign(wv + 2 * hw, 0.0f);
    line_o_.assign(wv + 2 * hw, 0.0f);
    // Rows without a known cell have row sums of +0, which add nothing: they are skipped.
    row_known_.resize(static_cast<std::size_t>(nx));
    for (int i = 0; i < nx; ++i) {
        const uint8_t* kr = &known_[i * w];
        row_known_[static_cast<std::size_t>(i)] = std::find(kr, kr + w, 1) != kr + w;
    }
    auto row_pass = [&](int i) {
        if (!row_known_[static_cast<std::size_t>(i)]) return;
        float *lw = line_w_.data() + hw, *lz = line_z_.data() + hw, *lo = line_o_.data() + hw;
        const std::size_t k = static_cast<std::size_t>(i) * w;
        kernels::slope_row_inputs(w, &known_[k], &out.cell_class[k], &g.mean_z_m[k], z0, lw, lz, lo);
        float* r = rows(i);
        kernels::slope_row_sums(line_w_.data(), line_z_.data(), line_o_.data(), hp, wv, r + W * wv, r + WQ * wv,
                                r + WQQ * wv, r + WZ * wv, r + WZQ * wv, r + OBST * wv);
    };
    int rows_done = 0;
    const double min_cells = 0.5 * (2 * hp + 1) * (2 * hp + 1);
    slope_rows_.resize(static_cast<std::size_t>(span));
    slope_fd_.resize(static_cast<std::size_t>(span));
    moments_.resize(wv * 10);
    for (int i = 0; i < nx; ++i) {
        for (; rows_done <= std::min(nx - 1, i + hp); ++rows_done) row_pass(rows_done);
        // The window's moments about its centre cell, for each cell of row i.
        int nrows = 0;
        for (int p = std::max(0, i - hp); p <= std::min(nx - 1, i + hp); ++p) {
            if (!row_known_[static_cast<std::size_t>(p)]) continue;
            slope_rows_[static_cast<std::size_t>(nrows)] = rows(p);
            slope_fd_[static_cast<std::size_t>(nrows)] = static_cast<float>(p - i);
            ++nrows;
        }
        // Only the cells from the row's first known one to its last need a slope.
        const uint8_t* kr = &known_[i * w];
        const int jlo = static_cast<int>(std::find(kr, kr + w, 1) - kr);
        if (jlo == ny) continue;
        int jhi = ny;
        while (!kr[jhi - 1]) --jhi;  // stops at jlo's at the latest
        kernels::slope_column_sums(slope_rows_.data(), slope_fd_.data(), nrows, wv,
                                   static_cast<std::size_t>(jlo) / kL * kL,
                                   (static_cast<std::size_t>(jhi) + kL - 1) / kL * kL, moments_.data());
        const float* so = &moments_[9 * wv];
        // The plane's gradient (cells as units) from the centred moments, and the tangent of
        // its steepest angle (classifier_kernels); the arc tangent follows.
        tangent_.resize(w);
        const float* tangent = tangent_.data();
        kernels::slope_tangents(moments_.data(), wv, jlo, jhi, min_cells, g.resolution_m, tangent_.data());
        for (int j = jlo; j < jhi; ++j) {
            const std::size_t k = static_cast<std::size_t>(i) * w + j;
            if (std::isnan(top_[k])) continue;
            if (so[j] > 0.5f) edge_[k] |= kObstacleNear;
            if (!std::isnan(tangent[j])) out.slope_deg[k] = std::atan(tangent[j]) * static_cast<float>(180.0 / M_PI);
        }
    }

    // 5. Too steep is an obstacle (where no step obstacle spoils the plane); the rest costs
    // the largest of its step, drop, roughness and slope against their limits.
    kernels::slope_class_and_cost(n, out.step_m.data(), out.drop_m.data(), out.roughness_m.data(), out.slope_deg.data(),
                                  edge_.data(), kObstacleNear,
                                  {c.max_step_m, c.max_drop_m, c.max_roughness_m, c.max_slope_deg},
                                  out.cell_class.data(), out.cost.data());
}

}  // namespace ugv::traverse
