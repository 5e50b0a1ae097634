#include "classifier_kernels.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#include "ugv/traverse/cell_classifier.hpp"
#include "ugv/simd/float4.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#define UGV_TRAVERSE_AVX2 1
#include <immintrin.h>
#endif

namespace ugv::traverse {

namespace {

std::atomic<bool> g_avx2_allowed{true};

bool cpu_has_avx2()
{
#if defined(UGV_TRAVERSE_AVX2)
    static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
    return has;
#else
    return false;
#endif
}

}  // namespace

void allow_avx2(bool allowed) { g_avx2_allowed.store(allowed, std::memory_order_relaxed); }

namespace kernels {

namespace {

using namespace simd;
using F4 = Float4;
using I4 = Int4;
using D2 = Double2;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The loops that the compiler vectorises by itself, written once: inlined into the baseline
// and the AVX2 entry points, each compiled for its own lanes.
[[gnu::always_inline]] inline std::size_t count_below_body(const float* __restrict v, std::size_t n, float t)
{
    int32_t c = 0;
    for (std::size_t u = 0; u < n; ++u) c += v[u] < t ? 1 : 0;
    return static_cast<std::size_t>(c);
}

[[gnu::always_inline]] inline void slope_tangents_body(const float* __restrict m, std::size_t w4, int jlo, int jhi,
                                                       double min_cells, double resolution_m,
                                                       float* __restrict tangent)
{
    const float *s0 = m, *sp = m + w4, *spp = m + 2 * w4, *sq = m + 3 * w4, *sqq = m + 4 * w4;
    const float *spq = m + 5 * w4, *sz = m + 6 * w4, *szp = m + 7 * w4, *szq = m + 8 * w4;
    // No branch and no call, so that it vectorises.
    for (int j = jlo; j < jhi; ++j) {
        const double c0 = s0[j];
        const double mp = sp[j] / c0, mq = sq[j] / c0, mz = sz[j] / c0;
        const double cii = spp[j] - c0 * mp * mp, cjj = sqq[j] - c0 * mq * mq, cij = spq[j] - c0 * mp * mq;
        const double ciz = szp[j] - c0 * mp * mz, cjz = szq[j] - c0 * mq * mz;
        const double det = cii * cjj - cij * cij;
        const double gi = (cjj * ciz - cij * cjz) / det, gj = (cii * cjz - cij * ciz) / det;
        const float t = static_cast<float>(std::sqrt(gi * gi + gj * gj) / resolution_m);
        tangent[j] = (c0 >= min_cells) & !(det < 1e-6 * c0 * c0) ? t : kNaN;
    }
}

[[gnu::always_inline]] inline void add_row_moments_body(std::size_t n, const float* __restrict known, float dp,
                                                        float* __restrict c1, float* __restrict cp,
                                                        float* __restrict cpp)
{
    for (std::size_t q = 0; q < n; ++q) {
        c1[q] += known[q];
        cp[q] += dp * known[q];
        cpp[q] += dp * dp * known[q];
    }
}

[[gnu::always_inline]] inline void slope_row_inputs_body(std::size_t n, const uint8_t* __restrict known,
                                                         const CellClass* __restrict cell_class,
                                                         const float* __restrict mean, float z0, float* __restrict lw,
                                                         float* __restrict lz, float* __restrict lo)
{
    for (std::size_t j = 0; j < n; ++j) {
        const bool counts = (known[j] != 0) & (cell_class[j] == CellClass::traversable);
        lw[j] = counts ? 1.0f : 0.0f;
        lz[j] = counts ? mean[j] - z0 : 0.0f;
        lo[j] = (known[j] != 0) & !counts ? 1.0f : 0.0f;
    }
}

// The slope's sums, V a vector of 4 or 8 floats (GCC/Clang vector extensions; each lane the
// scalar expression's IEEE result, so both widths give the same sums). memcpy for the
// unaligned loads and stores, so that no function passes a V by value.
template <class V>
[[gnu::always_inline]] inline void slope_row_sums_body(const float* __restrict lw, const float* __restrict lz,
                                                       const float* __restrict lo, int hp, std::size_t wv,
                                                       float* __restrict rw, float* __restrict rwq,
                                                       float* __restrict rwqq, float* __restrict rwz,
                                                       float* __restrict rwzq, float* __restrict ro)
{
    constexpr std::size_t kN = sizeof(V) / sizeof(float);
    for (std::size_t j = 0; j < wv; j += kN) {
        V sw{}, swq{}, swqq{}, swz{}, swzq{}, so{};
        for (int t = 0; t <= 2 * hp; ++t) {
            const float fd = static_cast<float>(t - hp);
            V wt, zt, ot;
            std::memcpy(&wt, lw + j + t, sizeof wt);
            std::memcpy(&zt, lz + j + t, sizeof zt);
            std::memcpy(&ot, lo + j + t, sizeof ot);
            const V zv = zt * wt;
            sw += wt;
            swq += fd * wt;
            swqq += fd * fd * wt;
            swz += zv;
            swzq += fd * zv;
            so += ot;
        }
        std::memcpy(rw + j, &sw, sizeof sw);
        std::memcpy(rwq + j, &swq, sizeof swq);
        std::memcpy(rwqq + j, &swqq, sizeof swqq);
        std::memcpy(rwz + j, &swz, sizeof swz);
        std::memcpy(rwzq + j, &swzq, sizeof swzq);
        std::memcpy(ro + j, &so, sizeof so);
    }
}

template <class V>
[[gnu::always_inline]] inline void slope_column_sums_body(const float* const* rows, const float* fds, int nrows,
                                                          std::size_t wv, std::size_t j_from, std::size_t j_to,
                                                          float* __restrict m)
{
    constexpr std::size_t kN = sizeof(V) / sizeof(float);
    for (std::size_t j = j_from; j < j_to; j += kN) {
        V s0{}, sp{}, spp{}, sq{}, sqq{}, spq{}, sz{}, szp{}, szq{}, so{};
        for (int r = 0; r < nrows; ++r) {
            const float* row = rows[r];
            const float fd = fds[r];
            V rw, rwq, rwqq, rwz, rwzq, ro;
            std::memcpy(&rw, row + j, sizeof rw);
            std::memcpy(&rwq, row + wv + j, sizeof rwq);
            std::memcpy(&rwqq, row + 2 * wv + j, sizeof rwqq);
            std::memcpy(&rwz, row + 3 * wv + j, sizeof rwz);
            std::memcpy(&rwzq, row + 4 * wv + j, sizeof rwzq);
            std::memcpy(&ro, row + 5 * wv + j, sizeof ro);
            s0 += rw;
            sp += fd * rw;
            spp += fd * fd * rw;
            sq += rwq;
            sqq += rwqq;
            spq += fd * rwq;
            sz += rwz;
            szp += fd * rwz;
            szq += rwzq;
            so += ro;
        }
        const V all[10] = {s0, sp, spp, sq, sqq, spq, sz, szp, szq, so};
        for (std::size_t e = 0; e < 10; ++e) std::memcpy(m + e * wv + j, &all[e], sizeof all[e]);
    }
}

[[gnu::always_inline]] inline float supported_extreme(float mean, float extreme, float variance, int32_t count,
                                                     double min_support)
{
    const double d = static_cast<double>(extreme) - mean;
    const double near_extreme = count * static_cast<double>(variance) / (d * d);
    return (std::abs(d) < 1e-4) | (near_extreme >= min_support) ? extreme : mean;
}

// Without a branch, so that it vectorises (the quotient is computed also where it is not
// used, and where the cell is not measured: selected away).
[[gnu::always_inline]] inline void supported_extremes_body(std::size_t n, const float* __restrict mean,
                                                           const float* __restrict highest,
                                                           const float* __restrict lowest,
                                                           const float* __restrict variance,
                                                           const int32_t* __restrict count,
                                                           const uint8_t* __restrict measured, double min_support,
                                                           float* __restrict top, float* __restrict bottom,
                                                           float* __restrict roughness, float* __restrict span)
{
    for (std::size_t k = 0; k < n; ++k) {
        const float v = variance[k], var = std::abs(v) <= std::numeric_limits<float>::max() ? v : 0.0f;
        const float m = mean[k], hi = highest[k], lo = lowest[k];
        const bool ok = measured[k] != 0;
        const float t = supported_extreme(m, hi, var, count[k], min_support);
        const float b = supported_extreme(m, lo, var, count[k], min_support), r = std::sqrt(var);
        top[k] = ok ? t : kNaN;
        bottom[k] = ok ? b : kNaN;
        roughness[k] = ok ? r : kNaN;
        span[k] = ok ? hi - lo : kNaN;
    }
}

// The per-cell passes of steps 2-4: selects without a branch, so that they vectorise.
[[gnu::always_inline]] inline void steps_and_drops_body(std::size_t n, const float* __restrict top,
                                                        const float* __restrict bottom, const float* __restrict lowest,
                                                        const float* __restrict highest, float* __restrict step,
                                                        float* __restrict drop)
{
    for (std::size_t k = 0; k < n; ++k) {
        const float up = top[k] - lowest[k], down = highest[k] - bottom[k];  // std::max(0, x)
        step[k] = top[k] == top[k] ? (0.0f < up ? up : 0.0f) : kNaN;
        drop[k] = top[k] == top[k] ? (0.0f < down ? down : 0.0f) : kNaN;
    }
}

[[gnu::always_inline]] inline void cell_levels_body(std::size_t n, const float* __restrict top,
                                                    const float* __restrict bottom, const float* __restrict mean,
                                                    const float* __restrict highest, const float* __restrict lowest,
                                                    uint8_t* __restrict known, float* __restrict level)
{
    for (std::size_t k = 0; k < n; ++k) {
        const float m = mean[k];
        const bool raised = (highest[k] == m) & (lowest[k] < m), lowered = (lowest[k] == m) & (highest[k] > m);
        const float own = raised ? bottom[k] : (lowered ? top[k] : m);
        known[k] = top[k] == top[k] ? 1 : 0;
        level[k] = top[k] == top[k] ? own : m;
    }
}

[[gnu::always_inline]] inline void height_flags_body(std::size_t n, const float* __restrict top,
                                                     const float* __restrict bottom, const float* __restrict ground,
                                                     const float* __restrict step, const float* __restrict mean,
                                                     const float* __restrict lowest_level, const HeightLimits& limits,
                                                     uint8_t* __restrict edge, uint8_t* __restrict face)
{
    const float max_step = limits.max_step, max_drop = limits.max_drop, face_step = limits.face_step;
    const uint8_t high = limits.high_bit, low = limits.low_bit;
    for (std::size_t k = 0; k < n; ++k) {
        const float up = top[k] - ground[k], down = ground[k] - bottom[k], off = mean[k] - ground[k];
        const bool within = top[k] - bottom[k] >= max_step;
        edge[k] = static_cast<uint8_t>((up >= max_step || (within & (up >= down) & (off >= face_step)) ? high : 0) |
                                       (down >= max_drop || (within & (down > up) & (-off >= face_step)) ? low : 0));
        face[k] = (step[k] >= max_step) & !(mean[k] - lowest_level[k] < face_step) ? 1 : 0;
    }
}

// Without a branch, so that it vectorises: every quotient is computed and the verdicts
// selected. std::max (a < b ? b : a) leaves a NaN slope out as the plain loop's test did.
[[gnu::always_inline]] inline void slope_class_and_cost_body(std::size_t n, const float* __restrict step,
                                                             const float* __restrict drop,
                                                             const float* __restrict roughness,
                                                             const float* __restrict slope_deg,
                                                             const uint8_t* __restrict flags, uint8_t near_bit,
                                                             const CostLimits& limits, CellClass* __restrict cell_class,
                                                             float* __restrict cost)
{
    const double max_step = limits.max_step_m, max_drop = limits.max_drop_m;
    const double max_rough = limits.max_roughness_m, max_slope = limits.max_slope_deg;
    for (std::size_t k = 0; k < n; ++k) {
        const CellClass cls = cell_class[k];
        const double slope = slope_deg[k];
        const bool steep = (cls == CellClass::traversable) & ((flags[k] & near_bit) == 0) & (slope > max_slope);
        const CellClass now = steep ? CellClass::obstacle : cls;
        double q = std::max(step[k] / max_step, drop[k] / max_drop);
        q = std::max(q, roughness[k] / max_rough);
        q = std::max(q, slope / max_slope);
        const float c = static_cast<float>(std::min(1.0, q));
        cell_class[k] = now;
        cost[k] = cls == CellClass::unknown ? kNaN : (now == CellClass::traversable ? c : 1.0f);
    }
}

std::size_t gather_in_sse(const float* v, std::size_t n, float lo, float hi, float* __restrict buf)
{
    // Four at a time tested, and the lanes that hold one gathered.
    std::size_t m = 0, u = 0;
    const F4 lo4 = {lo, lo, lo, lo}, hi4 = {hi, hi, hi, hi};
    for (; u + 4 <= n; u += 4)
        for (unsigned in = lane_bits((load4(v + u) >= lo4) & (load4(v + u) < hi4)); in != 0; in &= in - 1)
            buf[m++] = v[u + static_cast<std::size_t>(__builtin_ctz(in))];
    for (; u < n; ++u) {
        buf[m] = v[u];
        m += v[u] >= lo && v[u] < hi ? 1 : 0;
    }
    return m;
}

#if defined(UGV_TRAVERSE_AVX2)
[[gnu::target("avx2,popcnt")]] std::size_t count_below_avx2(const float* v, std::size_t n, float t)
{
    return count_below_body(v, n, t);
}

using F8 = float __attribute__((vector_size(32)));

[[gnu::target("avx2,popcnt")]] void add_row_moments_avx2(std::size_t n, const float* known, float dp, float* c1,
                                                         float* cp, float* cpp)
{
    add_row_moments_body(n, known, dp, c1, cp, cpp);
}

[[gnu::target("avx2,popcnt")]] void slope_row_inputs_avx2(std::size_t n, const uint8_t* known,
                                                          const CellClass* cell_class, const float* mean, float z0,
                                                          float* lw, float* lz, float* lo)
{
    slope_row_inputs_body(n, known, cell_class, mean, z0, lw, lz, lo);
}

[[gnu::target("avx2,popcnt")]] void slope_row_sums_avx2(const float* lw, const float* lz, const float* lo, int hp,
                                                        std::size_t wv, float* rw, float* rwq, float* rwqq,
                                                        float* rwz, float* rwzq, float* ro)
{
    slope_row_sums_body<F8>(lw, lz, lo, hp, wv, rw, rwq, rwqq, rwz, rwzq, ro);
}

[[gnu::target("avx2,popcnt")]] void slope_column_sums_avx2(const float* const* rows, const float* fds, int nrows,
                                                           std::size_t wv, std::size_t j_from, std::size_t j_to,
                                                           float* m)
{
    slope_column_sums_body<F8>(rows, fds, nrows, wv, j_from, j_to, m);
}

[[gnu::target("avx2,popcnt")]] void slope_tangents_avx2(const float* m, std::size_t w4, int jlo, int jhi,
                                                        double min_cells, double resolution_m, float* tangent)
{
    slope_tangents_body(m, w4, jlo, jhi, min_cells, resolution_m, tangent);
}

[[gnu::target("avx2,popcnt")]] void supported_extremes_avx2(std::size_t n, const float* mean, const float* highest,
                                                            const float* lowest, const float* variance,
                                                            const int32_t* count, const uint8_t* measured,
                                                            double min_support, float* top, float* bottom,
                                                            float* roughness, float* span)
{
    supported_extremes_body(n, mean, highest, lowest, variance, count, measured, min_support, top, bottom, roughness,
                            span);
}

[[gnu::target("avx2,popcnt")]] void steps_and_drops_avx2(std::size_t n, const float* top, const float* bottom,
                                                         const float* lowest, const float* highest, float* step,
                                                         float* drop)
{
    steps_and_drops_body(n, top, bottom, lowest, highest, step, drop);
}

[[gnu::target("avx2,popcnt")]] void cell_levels_avx2(std::size_t n, const float* top, const float* bottom,
                                                     const float* mean, const float* highest, const float* lowest,
                                                     uint8_t* known, float* level)
{
    cell_levels_body(n, top, bottom, mean, highest, lowest, known, level);
}

[[gnu::target("avx2,popcnt")]] void height_flags_avx2(std::size_t n, const float* top, const float* bottom,
                                                      const float* ground, const float* step, const float* mean,
                                                      const float* lowest_level, const HeightLimits& limits,
                                                      uint8_t* edge, uint8_t* face)
{
    height_flags_body(n, top, bottom, ground, step, mean, lowest_level, limits, edge, face);
}

[[gnu::target("avx2,popcnt")]] void slope_class_and_cost_avx2(std::size_t n, const float* step, const float* drop,
                                                              const float* roughness, const float* slope_deg,
                                                              const uint8_t* flags, uint8_t near_bit, const CostLimits& limits,
                                                              CellClass* cell_class, float* cost)
{
    slope_class_and_cost_body(n, step, drop, roughness, slope_deg, flags, near_bit, limits, cell_class, cost);
}

// Per mask of 8 lanes, the lanes set, first to last (then 0): a permutation that packs them.
struct PackTable
{
    alignas(32) int32_t lanes[256][8];
    constexpr PackTable() : lanes{}
    {
        for (int mask = 0; mask < 256; ++mask) {
            int e = 0;
            for (int lane = 0; lane < 8; ++lane)
                if (mask & (1 << lane)) lanes[mask][e++] = lane;
        }
    }
};
constexpr PackTable kPack{};

// Eight at a time, without a branch: the lanes in range packed by a permutation and stored
// (all eight: m <= u, so they fit in buf's n), the count advanced by the mask's bits.
[[gnu::target("avx2,popcnt")]] std::size_t gather_in_avx2(const float* v, std::size_t n, float lo, float hi,
                                                           float* __restrict buf)
{
    std::size_t m = 0, u = 0;
    const __m256 lo8 = _mm256_set1_ps(lo), hi8 = _mm256_set1_ps(hi);
    for (; u + 8 <= n; u += 8) {
        const __m256 x = _mm256_loadu_ps(v + u);
        const __m256 in = _mm256_and_ps(_mm256_cmp_ps(x, lo8, _CMP_GE_OQ), _mm256_cmp_ps(x, hi8, _CMP_LT_OQ));
        const unsigned mask = static_cast<unsigned>(_mm256_movemask_ps(in));
        const __m256i perm = _mm256_load_si256(reinterpret_cast<const __m256i*>(kPack.lanes[mask]));
        _mm256_storeu_ps(buf + m, _mm256_permutevar8x32_ps(x, perm));
        m += static_cast<std::size_t>(__builtin_popcount(mask));
    }
    for (; u < n; ++u) {
        buf[m] = v[u];
        m += v[u] >= lo && v[u] < hi ? 1 : 0;
    }
    return m;
}
#endif

}  // namespace

// The loops that need the lanes' own intrinsics: 4 lanes for the baseline, 8 for AVX2
// (lane_kernels.inc).
#define UGV_LANES 4
#define UGV_LANES_NS lanes4
#include "lane_kernels.inc"
#undef UGV_LANES
#undef UGV_LANES_NS
#if defined(UGV_TRAVERSE_AVX2)
#pragma GCC push_options
#pragma GCC target("avx2,popcnt")
#define UGV_LANES 8
#define UGV_LANES_NS lanes8
#include "lane_kernels.inc"
#undef UGV_LANES
#undef UGV_LANES_NS
#pragma GCC pop_options
#endif

bool use_avx2() { return cpu_has_avx2() && g_avx2_allowed.load(std::memory_order_relaxed); }

std::size_t count_below(const float* v, std::size_t n, float t)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return count_below_avx2(v, n, t);
#endif
    return count_below_body(v, n, t);
}

std::size_t gather_in(const float* v, std::size_t n, float lo, float hi, float* buf)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return gather_in_avx2(v, n, lo, hi, buf);
#endif
    return gather_in_sse(v, n, lo, hi, buf);
}

