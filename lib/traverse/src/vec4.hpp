// GCC/Clang vector extensions of 4 lanes, shared by the classifier's loops and the kernels
// (what each lane computes is the scalar expression's IEEE result, so the values do not
// depend on the vectors).
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace ugv::traverse::vec4 {

using F4 = float __attribute__((vector_size(16)));
using I4 = int32_t __attribute__((vector_size(16)));
using D2 = double __attribute__((vector_size(16)));

inline F4 load4(const float* p)
{
    F4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline I4 load4(const int32_t* p)
{
    I4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline void store4(float* p, F4 v) { std::memcpy(p, &v, sizeof v); }
inline F4 nan4()
{
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    return F4{kNaN, kNaN, kNaN, kNaN};
}
inline D2 low2(F4 v) { return D2{v[0], v[1]}; }
inline D2 high2(F4 v) { return D2{v[2], v[3]}; }
inline F4 abs4(F4 v) { return (F4)((I4)v & I4{INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX}); }
// A comparison's mask as bits, lane e in bit e (SSE: one movmskps).
inline unsigned lane_bits(I4 m)
{
#if defined(__SSE2__)
    return static_cast<unsigned>(_mm_movemask_ps((__m128)m));
#else
    return (m[0] & 1u) | (m[1] & 2u) | (m[2] & 4u) | (m[3] & 8u);
#endif
}

}  // namespace ugv::traverse::vec4
