#include "runtime/coupled/tangent_spectrum.h"

#include <Spectra/GenEigsRealShiftSolver.h>
#include <Spectra/GenEigsSolver.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/coupled/linearization.h"

namespace mbfe::runtime {

namespace {

// Arnoldi's convergence test: an eigenvalue is accepted when its Ritz
// residual is below this share of |lambda|. The limits come out to about 4
// digits (the ten-span catenary's RK4 limit moves by 2e-4 between 1e-6 and
// 1e-10, its top being ten nearly equal copies of one span's), and each
// decade tighter costs about twice the products there (docs/performance.md).
constexpr double kArnoldiTol = 1e-6;
// Restarts allowed before giving up; the shipped catenaries converge in tens
// to about two hundred.
constexpr int kArnoldiMaxRestarts = 2000;
// Krylov subspace of 2 nev + 1 vectors (ARPACK's advice), at least 40: the top
// of a beam mesh's spectrum is a dense cluster, and a wider subspace separates
// it in fewer restarts.
int subspace_size(int nev, int n) { return std::min(n, std::max(2 * nev + 1, 40)); }

// A zero mode of the tangents' A is exactly zero but for round-off: a simple
// one comes out at ~eps s (s ~ omega_max, the balancing scale below), a
// defective pair (a free coordinate with neither stiffness nor damping:
// z'' = 0, a Jordan block) splits into +-sqrt(eps) s ~ 1e-8 s (1.1e-8
// measured on a free slider beside the moving-mass bridge). Eigenvalues below
// this share of s are zero modes. A physical mode that slow turns by under
// 3e-6 rad per step at RK4's limit (~2.8 / s), and an undamped one grows
// under forward Euler by a factor 1 + 4e-12 a step: nothing a limit is about.
constexpr double kZeroModeScaleRel = 1e-6;

// When A is singular (a zero mode: K_t has a null space) the bottom end is
// searched about this negative real shift, relative to the largest |lambda|:
// far below any physical mode yet far above the LU's round-off, and on the
// stable side so that no eigenvalue sits on it.
constexpr double kSingularShiftRel = 1e-9;

// Arnoldi works on the balanced D^-1 A D, D = diag(I, s I) (rates in units of
// s ~ omega_max, as dense_spectrum's balancing): the same eigenvalues, but an
// undamped mode's eigenvector [x; lambda x / s] has parts of one size, and a
// Ritz residual of 1e-6 |lambda| then moves the eigenvalue by about as much
// (unbalanced, the vehicle's fastest pair moved by 2e-4 |lambda|).
struct StateProduct {
  using Scalar = double;
  const StateOperator* tangents;
  double s = 1.0;
  mutable Eigen::VectorXd scaled;
  Eigen::Index rows() const { return 2 * tangents->size(); }
  Eigen::Index cols() const { return rows(); }
  void perform_op(const double* x, double* y) const {
    const Eigen::Index n = tangents->size();
    scaled = Eigen::Map<const Eigen::VectorXd>(x, 2 * n);
    scaled.tail(n) *= s;
    tangents->apply_state_matrix(scaled.data(), y);
    Eigen::Map<Eigen::VectorXd>(y + n, n) /= s;
  }
};

struct ShiftedSolve {
  using Scalar = double;
  StateOperator* tangents;
  double s = 1.0;
  bool factored = false;  // at tangents->shift() already
  mutable Eigen::VectorXd scaled;
  Eigen::Index rows() const { return 2 * tangents->size(); }
  Eigen::Index cols() const { return rows(); }
  void set_shift(const double& sigma) {
    if (!(factored && sigma == tangents->shift())) tangents->factorize_shifted(sigma);
    factored = true;
  }
  void perform_op(const double* x, double* y) const {
    const Eigen::Index n = tangents->size();
    scaled = Eigen::Map<const Eigen::VectorXd>(x, 2 * n);
    scaled.tail(n) *= s;
    tangents->solve_shifted(scaled.data(), y);
    Eigen::Map<Eigen::VectorXd>(y + n, n) /= s;
  }
};

// s = sqrt(|M^-1 K_t r| / |r|) for a fixed pseudo-random r: its norm is
// dominated by the stiffest modes, so s is omega_max within a small factor.
double balancing_scale(const StateOperator& tangents) {
  const int n = tangents.size();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(2 * n), y(2 * n);
  for (int i = 0; i < n; ++i) x[i] = 1.0 + 0.5 * std::sin(1.0 + i);  // fixed, no zero entry
  tangents.apply_state_matrix(x.data(), y.data());
  const double s = std::sqrt(y.tail(n).norm() / x.head(n).norm());
  return s > 0.0 && std::isfinite(s) ? s : 1.0;
}

template <typename Solver>
std::vector<std::complex<double>> converged(Solver& solver, const char* end) {
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, kArnoldiMaxRestarts, kArnoldiTol);
  if (solver.info() != Spectra::CompInfo::Successful)
    throw std::runtime_error(std::string("the Arnoldi iteration for the ") + end +
                             " eigenvalues of the coupled linearisation did not converge in " +
                             std::to_string(kArnoldiMaxRestarts) + " restarts");
  const Eigen::VectorXcd ev = solver.eigenvalues();
  return {ev.data(), ev.data() + ev.size()};
}

StateSpectrum dense_tangent_spectrum(const StateOperator& tangents) {
  Eigen::MatrixXd a = tangents.dense_state_matrix();
  // Balanced as linearized_spectrum does: rates in units of sqrt(max |A21|).
  const int nz = tangents.size();
  const double sigma = nz > 0 ? std::sqrt(a.bottomLeftCorner(nz, nz).cwiseAbs().maxCoeff()) : 0.0;
  if (sigma > 0.0 && std::isfinite(sigma)) {
    a.topRightCorner(nz, nz) *= sigma;
    a.bottomLeftCorner(nz, nz) /= sigma;
  }
  return dense_spectrum(a);
}

}  // namespace

