// 4-lane vectors for the hot loops (GCC/Clang vector extensions: SSE on x86-64 without
// -march, NEON on ARM, scalar code elsewhere). Each lane computes the scalar expression's
// IEEE result, so values do not depend on the vectors.
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace ugv::simd {

using Float4 = float __attribute__((vector_size(16)));
using Int4 = int32_t __attribute__((vector_size(16)));
using Double2 = double __attribute__((vector_size(16)));

inline Float4 load4(const float* p)
{
    Float4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

inline Int4 load4(const int32_t* p)
{
    Int4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

inline void store4(float* p, Float4 v) { std::memcpy(p, &v, sizeof v); }

inline Float4 splat(float v) { return Float4{v, v, v, v}; }

inline Float4 nan4() { return splat(std::numeric_limits<float>::quiet_NaN()); }

// Bit k set where lane k of the mask is set (SSE: one movmskps).
inline unsigned lane_bits(Int4 mask)
{
#if defined(__SSE__)
    return static_cast<unsigned>(_mm_movemask_ps(__m128(mask)));
#else
    return (mask[0] & 1u) | (mask[1] & 2u) | (mask[2] & 4u) | (mask[3] & 8u);
#endif
}

// Towards zero, as int; any int for a value that has none (out of range, or not a number).
inline Int4 truncate_to_int(Float4 v)
{
#if defined(__SSE2__)
    return Int4(_mm_cvttps_epi32(__m128(v)));
#else
    const Float4 lowest = splat(-2.0e9f), highest = splat(2.0e9f);
    v = v > lowest ? v : lowest;  // false for NaN: converted from -2e9
    v = v < highest ? v : highest;
    return __builtin_convertvector(v, Int4);
#endif
}

// The 4x4 transpose: rows a, b, c, d in, columns out (in place).
inline void transpose4(Float4& a, Float4& b, Float4& c, Float4& d)
{
    const Float4 ab_lo = __builtin_shufflevector(a, b, 0, 4, 1, 5);  // a0 b0 a1 b1
    const Float4 ab_hi = __builtin_shufflevector(a, b, 2, 6, 3, 7);  // a2 b2 a3 b3
    const Float4 cd_lo = __builtin_shufflevector(c, d, 0, 4, 1, 5);
    const Float4 cd_hi = __builtin_shufflevector(c, d, 2, 6, 3, 7);
    a = __builtin_shufflevector(ab_lo, cd_lo, 0, 1, 4, 5);
    b = __builtin_shufflevector(ab_lo, cd_lo, 2, 3, 6, 7);
    c = __builtin_shufflevector(ab_hi, cd_hi, 0, 1, 4, 5);
    d = __builtin_shufflevector(ab_hi, cd_hi, 2, 3, 6, 7);
}

}  // namespace ugv::simd
