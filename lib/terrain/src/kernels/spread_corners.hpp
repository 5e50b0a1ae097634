// The corner updates of a spread point in summed-area form (spread_sums.hpp), in two builds:
// 2-double vectors for any CPU, 4-double AVX2/FMA vectors (kernel_table.hpp). Private to
// the library.
#pragma once

#include <cstddef>

namespace ugv::terrain::detail {

// A corner record: 8 doubles (spread_sums.hpp lists them).
constexpr int kCornerComponents = 8;

// corners[(at_row[a] * stride + at_column[b]) * 8 + k] += rows[a][k] * columns[b][k], for
// a, b in 0..3 and k in 0..7. corners is 64-byte aligned.
using SpreadCorners = void (*)(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                               const double (*rows)[kCornerComponents], const double (*columns)[kCornerComponents]);

void spread_corners_generic(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                            const double (*rows)[kCornerComponents], const double (*columns)[kCornerComponents]);
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
void spread_corners_avx2(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                         const double (*rows)[kCornerComponents], const double (*columns)[kCornerComponents]);
#endif

}  // namespace ugv::terrain::detail
