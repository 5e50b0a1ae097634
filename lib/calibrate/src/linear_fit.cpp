#include "ugv/calibrate/linear_fit.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <vector>

namespace ugv::calibrate {

namespace {

LinearFit solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b)
{
    LinearFit f;
    const auto n = a.rows(), p = a.cols();
    if (n <= p) return f;
    const Eigen::MatrixXd normal = a.transpose() * a;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(normal);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return f;
    // Dependent columns: a pivot tiny against the largest diagonal element.
    if (ldlt.vectorD().minCoeff() <= 1e-12 * normal.diagonal().maxCoeff()) return f;
    f.value = ldlt.solve(a.transpose() * b);
    const double rss = (a * f.value - b).squaredNorm();
    f.rms = std::sqrt(rss / static_cast<double>(n));
    const Eigen::MatrixXd inverse = ldlt.solve(Eigen::MatrixXd::Identity(p, p));
    f.sigma = (inverse.diagonal() * (rss / static_cast<double>(n - p))).cwiseSqrt();
    f.rows = static_cast<std::size_t>(n);
    f.ok = f.value.allFinite() && f.sigma.allFinite();
    return f;
}

}  // namespace

LinearFit fit_linear(const Eigen::MatrixXd& rows, const Eigen::VectorXd& targets, double gate_sigmas)
{
    LinearFit first = solve(rows, targets);
    if (!first.ok || gate_sigmas <= 0 || first.rms <= 0) return first;
    const Eigen::VectorXd residual = rows * first.value - targets;
    std::vector<Eigen::Index> keep;
    for (Eigen::Index i = 0; i < residual.size(); ++i)
        if (std::abs(residual[i]) <= gate_sigmas * first.rms) keep.push_back(i);
    if (keep.size() == static_cast<std::size_t>(rows.rows())) return first;
    Eigen::MatrixXd a(static_cast<Eigen::Index>(keep.size()), rows.cols());
    Eigen::VectorXd b(static_cast<Eigen::Index>(keep.size()));
    for (std::size_t k = 0; k < keep.size(); ++k) {
        a.row(static_cast<Eigen::Index>(k)) = rows.row(keep[k]);
        b[static_cast<Eigen::Index>(k)] = targets[keep[k]];
    }
    LinearFit second = solve(a, b);
    return second.ok ? second : first;
}

}  // namespace ugv::calibrate