void add_row_moments(std::size_t n, const float* known, float dp, float* c1, float* cp, float* cpp)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return add_row_moments_avx2(n, known, dp, c1, cp, cpp);
#endif
    add_row_moments_body(n, known, dp, c1, cp, cpp);
}

void slope_row_inputs(std::size_t n, const uint8_t* known, const CellClass* cell_class, const float* mean, float z0,
                      float* lw, float* lz, float* lo)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return slope_row_inputs_avx2(n, known, cell_class, mean, z0, lw, lz, lo);
#endif
    slope_row_inputs_body(n, known, cell_class, mean, z0, lw, lz, lo);
}

void slope_row_sums(const float* lw, const float* lz, const float* lo, int hp, std::size_t wv, float* rw, float* rwq,
                    float* rwqq, float* rwz, float* rwzq, float* ro)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return slope_row_sums_avx2(lw, lz, lo, hp, wv, rw, rwq, rwqq, rwz, rwzq, ro);
#endif
    slope_row_sums_body<F4>(lw, lz, lo, hp, wv, rw, rwq, rwqq, rwz, rwzq, ro);
}

void slope_column_sums(const float* const* rows, const float* fds, int nrows, std::size_t wv, std::size_t j_from,
                       std::size_t j_to, float* m)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return slope_column_sums_avx2(rows, fds, nrows, wv, j_from, j_to, m);