StateSpectrum tangent_spectrum(StateOperator& tangents, const TangentSpectrumOptions& options) {
  const int states = 2 * tangents.size();
  std::vector<std::complex<double>> ev;
  bool complete = true;
  const double s = states > 0 ? balancing_scale(tangents) : 1.0;
  if (states <= options.max_dense_states || states <= 2 * (options.fastest + options.slowest)) {
    ev = dense_tangent_spectrum(tangents).eigenvalues;
  } else {
    complete = false;
    StateProduct product{&tangents, s, {}};
    Spectra::GenEigsSolver<StateProduct> top(product, options.fastest, subspace_size(options.fastest, states));
    ev = converged(top, "fastest");
    double largest = 0.0;
    for (const auto& l : ev) largest = std::max(largest, std::abs(l));
    ShiftedSolve solve{&tangents, s, false, {}};
    double sigma = 0.0;
    try {
      tangents.factorize_shifted(0.0);
      solve.factored = true;
    } catch (const std::runtime_error&) {
      sigma = -kSingularShiftRel * largest;
    }
    Spectra::GenEigsRealShiftSolver<ShiftedSolve> bottom(solve, options.slowest, subspace_size(options.slowest, states),
                                                         sigma);
    for (const auto& l : converged(bottom, "slowest")) {
      // Both ends meet only when the model is barely above the dense limit.
      const bool seen = std::any_of(ev.begin(), ev.end(), [&](const std::complex<double>& m) {
        return std::abs(m - l) <= kArnoldiTol * 100.0 * std::max(std::abs(l), 1.0);
      });
      if (!seen) ev.push_back(l);
    }
    // Repeated real eigenvalues come out with imaginary parts of round-off.
    for (auto& l : ev)
      if (std::abs(l.imag()) <= 1e-10 * std::abs(l)) l = {l.real(), 0.0};
  }
  for (auto& l : ev)
    if (std::abs(l) <= kZeroModeScaleRel * s) l = 0.0;
  ev.insert(ev.end(), 2 * static_cast<std::size_t>(tangents.num_driven()), std::complex<double>(0.0, 0.0));
  StateSpectrum out = spectrum_from_eigenvalues(std::move(ev));
  out.complete = complete;
  return out;
}

std::vector<std::complex<double>> middle_of_spectrum(const StateSpectrum& partial, const StateSpectrum& source,
                                                     int fastest) {
  std::vector<std::complex<double>> middle;
  const std::vector<std::complex<double>>& ev = partial.eigenvalues;  // ascending modulus
  const std::size_t top = static_cast<std::size_t>(std::max(fastest, 0));
  if (partial.complete || ev.size() <= top) return middle;
  const double lo = std::abs(ev[ev.size() - top - 1]), hi = std::abs(ev[ev.size() - top]);
  for (const std::complex<double>& l : source.eigenvalues) {
    const double r = std::abs(l);
    if (r > lo && r < hi && l.real() <= 0.0) middle.push_back(l);
  }
  return middle;
}

}  // namespace mbfe::runtime
