#include "runtime/integrators/ode_system.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mbfe::runtime {

// Generic fallback: forward-difference Jacobian and a dense LU, both formed on
// every call. Systems that know their Jacobian (every linear one) override this.
void OdeSystem::solve_shifted(double t, const Eigen::VectorXd& y, double c, const Eigen::VectorXd& b,
                              Eigen::VectorXd& x) {
  const int n = size();
  Eigen::VectorXd f0(n), f1(n), yp = y;
  rhs(t, y, f0);
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
  const double sqrt_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  for (int j = 0; j < n; ++j) {
    const double dy = sqrt_eps * std::max(1.0, std::abs(y[j]));
    yp[j] = y[j] + dy;
    rhs(t, yp, f1);
    yp[j] = y[j];
    a.col(j) -= (c / dy) * (f1 - f0);
  }
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
  x = lu.solve(b);
  if (!x.allFinite())
    throw std::runtime_error("implicit step: the matrix I - c J is singular (c = " + std::to_string(c) +
                             ")");
}

}  // namespace mbfe::runtime
