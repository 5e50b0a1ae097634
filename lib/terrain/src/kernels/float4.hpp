// The 4-lane vectors of lib/simd under the names the terrain kernels use (a using-declaration,
// not a directive: float8.hpp's lane_bits(Int8) must overload these, not hide them).
#pragma once

#include "ugv/simd/float4.hpp"

namespace ugv::terrain::detail {

using simd::Float4;
using simd::Int4;
using simd::lane_bits;
using simd::load4;
using simd::splat;
using simd::store4;
using simd::transpose4;
using simd::truncate_to_int;

}  // namespace ugv::terrain::detail
