#include "multibody/linearization.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace mbfe::runtime {

Eigen::MatrixXd rhs_jacobian(PartitionedSystem& system, double t, const Eigen::VectorXd& y,
                             const LinearizationOptions& options) {
  const int n = system.size();
  const int nz = n / 2;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  a.topRightCorner(nz, nz).setIdentity();
  Eigen::VectorXd yp = y, fp(n), fm(n);
  for (int j = 0; j < n; ++j) {
    const double h = options.rel_step * std::max(1.0, std::abs(y[j]));
    yp[j] = y[j] + h;
    system.rhs(t, yp, fp);
    yp[j] = y[j] - h;
    system.rhs(t, yp, fm);
    yp[j] = y[j];
    a.col(j).tail(nz) = (fp.tail(nz) - fm.tail(nz)) / (2.0 * h);
  }
  system.rhs(t, y, fp);  // leave the Newton start at y
  return a;
}

StateSpectrum dense_spectrum(const Eigen::MatrixXd& a) {
  Eigen::EigenSolver<Eigen::MatrixXd> eig(a, /*computeEigenvectors=*/false);
  std::vector<std::complex<double>> ev(eig.eigenvalues().data(),
                                       eig.eigenvalues().data() + eig.eigenvalues().size());
  return spectrum_from_eigenvalues(std::move(ev));
}

StateSpectrum linearized_spectrum(const std::shared_ptr<CoupledDynamics>& dynamics, double t,
                                  const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                  const LinearizationOptions& options) {
  PartitionOptions po;
  po.closure_tol = options.closure_tol;
  PartitionedSystem system(dynamics, po);
  const Eigen::VectorXd y0 = system.initial_state(t, q, qd);
  return dense_spectrum(rhs_jacobian(system, t, y0, options));
}

}  // namespace mbfe::runtime
