#include "runtime/simulation/static_start.h"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mbfe::runtime {

namespace {

constexpr int kMaxIterations = 50;
// Central differences: the step that balances truncation (h^2) against
// round-off (eps / h), relative to the coordinate's size.
constexpr double kRelativeStep = 6e-6;
// Converged once the update is round-off of the coordinates (1e-12 relative)...
constexpr double kStepTolerance = 1e-12;
// ... or the residual has fallen by 1e-12 from its scale at the start.
constexpr double kResidualReduction = 1e-12;
// A Jacobian column space thinner than this (relative to its largest singular
// value) is a mechanism: a direction with no stiffness.
constexpr double kMechanismRcond = 1e-10;

}  // namespace

StaticSolution solve_static(const StaticResidualFn& residual, const Eigen::VectorXd& x0,
                            const std::vector<std::string>& names) {
  const Eigen::Index n = x0.size();
  StaticSolution out;
  out.x = x0;
  Eigen::VectorXd r, rp, rm;
  residual(out.x, r);
  const double scale = std::max(r.cwiseAbs().maxCoeff(), 1e-300);
  Eigen::MatrixXd J(r.size(), n);
  for (int it = 0; it < kMaxIterations; ++it) {
    out.iterations = it;
    out.residual = r.cwiseAbs().maxCoeff();
    if (out.residual <= kResidualReduction * scale || n == 0) return out;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double h = kRelativeStep * std::max(1.0, std::abs(out.x[j]));
      Eigen::VectorXd x = out.x;
      x[j] += h;
      residual(x, rp);
      x[j] = out.x[j] - h;
      residual(x, rm);
      J.col(j) = (rp - rm) / (2.0 * h);
    }
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(J);
    qr.setThreshold(kMechanismRcond);
    if (qr.rank() < n) {
      // The unknown that carries most of the direction without stiffness.
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
      Eigen::Index worst = 0;
      svd.matrixV().col(n - 1).cwiseAbs().maxCoeff(&worst);
      std::ostringstream os;
      os << "the structure is a mechanism: nothing holds '" << names[static_cast<std::size_t>(worst)]
         << "' in place (the static stiffness has rank " << qr.rank() << " of " << n
         << "); support it, or start from `initial:` as written";
      throw std::runtime_error(os.str());
    }
    const Eigen::VectorXd dx = qr.solve(r);
    out.x -= dx;
    residual(out.x, r);
    if (!r.allFinite()) break;
    if (dx.cwiseAbs().maxCoeff() <= kStepTolerance * (1.0 + out.x.cwiseAbs().maxCoeff())) {
      out.iterations = it + 1;
      out.residual = r.cwiseAbs().maxCoeff();
      return out;
    }
  }
  std::ostringstream os;
  os << "the static equilibrium at t = 0 did not converge in " << kMaxIterations
     << " Newton iterations (largest residual " << r.cwiseAbs().maxCoeff()
     << "); start from `initial:` as written, or from a state closer to equilibrium";
  throw std::runtime_error(os.str());
}

}  // namespace mbfe::runtime