#endif
    slope_column_sums_body<F4>(rows, fds, nrows, wv, j_from, j_to, m);
}

void slope_tangents(const float* m, std::size_t w4, int jlo, int jhi, double min_cells, double resolution_m,
                    float* tangent)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return slope_tangents_avx2(m, w4, jlo, jhi, min_cells, resolution_m, tangent);
#endif
    slope_tangents_body(m, w4, jlo, jhi, min_cells, resolution_m, tangent);
}

void supported_extremes(std::size_t n, const float* mean, const float* highest, const float* lowest,
                        const float* variance, const int32_t* count, const uint8_t* measured, double min_support,
                        float* top, float* bottom, float* roughness, float* span)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2())
        return supported_extremes_avx2(n, mean, highest, lowest, variance, count, measured, min_support, top, bottom,
                                       roughness, span);
#endif
    supported_extremes_body(n, mean, highest, lowest, variance, count, measured, min_support, top, bottom, roughness,
                            span);
}

void certainties(std::size_t n, const int32_t* count, const float* mean, const float* highest, const float* lowest,
                 const float* age, const CertaintyOf& of, float* certainty, uint8_t* measured)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return lanes8::certainties(n, count, mean, highest, lowest, age, of, certainty, measured);
#endif
    lanes4::certainties(n, count, mean, highest, lowest, age, of, certainty, measured);
}

