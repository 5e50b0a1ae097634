// The corner updates of a spread point in summed-area form (spread_sums.hpp), in two builds:
// 2-double vectors for any CPU, 4-double AVX2/FMA vectors (kernel_table.hpp). Private to
// the library.
#pragma once

#include <cstddef>

namespace ugv::terrain::detail {

// A corner record: 8 doubles (spread_sums.hpp lists them); the centred form's, the first 4.
constexpr int kCornerComponents = 8;
constexpr int kCentredCornerComponents = 4;

// One axis of a footprint: each of its four corners' entries (spread_sums.hpp).
struct CornerAxis
{
    double fraction[4], count[4], moment[4], moment2[4];
};

// corners[(at_row[a] * stride + at_column[b]) * 8 + k] += rows[a][k] * columns[b][k], for
// a, b in 0..3 and k in 0..7, where with w = weight[0], wz = weight[1], wz2 = weight[2]:
//   rows[a]    = (w f, wz f, wz2 f, count, w moment, w moment2, w f, w f)  of x's corner a,
//   columns[b] = (e, e, e, count, e, e, moment, moment2)                    of y's corner b
// (f, e: the fractions). The records are built inside, in registers: building them in
// memory cost as much as the updates. corners is 64-byte aligned.
using SpreadCorners = void (*)(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                               const double* weight, const CornerAxis& x, const CornerAxis& y);

// The centred form's: the same with records of the first 4 components (w, wz, wz2, count).
void spread_corners_centred_generic(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                                    const double* weight, const CornerAxis& x, const CornerAxis& y);

void spread_corners_generic(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                            const double* weight, const CornerAxis& x, const CornerAxis& y);
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
void spread_corners_avx2(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                         const double* weight, const CornerAxis& x, const CornerAxis& y);
void spread_corners_centred_avx2(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                                 const double* weight, const CornerAxis& x, const CornerAxis& y);
#endif

}  // namespace ugv::terrain::detail
