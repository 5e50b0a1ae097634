#include "spread_corners.hpp"

#include "float8.hpp"

namespace ugv::terrain::detail {

void spread_corners_generic(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                            const double (*rows)[kCornerComponents], const double (*columns)[kCornerComponents])
{
    for (int a = 0; a < 4; ++a) {
        double* line = corners + static_cast<std::size_t>(at_row[a]) * stride * kCornerComponents;
        for (int b = 0; b < 4; ++b) {
            double* c = line + static_cast<std::size_t>(at_column[b]) * kCornerComponents;
            for (int k = 0; k < kCornerComponents; ++k) c[k] += rows[a][k] * columns[b][k];
        }
    }
}

#if defined(UGV_TERRAIN_HAVE_AVX2)

UGV_AVX2 void spread_corners_avx2(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                                  const double (*rows)[kCornerComponents], const double (*columns)[kCornerComponents])
{
    __m256d column_lo[4], column_hi[4];
    for (int b = 0; b < 4; ++b) {
        column_lo[b] = _mm256_loadu_pd(columns[b]);
        column_hi[b] = _mm256_loadu_pd(columns[b] + 4);
    }
    for (int a = 0; a < 4; ++a) {
        const __m256d row_lo = _mm256_loadu_pd(rows[a]), row_hi = _mm256_loadu_pd(rows[a] + 4);
        double* line = corners + static_cast<std::size_t>(at_row[a]) * stride * kCornerComponents;
        for (int b = 0; b < 4; ++b) {
            double* c = line + static_cast<std::size_t>(at_column[b]) * kCornerComponents;
            _mm256_store_pd(c, _mm256_fmadd_pd(row_lo, column_lo[b], _mm256_load_pd(c)));
            _mm256_store_pd(c + 4, _mm256_fmadd_pd(row_hi, column_hi[b], _mm256_load_pd(c + 4)));
        }
    }
}

#endif

}  // namespace ugv::terrain::detail
