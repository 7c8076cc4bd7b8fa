#include "runtime/coupled/linearization.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "runtime/coupled/coordinate_partitioning.h"

namespace mbfe::runtime {

Eigen::MatrixXd rhs_jacobian(OdeSystem& system, double t, const Eigen::VectorXd& y,
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
  // A repeated real eigenvalue (the capped modes of an adjusted beam) comes out
  // of the QR iteration as pairs with imaginary parts of rounding size
  // (~1e-14 |lambda|): real, not oscillatory.
  for (auto& l : ev)
    if (std::abs(l.imag()) <= 1e-10 * std::abs(l)) l = {l.real(), 0.0};
  return spectrum_from_eigenvalues(std::move(ev));
}

StateSpectrum linearized_spectrum(OdeSystem& system, double t, const Eigen::VectorXd& y,
                                  const LinearizationOptions& options) {
  return balanced_spectrum(rhs_jacobian(system, t, y, options));
}

StateSpectrum balanced_spectrum(Eigen::MatrixXd a) {
  // Balance [[0, I], [A21, A22]] by the similarity diag(I, sigma I) (rates
  // measured in units of sigma): [[0, sigma I], [A21 / sigma, A22]], with
  // sigma = sqrt(max |A21|) ~ the fastest stiffness frequency. The eigenvalues
  // are the same; the QR iteration's rounding, relative to the largest entry,
  // drops from ~omega_max^2 to ~omega_max, which matters for the capped
  // eigenvalue of the adjusted beams (repeated and nearly critically damped).
  const int nz = static_cast<int>(a.rows()) / 2;
  const double sigma = std::sqrt(a.bottomLeftCorner(nz, nz).cwiseAbs().maxCoeff());
  if (sigma > 0.0 && std::isfinite(sigma)) {
    a.topRightCorner(nz, nz) *= sigma;
    a.bottomLeftCorner(nz, nz) /= sigma;
  }
  return dense_spectrum(a);
}

StateSpectrum linearized_spectrum(const std::shared_ptr<CoupledDynamics>& dynamics, double t,
                                  const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                  const LinearizationOptions& options) {
  PartitionOptions po;
  po.closure_tol = options.closure_tol;
  PartitionedSystem system(dynamics, po);
  const Eigen::VectorXd y0 = system.initial_state(t, q, qd);
  return linearized_spectrum(system, t, y0, options);
}

SplitSpectrum split_growing(const StateSpectrum& spectrum) {
  SplitSpectrum out;
  std::vector<std::complex<double>> limiting;
  for (auto l : spectrum.eigenvalues) {
    if (std::abs(l.real()) <= kRoundingRe * std::abs(l)) l = {0.0, l.imag()};
    if (l.real() > 0.0)
      ++out.growing;
    else
      limiting.push_back(l);
  }
  out.limiting = spectrum_from_eigenvalues(std::move(limiting));
  return out;
}

namespace {

double largest_modulus(const StateSpectrum& spectrum) {
  double largest = 0.0;
  for (const auto& l : spectrum.eigenvalues) largest = std::max(largest, std::abs(l));
  return largest;
}

}  // namespace

StateSpectrum with_zero_modes(const StateSpectrum& spectrum) {
  const double zero = kZeroModeRel * largest_modulus(spectrum);
  std::vector<std::complex<double>> ev = spectrum.eigenvalues;
  for (auto& l : ev)
    if (std::abs(l) <= zero) l = 0.0;
  StateSpectrum out = spectrum_from_eigenvalues(std::move(ev));
  out.complete = spectrum.complete;
  return out;
}

int growing_beyond_noise(const StateSpectrum& spectrum) {
  const double noise = kLinearizationNoiseRel * largest_modulus(spectrum);
  return static_cast<int>(std::count_if(spectrum.eigenvalues.begin(), spectrum.eigenvalues.end(),
                                        [noise](const std::complex<double>& l) { return l.real() > noise; }));
}

}  // namespace mbfe::runtime
