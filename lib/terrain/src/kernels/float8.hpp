// 8-float AVX2 vectors for the hot loops' second build (kernel_table.hpp). Everything here is
// compiled for AVX2 and FMA by a per-function target attribute, so a translation unit
// built for the baseline can hold it; it must only run where best_simd_level() is avx2. Only
// on x86-64 with GCC or Clang (UGV_TERRAIN_HAVE_AVX2). Private to the library.
#pragma once

#include <cstdint>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define UGV_TERRAIN_HAVE_AVX2 1
#include <immintrin.h>

#define UGV_AVX2 __attribute__((target("avx2,fma")))

namespace ugv::terrain::detail {

using Float8 = float __attribute__((vector_size(32)));
using Int8 = int32_t __attribute__((vector_size(32)));

UGV_AVX2 inline Float8 load8(const float* p) { return Float8(_mm256_loadu_ps(p)); }
UGV_AVX2 inline Float8 splat8(float v) { return Float8{} + v; }
// Bit k set where lane k of the mask is set.
UGV_AVX2 inline unsigned lane_bits(const Int8& mask) { return static_cast<unsigned>(_mm256_movemask_ps(__m256(mask))); }

}  // namespace ugv::terrain::detail

#endif
