#include "turn_end.hpp"

#include <cstddef>

#include "float4.hpp"
#include "ugv/terrain/simd.hpp"

namespace ugv::terrain::detail {

namespace {

// The 32 known bits of cells j .. j + 31 of a row (j a multiple of 32), byte by byte:
// the same on either byte order.
inline uint32_t held_bits(const uint8_t* row, int j)
{
    const uint8_t* b = row + j / 8;
    return static_cast<uint32_t>(b[0]) | static_cast<uint32_t>(b[1]) << 8 | static_cast<uint32_t>(b[2]) << 16 |
           static_cast<uint32_t>(b[3]) << 24;
}

// Bit q set where counts[q] is 0, for q < left (at most 32).
uint32_t zero_bits_scalar(const uint32_t* counts, int left)
{
    uint32_t bits = 0;
    for (int q = 0; q < left && q < 32; ++q)
        if (counts[q] == 0) bits |= 1u << q;
    return bits;
}

// Bit q set where counts[q] is 0, q < 32.
uint32_t zero_bits32_generic(const uint32_t* counts)
{
    uint32_t bits = 0;
    for (int q = 0; q < 32; q += 4) {
        const Int4 c = load4(reinterpret_cast<const int32_t*>(counts + q));
        bits |= lane_bits(c == 0) << q;
    }
    return bits;
}

// The loop of both builds: 32 cells at a time; a word of held bits that is 0 (unknown
// ground then, the most of a real map's) reads no counts.
template <uint32_t (*ZeroBits32)(const uint32_t*)>
inline __attribute__((always_inline)) void clear_unlanded(CellSums* working, const uint32_t* counts,
                                                          const uint8_t* held, int nx, int ny)
{
    const std::size_t row_bytes = static_cast<std::size_t>(held_row_bytes(ny));
    const std::size_t cells = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
    for (int pr = 0; pr < nx; ++pr) {
        const std::size_t first = static_cast<std::size_t>(pr) * static_cast<std::size_t>(ny);
        const uint8_t* row = held + static_cast<std::size_t>(pr) * row_bytes;
        for (int j = 0; j < ny; j += 32) {
            const uint32_t h = held_bits(row, j);
            if (h == 0) continue;
            const std::size_t at = first + static_cast<std::size_t>(j);
            // Near the map's end, where 32 counts would read past it, one by one.
            const uint32_t zero = at + 32 <= cells ? ZeroBits32(counts + at) : zero_bits_scalar(counts + at, ny - j);
            for (uint32_t clear = zero & h; clear != 0; clear &= clear - 1)
                working[at + static_cast<std::size_t>(__builtin_ctz(clear))] = CellSums{};
        }
    }
}

}  // namespace

void clear_unlanded_generic(CellSums* working, const uint32_t* counts, const uint8_t* held, int nx, int ny)
{
    clear_unlanded<zero_bits32_generic>(working, counts, held, nx, ny);
}

#if defined(UGV_TERRAIN_HAVE_AVX2)

namespace {

// Bit q set where counts[q] is 0, q < 32: four compares packed to bytes (the packs work
// within 128-bit halves, which the permutation puts back in order) and one byte mask.
UGV_AVX2 uint32_t zero_bits32_avx2(const uint32_t* counts)
{
    const __m256i* c = reinterpret_cast<const __m256i*>(counts);
    const __m256i zero = _mm256_setzero_si256();
    const __m256i a0 = _mm256_cmpeq_epi32(_mm256_loadu_si256(c), zero);
    const __m256i a1 = _mm256_cmpeq_epi32(_mm256_loadu_si256(c + 1), zero);
    const __m256i a2 = _mm256_cmpeq_epi32(_mm256_loadu_si256(c + 2), zero);
    const __m256i a3 = _mm256_cmpeq_epi32(_mm256_loadu_si256(c + 3), zero);
    // Bytes, in 4-byte words: a0[0..3] a1[0..3] a2[0..3] a3[0..3] | a0[4..7] a1[4..7] a2[4..7] a3[4..7].
    const __m256i bytes = _mm256_packs_epi16(_mm256_packs_epi32(a0, a1), _mm256_packs_epi32(a2, a3));
    const __m256i in_order = _mm256_permutevar8x32_epi32(bytes, _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7));
    return static_cast<uint32_t>(_mm256_movemask_epi8(in_order));
}

}  // namespace

UGV_AVX2 void clear_unlanded_avx2(CellSums* working, const uint32_t* counts, const uint8_t* held, int nx, int ny)
{
    clear_unlanded<zero_bits32_avx2>(working, counts, held, nx, ny);
}

#endif

ClearUnlanded clear_unlanded_kernel()
{
#if defined(UGV_TERRAIN_HAVE_AVX2)
    if (simd_level() == SimdLevel::avx2) return clear_unlanded_avx2;
#endif
    return clear_unlanded_generic;
}

}  // namespace ugv::terrain::detail
