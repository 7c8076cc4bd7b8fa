#include "runtime/multibody/rigid_tangents.h"

#include <cmath>
#include <vector>

#include "runtime/multibody/rigid_system.h"

namespace mbfe::runtime {

namespace {

// Central-difference step relative to the coordinate's size: the cube root
// of machine epsilon balances truncation (h^2) against round-off (eps / h).
constexpr double kDifferenceStep = 6e-6;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace

void rigid_dynamics_tangents(const mbfe_model_v1& kernels, double t, const double* q, const double* v, const double* a,
                             Eigen::MatrixXd& K, Eigen::MatrixXd& C) {
  const int nb = kernels.num_coordinates;
  if (kernels.dynamics_jacobians != nullptr) {
    std::vector<double> jk(static_cast<std::size_t>(nb * nb)), jc(jk.size());
    kernels.dynamics_jacobians(q, v, a, t, jk.data(), jc.data());
    K = Eigen::Map<const RowMajor>(jk.data(), nb, nb);
    C = Eigen::Map<const RowMajor>(jc.data(), nb, nb);
    return;
  }
  // tau = M a + F - Q at the fixed a, by central differences.
  K.setZero(nb, nb);
  C.setZero(nb, nb);
  RowMajor mb(nb, nb);
  Eigen::VectorXd f(nb), qf(nb), plus(nb), minus(nb);
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(q, nb), xd = Eigen::Map<const Eigen::VectorXd>(v, nb);
  const Eigen::Map<const Eigen::VectorXd> ab(a, nb);
  auto tau = [&](Eigen::VectorXd& out) {
    evaluate_dynamics(kernels, x.data(), xd.data(), t, mb.data(), f.data(), qf.data());
    out = mb * ab + f - qf;
  };
  for (int j = 0; j < nb; ++j) {
    for (Eigen::VectorXd* y : {&x, &xd}) {
      const double y0 = (*y)[j];
      const double h = kDifferenceStep * (1.0 + std::abs(y0));
      (*y)[j] = y0 + h;
      tau(plus);
      (*y)[j] = y0 - h;
      tau(minus);
      (*y)[j] = y0;
      (y == &x ? K : C).col(j) = (plus - minus) / (2.0 * h);
    }
  }
}

}  // namespace mbfe::runtime
