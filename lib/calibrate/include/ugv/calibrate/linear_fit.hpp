// Linear least squares with one outlier gate, for the calibrations' small regressions.
#pragma once

#include <cstddef>

#include <Eigen/Core>

namespace ugv::calibrate {

struct LinearFit
{
    bool ok = false;           // false: too few rows or the columns are dependent
    Eigen::VectorXd value;     // the parameters
    Eigen::VectorXd sigma;     // their formal 1-sigma (residual RMS x sqrt of the inverse's diagonal)
    double rms = 0;            // residual RMS of the rows kept
    std::size_t rows = 0;      // rows kept
};

// Solves rows * p = targets; then drops the rows whose residual is beyond gate_sigmas x RMS
// and solves again (gate_sigmas <= 0: no gate).
LinearFit fit_linear(const Eigen::MatrixXd& rows, const Eigen::VectorXd& targets, double gate_sigmas);

}  // namespace ugv::calibrate
