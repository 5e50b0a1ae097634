// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, as zlib computes it).
//
// zlib 1.2.13 computes it a word at a time; on x86-64 with PCLMULQDQ the bulk is folded
// 64 bytes a step with carry-less multiplications (the folding constants are x^k mod P for
// the fold distances) and reduced to 32 bits by Barrett reduction; zlib takes the ragged tail.
// zlib's function is the reference the tests compare with.
#include "ugv/foxglove/mcap_writer.hpp"

#include <zlib.h>

#include <algorithm>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define UGV_CRC32_CLMUL 1
#endif

namespace ugv::foxglove {

uint32_t crc32_reference(const uint8_t* data, std::size_t size, uint32_t crc)
{
    // zlib's crc32 takes uInt lengths: feed it in pieces.
    while (size > 0) {
        const std::size_t n = std::min<std::size_t>(size, 1u << 30);
        crc = static_cast<uint32_t>(::crc32(crc, data, static_cast<uInt>(n)));
        data += n;
        size -= n;
    }
    return crc;
}

#ifdef UGV_CRC32_CLMUL
namespace {

// x^k mod P (bit-reflected, 33 bits) for folding 512 bits (k1, k2), 128 bits (k3, k4) and
// 64 -> 32 bits (k5); P' and mu for the Barrett reduction.
constexpr long long k1 = 0x154442bd4, k2 = 0x1c6e41596;
constexpr long long k3 = 0x1751997d0, k4 = 0x0ccaa009e;
constexpr long long k5 = 0x163cd6124;
constexpr long long poly = 0x1db710641, mu = 0x1f7011641;

__attribute__((target("pclmul,sse4.1"))) inline __m128i fold(__m128i x, __m128i k)
{
    return _mm_xor_si128(_mm_clmulepi64_si128(x, k, 0x00), _mm_clmulepi64_si128(x, k, 0x11));
}

__attribute__((target("pclmul,sse4.1"))) inline __m128i load(const uint8_t* p)
{
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
}

// The raw CRC register (no pre- or post-inversion) over size bytes, size a multiple of 16
// and at least 64.
__attribute__((target("pclmul,sse4.1"))) uint32_t fold_crc(const uint8_t* p, std::size_t size, uint32_t crc)
{
    __m128i x0 = _mm_xor_si128(load(p), _mm_cvtsi32_si128(static_cast<int>(crc)));
    __m128i x1 = load(p + 16), x2 = load(p + 32), x3 = load(p + 48);
    p += 64;
    size -= 64;
    const __m128i k12 = _mm_set_epi64x(k2, k1);
    for (; size >= 64; p += 64, size -= 64) {
        x0 = _mm_xor_si128(fold(x0, k12), load(p));
        x1 = _mm_xor_si128(fold(x1, k12), load(p + 16));
        x2 = _mm_xor_si128(fold(x2, k12), load(p + 32));
        x3 = _mm_xor_si128(fold(x3, k12), load(p + 48));
    }
    const __m128i k34 = _mm_set_epi64x(k4, k3);
    x0 = _mm_xor_si128(fold(x0, k34), x1);
    x0 = _mm_xor_si128(fold(x0, k34), x2);
    x0 = _mm_xor_si128(fold(x0, k34), x3);
    for (; size >= 16; p += 16, size -= 16) x0 = _mm_xor_si128(fold(x0, k34), load(p));

    // 128 -> 64 bits (appending 32 zero bits), then 64 -> 32.
    const __m128i mask32 = _mm_set_epi32(0, 0, 0, -1);
    x0 = _mm_xor_si128(_mm_srli_si128(x0, 8), _mm_clmulepi64_si128(k34, x0, 0x01));
    x0 = _mm_xor_si128(_mm_srli_si128(x0, 4),
                       _mm_clmulepi64_si128(_mm_and_si128(x0, mask32), _mm_set_epi64x(0, k5), 0x00));
    const __m128i barrett = _mm_set_epi64x(mu, poly);
    __m128i t = _mm_clmulepi64_si128(_mm_and_si128(x0, mask32), barrett, 0x10);
    t = _mm_clmulepi64_si128(_mm_and_si128(t, mask32), barrett, 0x00);
    return static_cast<uint32_t>(_mm_extract_epi32(_mm_xor_si128(t, x0), 1));
}

const bool has_clmul = __builtin_cpu_supports("pclmul") && __builtin_cpu_supports("sse4.1");

}  // namespace
#endif

uint32_t crc32(const uint8_t* data, std::size_t size, uint32_t crc)
{
#ifdef UGV_CRC32_CLMUL
    if (has_clmul && size >= 64) {
        const std::size_t bulk = size & ~std::size_t{15};
        crc = ~fold_crc(data, bulk, ~crc);
        data += bulk;
        size -= bulk;
    }
#endif
    return crc32_reference(data, size, crc);
}

}  // namespace ugv::foxglove