float window_points(const float* first_row, std::size_t row_stride, int nr, int p0, std::size_t rs,
                    const int32_t* lane_known, float zref, float* v, double* sum_z, double* sum_pz)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return lanes8::window_points(first_row, row_stride, nr, p0, rs, lane_known, zref, v, sum_z, sum_pz);
#endif
    return lanes4::window_points(first_row, row_stride, nr, p0, rs, lane_known, zref, v, sum_z, sum_pz);
}

unsigned level_window(const float* v, int nr, int p0, std::size_t rs, const float* fq, const WindowPlane& plane,
                      float* lev, uint8_t* flags, std::size_t& below)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return lanes8::level_window(v, nr, p0, rs, fq, plane, lev, flags, below);
#endif
    return lanes4::level_window(v, nr, p0, rs, fq, plane, lev, flags, below);
}

void steps_and_drops(std::size_t n, const float* top, const float* bottom, const float* lowest, const float* highest,
                     float* step, float* drop)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return steps_and_drops_avx2(n, top, bottom, lowest, highest, step, drop);
#endif
    steps_and_drops_body(n, top, bottom, lowest, highest, step, drop);
}

void cell_levels(std::size_t n, const float* top, const float* bottom, const float* mean, const float* highest,
                 const float* lowest, uint8_t* known, float* level)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return cell_levels_avx2(n, top, bottom, mean, highest, lowest, known, level);
#endif
    cell_levels_body(n, top, bottom, mean, highest, lowest, known, level);
}

void height_flags(std::size_t n, const float* top, const float* bottom, const float* ground, const float* step,
                  const float* mean, const float* lowest_level, const HeightLimits& limits, uint8_t* edge,
                  uint8_t* face)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2()) return height_flags_avx2(n, top, bottom, ground, step, mean, lowest_level, limits, edge, face);
#endif
    height_flags_body(n, top, bottom, ground, step, mean, lowest_level, limits, edge, face);
}

void slope_class_and_cost(std::size_t n, const float* step, const float* drop, const float* roughness,
                          const float* slope_deg, const uint8_t* flags, uint8_t near_bit, const CostLimits& limits,
                          CellClass* cell_class, float* cost)
{
#if defined(UGV_TRAVERSE_AVX2)
    if (use_avx2())
        return slope_class_and_cost_avx2(n, step, drop, roughness, slope_deg, flags, near_bit, limits, cell_class, cost);
#endif
    slope_class_and_cost_body(n, step, drop, roughness, slope_deg, flags, near_bit, limits, cell_class, cost);
}

}  // namespace kernels

}  // namespace ugv::traverse
