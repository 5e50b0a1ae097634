#include <cmath>

#include <Eigen/Dense>

#include "ugv/traverse/cell_classifier.hpp"

namespace ugv::traverse {

double slope_reference_deg(const TerrainGrid& g, const std::vector<uint8_t>& counts, int i, int j, int h)
{
    // z = a + b x + c y over the window's counted cells, x and y in metres from (i, j).
    Eigen::MatrixXd A(0, 3);
    Eigen::VectorXd z(0);
    int n = 0;
    for (int p = std::max(0, i - h); p <= std::min(g.nx - 1, i + h); ++p)
        for (int q = std::max(0, j - h); q <= std::min(g.ny - 1, j + h); ++q) {
            const std::size_t k = static_cast<std::size_t>(p) * g.ny + q;
            if (!counts[k]) continue;
            A.conservativeResize(n + 1, 3);
            z.conservativeResize(n + 1);
            A.row(n) << 1.0, (p - i) * g.resolution_m, (q - j) * g.resolution_m;
            z(n) = g.mean_z_m[k];
            ++n;
        }
    if (n < 0.5 * (2 * h + 1) * (2 * h + 1)) return NAN;
    const Eigen::Matrix3d ata = A.transpose() * A;
    if (std::abs(ata.determinant()) < 1e-12) return NAN;
    const Eigen::Vector3d coef = ata.ldlt().solve(A.transpose() * z);
    return std::atan(std::hypot(coef(1), coef(2))) * 180.0 / M_PI;
}

}  // namespace ugv::traverse
