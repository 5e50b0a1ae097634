#include "spread_corners.hpp"

#include "float8.hpp"

namespace ugv::terrain::detail {

void spread_corners_generic(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                            const double* weight, const CornerAxis& x, const CornerAxis& y)
{
    const double w = weight[0], wz = weight[1], wz2 = weight[2];
    double rows[4][kCornerComponents], columns[4][kCornerComponents];
    for (int a = 0; a < 4; ++a) {
        const double f = x.fraction[a], e = y.fraction[a];
        double* r = rows[a];
        r[0] = w * f;
        r[1] = wz * f;
        r[2] = wz2 * f;
        r[3] = x.count[a];
        r[4] = w * x.moment[a];
        r[5] = w * x.moment2[a];
        r[6] = r[7] = w * f;
        double* c = columns[a];
        c[0] = c[1] = c[2] = c[4] = c[5] = e;
        c[3] = y.count[a];
        c[6] = y.moment[a];
        c[7] = y.moment2[a];
    }
    for (int a = 0; a < 4; ++a) {
        double* line = corners + static_cast<std::size_t>(at_row[a]) * stride * kCornerComponents;
        for (int b = 0; b < 4; ++b) {
            double* c = line + static_cast<std::size_t>(at_column[b]) * kCornerComponents;
            for (int k = 0; k < kCornerComponents; ++k) c[k] += rows[a][k] * columns[b][k];
        }
    }
}

void spread_corners_centred_generic(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                                    const double* weight, const CornerAxis& x, const CornerAxis& y)
{
    constexpr int k4 = kCentredCornerComponents;
    for (int a = 0; a < 4; ++a) {
        const double f = x.fraction[a];
        const double r[k4] = {weight[0] * f, weight[1] * f, weight[2] * f, x.count[a]};
        double* line = corners + static_cast<std::size_t>(at_row[a]) * stride * k4;
        for (int b = 0; b < 4; ++b) {
            const double e = y.fraction[b];
            double* c = line + static_cast<std::size_t>(at_column[b]) * k4;
            c[0] += r[0] * e;
            c[1] += r[1] * e;
            c[2] += r[2] * e;
            c[3] += r[3] * y.count[b];
        }
    }
}

#if defined(UGV_TERRAIN_HAVE_AVX2)

UGV_AVX2 void spread_corners_centred_avx2(double* corners, std::size_t stride, const int* at_row,
                                          const int* at_column, const double* weight, const CornerAxis& x,
                                          const CornerAxis& y)
{
    constexpr int k4 = kCentredCornerComponents;
    const __m256d weight_lo = _mm256_set_pd(1.0, weight[2], weight[1], weight[0]);
    __m256d column[4];
    std::size_t column_at[4];
    for (int b = 0; b < 4; ++b) {
        column_at[b] = static_cast<std::size_t>(at_column[b]) * k4;
        column[b] = _mm256_blend_pd(_mm256_set1_pd(y.fraction[b]), _mm256_set1_pd(y.count[b]), 0x8);
    }
    for (int a = 0; a < 4; ++a) {
        const __m256d row =
            _mm256_mul_pd(weight_lo, _mm256_blend_pd(_mm256_set1_pd(x.fraction[a]), _mm256_set1_pd(x.count[a]), 0x8));
        double* line = corners + static_cast<std::size_t>(at_row[a]) * stride * k4;
        for (int b = 0; b < 4; ++b) {
            double* c = line + column_at[b];
            _mm256_store_pd(c, _mm256_fmadd_pd(row, column[b], _mm256_load_pd(c)));
        }
    }
}

UGV_AVX2 void spread_corners_avx2(double* corners, std::size_t stride, const int* at_row, const int* at_column,
                                  const double* weight, const CornerAxis& x, const CornerAxis& y)
{
    // _mm256_set_pd lists the lanes from the highest.
    const __m256d weight_lo = _mm256_set_pd(1.0, weight[2], weight[1], weight[0]);
    const __m256d weight_hi = _mm256_set1_pd(weight[0]);
    __m256d column_lo[4], column_hi[4];
    // The column offsets once, not per corner (16 sign extensions and shifts otherwise).
    std::size_t column_at[4];
    for (int b = 0; b < 4; ++b) column_at[b] = static_cast<std::size_t>(at_column[b]) * kCornerComponents;
    for (int b = 0; b < 4; ++b) {
        const __m256d e = _mm256_set1_pd(y.fraction[b]);
        column_lo[b] = _mm256_blend_pd(e, _mm256_set1_pd(y.count[b]), 0x8);
        column_hi[b] = _mm256_set_pd(y.moment2[b], y.moment[b], y.fraction[b], y.fraction[b]);
    }
    for (int a = 0; a < 4; ++a) {
        const __m256d f = _mm256_set1_pd(x.fraction[a]);
        const __m256d row_lo = _mm256_mul_pd(weight_lo, _mm256_blend_pd(f, _mm256_set1_pd(x.count[a]), 0x8));
        const __m256d row_hi =
            _mm256_mul_pd(weight_hi, _mm256_set_pd(x.fraction[a], x.fraction[a], x.moment2[a], x.moment[a]));
        double* line = corners + static_cast<std::size_t>(at_row[a]) * stride * kCornerComponents;
        for (int b = 0; b < 4; ++b) {
            double* c = line + column_at[b];
            _mm256_store_pd(c, _mm256_fmadd_pd(row_lo, column_lo[b], _mm256_load_pd(c)));
            _mm256_store_pd(c + 4, _mm256_fmadd_pd(row_hi, column_hi[b], _mm256_load_pd(c + 4)));
        }
    }
}

#endif

}  // namespace ugv::terrain::detail
