#include "ugv/traverse/cell_classifier.hpp"

#include "local_ground.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace ugv::traverse {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();
// Bits of a cell's flags: its top max_step above the local ground (or a vertical face up
// from a neighbour), its bottom max_drop below it, an obstacle within the slope window (the
// plane there says nothing about the slope).
constexpr uint8_t kHigh = 1, kLow = 2, kObstacleNear = 4;

// GCC/Clang vector extensions for the local ground's windows (what each lane computes is
// the scalar expression's IEEE result, so the values do not depend on the vectors).
using F4 = float __attribute__((vector_size(16)));
using I4 = int32_t __attribute__((vector_size(16)));
using D2 = double __attribute__((vector_size(16)));
using L2 = int64_t __attribute__((vector_size(16)));

F4 load4(const float* p)
{
    F4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
I4 load4(const int32_t* p)
{
    I4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
void store4(float* p, F4 v) { std::memcpy(p, &v, sizeof v); }
F4 nan4() { return F4{kNaN, kNaN, kNaN, kNaN}; }
D2 low2(F4 v) { return D2{v[0], v[1]}; }
D2 high2(F4 v) { return D2{v[2], v[3]}; }
D2 abs2(D2 v) { return (D2)((L2)v & L2{INT64_MAX, INT64_MAX}); }

int half_width(double radius_m, double resolution_m) { return ground_half_width(radius_m, resolution_m); }

// The highest sample of a cell when enough samples stand near it, else the mean: one
// stray return does not make a cell tall. Samples near the extreme, estimated from the
// (weighted) variance: a fraction p of the samples at distance d from the mean gives a
// variance of about p d^2, so p n ~ n var / d^2 (a face spread evenly gives n/3).
float supported_extreme(float mean, float extreme, float variance, int32_t count, double min_support)
{
    const double d = static_cast<double>(extreme) - mean;
    if (std::abs(d) < 1e-4) return extreme;
    const double var = std::isfinite(variance) ? variance : 0.0;
    const double near_extreme = count * var / (d * d);
    return near_extreme >= min_support ? extreme : mean;
}

// The height a known cell stands for in the local ground (docs/traverse.md section 1, step 4):
// its mean, or its supported bottom (top) when the mean stands above (below) all its own samples.
float cell_level(const TerrainGrid& g, std::size_t k, float top, float bottom)
{
    const float mean = g.mean_z_m[k];
    if (g.max_z_m[k] == mean && g.min_z_m[k] < mean) return bottom;
    if (g.min_z_m[k] == mean && g.max_z_m[k] > mean) return top;
    return mean;
}

// How many of v[0, n) are below t (a loop that vectorises).
std::size_t count_below(const float* __restrict v, std::size_t n, float t)
{
    int32_t c = 0;
    for (std::size_t u = 0; u < n; ++u) c += v[u] < t ? 1 : 0;
    return static_cast<std::size_t>(c);
}

// The value of rank k (from 0) among the `finite` values of v[0, n) that are not NaN (NaN
// marks a hole): what std::nth_element would put at k were the holes left out. A bracket
// [lo, hi) that holds it (count_below(lo) <= k < count_below(hi)) is
// found from guess in steps that grow from `step`, then narrowed at the level the counts
// point to until it holds few values; those are gathered and the one of rank k among
// them picked by insertion sort (the first of equal values in v's order, as a running
// minimum would). buf holds n values.
float select_rank(const float* v, std::size_t n, std::size_t finite, std::size_t k, float guess, float step,
                  float* __restrict buf)
{
    constexpr std::size_t kFew = 12;
    float lo = -kInf, hi = kInf;
    std::size_t below_lo = 0, below_hi = finite;
    float t = guess;
    for (int iter = 0; iter < 64 && below_hi - below_lo > kFew; ++iter) {
        const std::size_t c = count_below(v, n, t);
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
    // The values in [lo, hi), in v's order; rank k - below_lo among them. Four at a time
    // tested, and the few fours that hold one gathered.
    std::size_t m = 0, u = 0;
    const F4 lo4 = {lo, lo, lo, lo}, hi4 = {hi, hi, hi, hi};
    for (; u + 4 <= n; u += 4) {
        const I4 in = (load4(v + u) >= lo4) & (load4(v + u) < hi4);
        if ((in[0] | in[1] | in[2] | in[3]) == 0) continue;
        for (std::size_t e = u; e < u + 4; ++e) {
            buf[m] = v[e];
            m += v[e] >= lo && v[e] < hi ? 1 : 0;
        }
    }
    for (; u < n; ++u) {
        buf[m] = v[u];
        m += v[u] >= lo && v[u] < hi ? 1 : 0;
    }
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
    for (std::size_t a = 1; a < m; ++a) {  // stable: equal values keep their order
        const float x = buf[a];
        std::size_t b = a;
        for (; b > 0 && x < buf[b - 1]; --b) buf[b] = buf[b - 1];
        buf[b] = x;
    }
    std::size_t first = r;  // the first of a run of equal values (+0 and -0)
    while (first > 0 && buf[first - 1] == buf[r]) --first;
    return buf[first];
}

// out[k] = min (or max) of in over the square window of half-width h around k; cells
// outside the grid are skipped. Separable: rows, then columns; each pass a running
// min/max over whole rows so that it vectorises.
template <bool kMin>
void window_extreme(const std::vector<float>& in, int nx, int ny, int h, std::vector<float>& tmp,
                    std::vector<float>& out)
{
    const auto pick = [](float a, float b) { return kMin ? (b < a ? b : a) : (b > a ? b : a); };
    const std::size_t w = static_cast<std::size_t>(ny);
    tmp.resize(in.size());
    out.resize(in.size());
    for (int i = 0; i < nx; ++i) {
        const float* __restrict row = &in[i * w];
        float* __restrict t = &tmp[i * w];
        for (std::size_t j = 0; j < w; ++j) t[j] = row[j];
        for (int d = 1; d <= h; ++d) {
            const std::size_t dd = static_cast<std::size_t>(std::min(d, ny));
            for (std::size_t j = 0; j + dd < w; ++j) t[j] = pick(t[j], row[j + dd]);
            for (std::size_t j = dd; j < w; ++j) t[j] = pick(t[j], row[j - dd]);
        }
    }
    for (int i = 0; i < nx; ++i) {
        float* __restrict o = &out[i * w];
        const float* __restrict t0 = &tmp[i * w];
        for (std::size_t j = 0; j < w; ++j) o[j] = t0[j];
        for (int p = std::max(0, i - h); p <= std::min(nx - 1, i + h); ++p) {
            if (p == i) continue;
            const float* __restrict t = &tmp[static_cast<std::size_t>(p) * w];
            for (std::size_t j = 0; j < w; ++j) o[j] = pick(o[j], t[j]);
        }
    }
}

// (Not inlined: GCC vectorises them only with the __restrict parameters in view.)
// One column offset d of the slope's row pass: the row's weights w, heights z and obstacle
// flags o, shifted by d, added into the five row sums and the obstacle count.
template <bool kFirst>
[[gnu::noinline]] void add_row_tap(const float* __restrict lw, const float* __restrict lz, const float* __restrict lo,
                 float* __restrict rw, float* __restrict rwq, float* __restrict rwqq, float* __restrict rwz,
                 float* __restrict rwzq, float* __restrict ro, int d, int ny)
{
    const float fd = static_cast<float>(d);
    const int from = std::max(0, -d), to = std::max(0, ny - std::max(0, d));
    if (kFirst) {  // the sums start at +0 (0 + x below), so that no pass clears them first
        for (int j = 0; j < std::min(from, ny); ++j) rw[j] = rwq[j] = rwqq[j] = rwz[j] = rwzq[j] = ro[j] = 0.0f;
        for (int j = std::max(to, std::min(from, ny)); j < ny; ++j) rw[j] = rwq[j] = rwqq[j] = rwz[j] = rwzq[j] = ro[j] = 0.0f;
        for (int j = from; j < to; ++j) {
            const float wv = lw[j + d], zv = lz[j + d] * wv;
            rw[j] = 0.0f + wv;
            rwq[j] = 0.0f + fd * wv;
            rwqq[j] = 0.0f + fd * fd * wv;
            rwz[j] = 0.0f + zv;
            rwzq[j] = 0.0f + fd * zv;
            ro[j] = 0.0f + lo[j + d];
        }
        return;
    }
    for (int j = from; j < to; ++j) {
        const float wv = lw[j + d], zv = lz[j + d] * wv;
        rw[j] += wv;
        rwq[j] += fd * wv;
        rwqq[j] += fd * fd * wv;
        rwz[j] += zv;
        rwzq[j] += fd * zv;
        ro[j] += lo[j + d];
    }
}

// One row offset fd of the column pass: a row's sums added into the window's moments.
template <bool kFirst>
[[gnu::noinline]] void add_column_tap(const float* __restrict rw, const float* __restrict rwq,
                                      const float* __restrict rwqq, const float* __restrict rwz,
                                      const float* __restrict rwzq, const float* __restrict ro, float* __restrict s0,
                                      float* __restrict sp, float* __restrict spp, float* __restrict sq,
                                      float* __restrict sqq, float* __restrict spq, float* __restrict sz,
                                      float* __restrict szp, float* __restrict szq, float* __restrict so, float fd,
                                      std::size_t w)
{
    if (kFirst) {  // the sums start at +0: 0 + x, so that no pass clears them first
        for (std::size_t j = 0; j < w; ++j) {
            s0[j] = 0.0f + rw[j];
            sp[j] = 0.0f + fd * rw[j];
            spp[j] = 0.0f + fd * fd * rw[j];
            sq[j] = 0.0f + rwq[j];
            sqq[j] = 0.0f + rwqq[j];
            spq[j] = 0.0f + fd * rwq[j];
            sz[j] = 0.0f + rwz[j];
            szp[j] = 0.0f + fd * rwz[j];
            szq[j] = 0.0f + rwzq[j];
            so[j] = 0.0f + ro[j];
        }
        return;
    }
    for (std::size_t j = 0; j < w; ++j) {
        s0[j] += rw[j];
        sp[j] += fd * rw[j];
        spp[j] += fd * fd * rw[j];
        sq[j] += rwq[j];
        sqq[j] += rwqq[j];
        spq[j] += fd * rwq[j];
        sz[j] += rwz[j];
        szp[j] += fd * rwz[j];
        szq[j] += rwzq[j];
        so[j] += ro[j];
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
    positive(c.max_roughness_m, "max_roughness_m");
    positive(c.max_age_s, "max_age_s");
    positive(c.max_driven_m, "max_driven_m");
    if (!(c.max_slope_deg > 0 && c.max_slope_deg < 90)) throw std::invalid_argument("max_slope_deg must be in (0, 90)");
    if (!(c.min_support_samples >= 1 && c.min_support_samples <= 1000))
        throw std::invalid_argument("min_support_samples must be in [1, 1000]");
}

void CellClassifier::local_ground(const TerrainGrid& g, double radius_m, double max_step_m, std::vector<float>& ground)
{
    // local_ground_reference, lattice point by lattice point, is the specification. Here the
    // window's geometry (the moments of its known cells' offsets) comes from sums along the
    // columns of a lattice row's window rows, then along the window's columns; the heights'
    // moments from the window's points in rows of vectors of 4, unknown points as NaN (the
    // same floats as the reference's, summed in double: integer offsets times floats, exact
    // in any order); the second plane's by subtracting the points off the first; the
    // percentile by counting.
    const int nx = g.nx, ny = g.ny, h = ground_half_width(radius_m, g.resolution_m);
    const int lx = (nx - 1) / kGroundStride + 1, ly = (ny - 1) / kGroundStride + 1;
    const std::size_t n = g.cells(), w = static_cast<std::size_t>(ny), half = (w + 1) / 2;
    lattice_.assign(static_cast<std::size_t>(lx) * ly, kNaN);
    lattice_slope_.assign(static_cast<std::size_t>(lx) * ly, {0.0f, 0.0f});
    // Known cells as 1; the means split by column parity (NaN where unknown) so that a
    // window's every other column is contiguous.
    known_d_.resize(n);
    parity_means_.assign(2 * static_cast<std::size_t>(nx) * half + 4, kNaN);  // + 4: a window row's last vector
    for (std::size_t k = 0; k < n; ++k) known_d_[k] = known_[k] ? 1.0 : 0.0;
    for (int i = 0; i < nx; ++i)
        for (std::size_t j = 0; j < w; ++j)
            if (known_[i * w + j]) parity_means_[((j & 1) * nx + i) * half + j / 2] = g.mean_z_m[i * w + j];
    // A window's points: up to h + 1 rows of h + 1, each row padded to whole vectors of 4.
    const std::size_t row_vectors = (static_cast<std::size_t>(h) + 4) / 4;
    const std::size_t max_points = (static_cast<std::size_t>(h) + 1) * row_vectors * 4;
    win_v_.resize(max_points);
    win_sel_.resize(max_points);
    win_q_.resize(4 * row_vectors);
    lane_known_.resize(4 * row_vectors);
    lane_q_.resize(2 * row_vectors);
    lane_z_.resize(2 * row_vectors);
    lane_pz_.resize(2 * row_vectors);
    column_sums_.resize(3 * w);
    double *c1 = &column_sums_[0], *cp = &column_sums_[w], *cpp = &column_sums_[2 * w];
    const double band = static_cast<float>(0.5 * max_step_m);
    for (int a = 0; a < lx; ++a) {
        const int i = a * kGroundStride, plo = std::max(0, i - h), phi = std::min(nx - 1, i + h);
        // Down the window's rows (every other), for every column: the sums of 1, p, pp.
        std::fill(column_sums_.begin(), column_sums_.end(), 0.0);
        for (int p = plo; p <= phi; p += 2) {
            const double dp = p - i;
            const double* __restrict kr = &known_d_[p * w];
            for (std::size_t q = 0; q < w; ++q) {
                c1[q] += kr[q];
                cp[q] += dp * kr[q];
                cpp[q] += dp * dp * kr[q];
            }
        }
        for (int b = 0; b < ly; ++b) {
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
            // The window's points relative to zref: nr rows of nv vectors of 4 (the row's nq
            // points, then NaN; NaN also where unknown). count of them are known (the
            // geometry's s0).
            const int nr = (phi - plo) / 2 + 1, nq = (qhi - qlo) / 2 + 1, nv = (nq + 3) / 4;
            const std::size_t count = static_cast<std::size_t>(m.s0);
            float* __restrict v = win_v_.data();
            float* __restrict fq = win_q_.data();
            for (int t = 0; t < 4 * nv; ++t) {
                fq[t] = t < nq ? static_cast<float>(qlo + 2 * t - j) : 0.0f;
                lane_known_[static_cast<std::size_t>(t)] = t < nq ? -1 : 0;
            }
            const F4 zr = {zref, zref, zref, zref};
            for (int r = 0; r < nr; ++r) {
                const float* row = &parity_means_[((qlo & 1) * nx + plo + 2 * r) * half + qlo / 2];
                for (int c = 0; c < nv; ++c) {
                    const I4 in = load4(&lane_known_[4 * static_cast<std::size_t>(c)]);
                    const F4 x = load4(row + 4 * c) - zr;
                    store4(v + (static_cast<std::size_t>(r) * nv + c) * 4, (F4)(((I4)x & in) | ((I4)nan4() & ~in)));
                }
            }
            // The heights' moments, per lane of the window's columns, then across them. The sums
            // are exact (floats times small integers, in double), so their order does not
            // matter; an unknown point adds +0 to a sum that started at +0.
            D2* __restrict az = lane_z_.data();
            D2* __restrict apz = lane_pz_.data();
            D2* __restrict dq = lane_q_.data();
            for (int c = 0; c < nv; ++c) {
                const F4 q = load4(fq + 4 * c);
                dq[2 * c] = low2(q);
                dq[2 * c + 1] = high2(q);
                az[2 * c] = az[2 * c + 1] = apz[2 * c] = apz[2 * c + 1] = D2{0.0, 0.0};
            }
            for (int r = 0; r < nr; ++r) {
                const double p = plo + 2 * r - i;
                const D2 fp = {p, p};
                for (int c = 0; c < nv; ++c) {
                    const F4 x = load4(v + (static_cast<std::size_t>(r) * nv + c) * 4);
                    const F4 xz = (F4)((I4)x & (x == x));
                    const D2 lo = low2(xz), hi = high2(xz);
                    az[2 * c] += lo;
                    az[2 * c + 1] += hi;
                    apz[2 * c] += fp * lo;
                    apz[2 * c + 1] += fp * hi;
                }
            }
            for (int e = 0; e < 2 * nv; ++e) {
                const D2 qz = dq[e] * az[e];
                m.sz += az[e][0] + az[e][1];
                m.spz += apz[e][0] + apz[e][1];
                m.sqz += qz[0] + qz[1];
            }
            const PlaneFit first = plane_from_moments(m, nullptr);
            // The second plane: without the points more than band off the first (unknown ones
            // compare false). Whether any is off, tested in vectors; the few windows with one
            // then subtract those points (exact sums: in any order).
            {
                const double fa = first.a, fgp = first.gp, fgq = first.gq;
                const D2 band2 = {band, band}, gq2 = {fgq, fgq};
                for (int e = 0; e < 2 * nv; ++e) apz[e] = gq2 * dq[e];  // reused: fgq q
                L2 any = {0, 0};
                for (int r = 0; r < nr; ++r) {
                    const double p = static_cast<float>(plo + 2 * r - i), cr = fa + fgp * p;
                    const D2 cr2 = {cr, cr};
                    for (int c = 0; c < nv; ++c) {
                        const F4 x = load4(v + (static_cast<std::size_t>(r) * nv + c) * 4);
                        any |= abs2(low2(x) - (cr2 + apz[2 * c])) > band2;
                        any |= abs2(high2(x) - (cr2 + apz[2 * c + 1])) > band2;
                    }
                }
                if (any[0] | any[1]) {
                    for (int r = 0; r < nr; ++r)
                        for (int t = 0; t < nq; ++t) {
                            const double p = static_cast<float>(plo + 2 * r - i), q = fq[t];
                            const double x = v[(static_cast<std::size_t>(r) * nv) * 4 + t];
                            if (!(std::abs(x - (fa + fgp * p + fgq * q)) > band)) continue;
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
            }
            const PlaneFit fit = plane_from_moments(m, &first);
            // Levelled: each point less the plane's slope (unknown points stay NaN).
            {
                const F4 gq4 = {fit.gq, fit.gq, fit.gq, fit.gq};
                for (int r = 0; r < nr; ++r) {
                    const float gp = fit.gp * static_cast<float>(plo + 2 * r - i);
                    const F4 gp4 = {gp, gp, gp, gp};
                    for (int c = 0; c < nv; ++c) {
                        float* at = v + (static_cast<std::size_t>(r) * nv + c) * 4;
                        store4(at, load4(at) + (zr - (gp4 + gq4 * load4(fq + 4 * c))));
                    }
                }
            }
            const std::size_t points = static_cast<std::size_t>(nr) * static_cast<std::size_t>(nv) * 4;
            lattice_[static_cast<std::size_t>(a) * ly + b] =
                select_rank(v, points, count, ground_rank(count), fit.a + zref, 0.01f, win_sel_.data());
            lattice_slope_[static_cast<std::size_t>(a) * ly + b] = {fit.gp, fit.gq};
        }
    }
    interpolate_ground(g, known_, lattice_, lattice_slope_, ground);
}

void CellClassifier::classify(const TerrainGrid& g, const Odometer& odometer, TraversabilityLayers& out)
{
    const int nx = g.nx, ny = g.ny;
    const std::size_t n = g.cells();
    const ClassifierConfig& c = config_;
    out.reset(nx, ny);
    top_.assign(n, kNaN);
    bottom_.assign(n, kNaN);

    // 1. What is known, how certain, and each known cell's supported top and bottom.
    const bool have_age = g.age_s.size() == n;
    float memo_age = kNaN;  // cells fused from one cloud share an age
    double memo_driven = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        if (g.count[k] <= 0 || !std::isfinite(g.mean_z_m[k])) continue;
        // Only other cells' spread shares (section 3.5), no sample measured in the cell: the
        // terrain map then shows max = min = mean. Nothing was seen there.
        if (g.count[k] >= 2 && g.max_z_m[k] == g.min_z_m[k] && g.max_z_m[k] == g.mean_z_m[k]) continue;
        double certainty = 1.0;
        if (have_age && std::isfinite(g.age_s[k])) {
            const float age = g.age_s[k];
            if (age != memo_age) {
                memo_age = age;
                memo_driven = odometer.driven_since(age);
            }
            certainty = std::max(0.0, 1.0 - age / c.max_age_s) * std::max(0.0, 1.0 - memo_driven / c.max_driven_m);
        }
        out.certainty[k] = static_cast<float>(certainty);
        if (certainty <= 0.0) continue;  // decayed: UNKNOWN
        const float var = std::isfinite(g.variance_z_m2[k]) ? g.variance_z_m2[k] : 0.0f;
        top_[k] = supported_extreme(g.mean_z_m[k], g.max_z_m[k], var, g.count[k], c.min_support_samples);
        bottom_[k] = supported_extreme(g.mean_z_m[k], g.min_z_m[k], var, g.count[k], c.min_support_samples);
        out.roughness_m[k] = std::sqrt(var);
        out.span_m[k] = g.max_z_m[k] - g.min_z_m[k];
    }

    // 2. Steps and drops against the cells within step_radius (the cell itself included):
    // step = own top - lowest bottom around; drop = highest mean around - own bottom.
    const int hs = half_width(c.step_radius_m, g.resolution_m);
    tmp_.resize(n);
    for (std::size_t k = 0; k < n; ++k) tmp_[k] = std::isnan(bottom_[k]) ? kInf : bottom_[k];
    window_extreme<true>(tmp_, nx, ny, hs, window_, lowest_);
    for (std::size_t k = 0; k < n; ++k) tmp_[k] = std::isnan(top_[k]) ? -kInf : g.mean_z_m[k];
    window_extreme<false>(tmp_, nx, ny, hs, window_, highest_);
    edge_.assign(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
        if (std::isnan(top_[k])) continue;
        out.step_m[k] = std::max(0.0f, top_[k] - lowest_[k]);
        out.drop_m[k] = std::max(0.0f, highest_[k] - bottom_[k]);
    }

    // 3. Height classes. A cell is an obstacle when its top stands max_step above the local
    // ground, a negative obstacle when its bottom lies max_drop below it. The local ground
    // is taken on a lattice of every third cell: the 40th percentile of the levels within
    // ground_radius (every other cell) once the slope of the plane through them is taken
    // out, so a box or ditch narrower than the radius is the minority and a slope is its own
    // ground, also where the window is cut by the map's edge or by unknown cells. (Below the
    // median: a wall seen only at its foot, in a line of well-sampled cells at the edge of
    // what is known, would otherwise raise its own ground.)
    known_.resize(n);
    for (std::size_t k = 0; k < n; ++k) known_[k] = std::isnan(top_[k]) ? 0 : 1;
    // Over the cells' levels: the mean, unless it lies outside the cell's own samples (the
    // terrain map then publishes it as the max or the min). Then other cells' spread shares
    // moved it (docs/terrain.md, section 3.5: a wall's samples at range raise the means of
    // the ground cells before it, never their lowest samples), and the level is the measured
    // extreme on the other side: the bottom under a mean raised, the top over a mean lowered.
    levels_.resolution_m = g.resolution_m;
    levels_.nx = nx;
    levels_.ny = ny;
    levels_.mean_z_m.resize(n);
    for (std::size_t k = 0; k < n; ++k) levels_.mean_z_m[k] = known_[k] ? cell_level(g, k, top_[k], bottom_[k]) : g.mean_z_m[k];
    local_ground(levels_, c.ground_radius_m, c.max_step_m, out.ground_m);
    // The lowest level within step_radius, for the vertical faces below.
    for (std::size_t k = 0; k < n; ++k) tmp_[k] = known_[k] ? levels_.mean_z_m[k] : kInf;
    window_extreme<true>(tmp_, nx, ny, hs, window_, lowest_mean_);
    const std::vector<float>& ground_ = out.ground_m;
    for (std::size_t k = 0; k < n; ++k) {
        if (std::isnan(top_[k]) || std::isnan(ground_[k])) continue;
        if (top_[k] - ground_[k] >= c.max_step_m) edge_[k] |= kHigh;
        if (ground_[k] - bottom_[k] >= c.max_drop_m) edge_[k] |= kLow;
    }
    // A vertical face up from a neighbour is an obstacle whatever the local ground (a ramp's
    // side, a wide ditch's rim), unless a drop lies beside it: that step is the ditch's edge,
    // already a negative obstacle. The means must step too (the cell's mean over the lowest
    // level around): the spread of passes seen with different pose errors moves a cell's
    // extremes, not its mean.
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i) * ny + j;
            if (std::isnan(top_[k]) || out.step_m[k] < c.max_step_m || g.mean_z_m[k] - lowest_mean_[k] < c.face_mean_step_m)
                continue;
            bool drop_beside = false;
            for (int p = std::max(0, i - hs); p <= std::min(nx - 1, i + hs) && !drop_beside; ++p)
                for (int q = std::max(0, j - hs); q <= std::min(ny - 1, j + hs); ++q)
                    if (edge_[static_cast<std::size_t>(p) * ny + q] & kLow) drop_beside = true;
            if (!drop_beside) edge_[k] |= kHigh;
        }
    }
    // A cell of fewer samples than min_support_samples is an obstacle only if a neighbour
    // is too: one stray return alone is not.
    auto neighbour_has = [&](int i, int j, uint8_t bit) {
        for (int p = std::max(0, i - 1); p <= std::min(nx - 1, i + 1); ++p)
            for (int q = std::max(0, j - 1); q <= std::min(ny - 1, j + 1); ++q)
                if ((p != i || q != j) && (edge_[static_cast<std::size_t>(p) * ny + q] & bit)) return true;
        return false;
    };
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i) * ny + j;
            if (std::isnan(top_[k])) continue;
            CellClass cls = CellClass::traversable;
            const bool few = g.count[k] < c.min_support_samples;
            if ((edge_[k] & kHigh) && !(few && !neighbour_has(i, j, kHigh)))
                cls = CellClass::obstacle;
            else if ((edge_[k] & kLow) && !(few && !neighbour_has(i, j, kLow)))
                cls = CellClass::negative_obstacle;
            out.cell_class[k] = cls;
        }
    }

    // 4. Slope: the plane fitted to the means of the cells within slope_radius that are not
    // step obstacles (a box would tilt the ground beside it). Separable: along each row,
    // over the window's columns, the sums of w, w dq, w dq^2, w z, w z dq (w = 1 for a cell
    // that counts, dq its column offset, z its height relative to the vehicle); then down
    // the window's rows the plane's centred moments, and the obstacles in the window.
    // slope_reference() is the same fit written window by window.
    const int hp = half_width(c.slope_radius_m, g.resolution_m);
    enum { W, WQ, WQQ, WZ, WZQ, OBST, kRowSums };
    const std::size_t w = static_cast<std::size_t>(ny);
    // Row sums for the 2 hp + 1 rows a window spans, in a ring (row p in slot p mod span),
    // each computed as the column pass first needs it.
    const int span = 2 * hp + 1;
    row_sums_.resize(static_cast<std::size_t>(span) * kRowSums * w);
    auto rows = [&](int which, int p) {
        return &row_sums_[(static_cast<std::size_t>(p % span) * kRowSums + static_cast<std::size_t>(which)) * w];
    };
    const float z0 = static_cast<float>(g.position_m.z());
    line_w_.resize(w);
    line_z_.resize(w);
    line_o_.resize(w);
    auto row_pass = [&](int i) {
        std::fill(line_w_.begin(), line_w_.end(), 0.0f);
        std::fill(line_z_.begin(), line_z_.end(), 0.0f);
        std::fill(line_o_.begin(), line_o_.end(), 0.0f);
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i) * w + j;
            if (std::isnan(top_[k])) continue;
            if (out.cell_class[k] != CellClass::traversable) {
                line_o_[j] = 1.0f;
                continue;
            }
            line_w_[j] = 1.0f;
            line_z_[j] = g.mean_z_m[k] - z0;
        }
        for (int d = -hp; d <= hp; ++d)
            (d == -hp ? add_row_tap<true> : add_row_tap<false>)(line_w_.data(), line_z_.data(), line_o_.data(),
                                                                 rows(W, i), rows(WQ, i), rows(WQQ, i), rows(WZ, i),
                                                                 rows(WZQ, i), rows(OBST, i), d, ny);
    };
    int rows_done = 0;
    const double min_cells = 0.5 * (2 * hp + 1) * (2 * hp + 1);
    for (int i = 0; i < nx; ++i) {
        for (; rows_done <= std::min(nx - 1, i + hp); ++rows_done) row_pass(rows_done);
        // The window's moments about its centre cell, for each cell of row i.
        moments_.resize(w * 10);
        float *s0 = &moments_[0], *sp = &moments_[w], *spp = &moments_[2 * w], *sq = &moments_[3 * w];
        float *sqq = &moments_[4 * w], *spq = &moments_[5 * w], *sz = &moments_[6 * w], *szp = &moments_[7 * w];
        float *szq = &moments_[8 * w], *so = &moments_[9 * w];
        for (int p = std::max(0, i - hp); p <= std::min(nx - 1, i + hp); ++p)
            (p == std::max(0, i - hp) ? add_column_tap<true> : add_column_tap<false>)(
                rows(W, p), rows(WQ, p), rows(WQQ, p), rows(WZ, p), rows(WZQ, p), rows(OBST, p), s0, sp, spp, sq, sqq,
                spq, sz, szp, szq, so, static_cast<float>(p - i), w);
        // The plane's gradient (cells as units) from the centred moments, and the tangent of
        // its steepest angle; NaN with too few cells or cells (nearly) on a line. No branch
        // and no call, so that it vectorises; the arc tangent follows.
        tangent_.resize(w);
        float* __restrict tangent = tangent_.data();
        for (int j = 0; j < ny; ++j) {
            const double c0 = s0[j];
            const double mp = sp[j] / c0, mq = sq[j] / c0, mz = sz[j] / c0;
            const double cii = spp[j] - c0 * mp * mp, cjj = sqq[j] - c0 * mq * mq, cij = spq[j] - c0 * mp * mq;
            const double ciz = szp[j] - c0 * mp * mz, cjz = szq[j] - c0 * mq * mz;
            const double det = cii * cjj - cij * cij;
            const double gi = (cjj * ciz - cij * cjz) / det, gj = (cii * cjz - cij * ciz) / det;
            const float t = static_cast<float>(std::sqrt(gi * gi + gj * gj) / g.resolution_m);
            tangent[j] = c0 >= min_cells && !(det < 1e-6 * c0 * c0) ? t : kNaN;
        }
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i) * w + j;
            if (std::isnan(top_[k])) continue;
            if (so[j] > 0.5f) edge_[k] |= kObstacleNear;
            if (!std::isnan(tangent[j])) out.slope_deg[k] = std::atan(tangent[j]) * static_cast<float>(180.0 / M_PI);
        }
    }

    // 5. Too steep is an obstacle (where no step obstacle spoils the plane); the rest costs
    // the largest of its step, drop, roughness and slope against their limits.
    for (std::size_t k = 0; k < n; ++k) {
        if (std::isnan(top_[k])) continue;
        CellClass& cls = out.cell_class[k];
        if (cls == CellClass::traversable && !(edge_[k] & kObstacleNear) && out.slope_deg[k] > c.max_slope_deg)
            cls = CellClass::obstacle;
        if (cls != CellClass::traversable) {
            out.cost[k] = 1.0f;
            continue;
        }
        double cost = std::max(out.step_m[k] / c.max_step_m, out.drop_m[k] / c.max_drop_m);
        cost = std::max(cost, out.roughness_m[k] / c.max_roughness_m);
        if (std::isfinite(out.slope_deg[k])) cost = std::max(cost, out.slope_deg[k] / c.max_slope_deg);
        out.cost[k] = static_cast<float>(std::min(1.0, cost));
    }
}

}  // namespace ugv::traverse
