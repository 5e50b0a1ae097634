// The placement pass of the fusion loop over one chunk of points, in two builds: four
// points at a time for any CPU, eight at a time with AVX2 and FMA (kernel_table.hpp). Both
// run place_math; they differ in how many lanes and in how the outputs are stored.
#include <cstring>

#include "fusion_kernels.hpp"

namespace ugv::terrain::detail {

namespace {

// Points first .. count-1 (first a multiple of 4), four at a time.
void place_from(const Placement& p, const float* const* in, std::size_t first, std::size_t count, PlacedPoints& out)
{
    std::size_t k = first;
    for (; k + 4 <= count; k += 4)
        place_points(p, load4(in[0] + k), load4(in[1] + k), load4(in[2] + k), load4(in[3] + k), load4(in[4] + k),
                     load4(in[5] + k), out, k);
    if (k < count) {
        // The last 1-3 points, padded (the padding is never read back).
        Float4 last[6] = {};
        for (int a = 0; a < 6; ++a)
            for (std::size_t q = 0; k + q < count; ++q) last[a][q] = in[a][k + q];
        place_points(p, last[0], last[1], last[2], last[3], last[4], last[5], out, k);
    }
}

}  // namespace

void place_chunk_generic(const Placement& p, const float* const* in, std::size_t count, PlacedPoints& out)
{
    place_from(p, in, 0, count, out);
}

#if defined(UGV_TERRAIN_HAVE_AVX2)

namespace {

// The batch's constants, each lane of the 4-wide ones being the same, 8 wide.
UGV_AVX2 inline void widen(const Placement& p, PlacementOf<Float8>& q)
{
    static_assert(sizeof(Placement) / sizeof(Float4) * sizeof(Float8) == sizeof(PlacementOf<Float8>));
    const auto* from = reinterpret_cast<const Float4*>(&p);
    auto* to = reinterpret_cast<Float8*>(&q);
    for (std::size_t k = 0; k < sizeof(Placement) / sizeof(Float4); ++k) to[k] = splat8(from[k][0]);
}

// Points first .. first+7 into out (place_points, 8 wide).
UGV_AVX2 inline void place_points8(const PlacementOf<Float8>& p, const float* const* in, std::size_t first,
                                   PlacedPoints& out)
{
    PlacedVector<Float8, Int8> placed;
    place_math(p, load8(in[0] + first), load8(in[1] + first), load8(in[2] + first),
                            load8(in[3] + first), load8(in[4] + first), load8(in[5] + first), placed);
    store_placed(placed, out, first);
    const unsigned bits = lane_bits(placed.fuse);
    out.all_fuse[first / 4] = (bits & 0xfu) == 0xfu;
    out.all_fuse[first / 4 + 1] = (bits >> 4) == 0xfu;
    // One {0, x_rel, y_rel, z} per point: a 4x4 transpose in each 128-bit half gives points
    // first+c (low half) and first+4+c (high half) in vector c.
    const Float8 zero{};
    const Float8 t0 = __builtin_shufflevector(zero, placed.x_rel, 0, 8, 1, 9, 4, 12, 5, 13);
    const Float8 t1 = __builtin_shufflevector(zero, placed.x_rel, 2, 10, 3, 11, 6, 14, 7, 15);
    const Float8 t2 = __builtin_shufflevector(placed.y_rel, placed.l[2], 0, 8, 1, 9, 4, 12, 5, 13);
    const Float8 t3 = __builtin_shufflevector(placed.y_rel, placed.l[2], 2, 10, 3, 11, 6, 14, 7, 15);
    const Float8 s[4] = {__builtin_shufflevector(t0, t2, 0, 1, 8, 9, 4, 5, 12, 13),
                         __builtin_shufflevector(t0, t2, 2, 3, 10, 11, 6, 7, 14, 15),
                         __builtin_shufflevector(t1, t3, 0, 1, 8, 9, 4, 5, 12, 13),
                         __builtin_shufflevector(t1, t3, 2, 3, 10, 11, 6, 7, 14, 15)};
    for (std::size_t c = 0; c < 4; ++c) {
        _mm_storeu_ps(out.sample[first + c], _mm256_castps256_ps128(__m256(s[c])));
        _mm_storeu_ps(out.sample[first + 4 + c], _mm256_extractf128_ps(__m256(s[c]), 1));
    }
}

}  // namespace

UGV_AVX2 void place_chunk_avx2(const Placement& p, const float* const* in, std::size_t count, PlacedPoints& out)
{
    PlacementOf<Float8> wide;
    widen(p, wide);
    std::size_t k = 0;
    for (; k + 8 <= count; k += 8) place_points8(wide, in, k, out);
    place_from(p, in, k, count, out);  // the last 1-7 points, four at a time
}


#endif


}  // namespace ugv::terrain::detail
