#include "runtime/modal/state_spectrum.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mbfe::runtime {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
}  // namespace

std::vector<ModalDynamics> rayleigh_modes(const Eigen::VectorXd& omega, double alpha, double beta) {
  std::vector<ModalDynamics> modes(omega.size());
  for (Eigen::Index j = 0; j < omega.size(); ++j) {
    const double w = omega[j];
    modes[j] = {w, alpha + beta * w * w, w * w};
  }
  return modes;
}

std::pair<std::complex<double>, std::complex<double>> modal_roots(double c, double k) {
  const double disc = c * c - 4.0 * k;
  if (disc < 0.0) {
    const double re = -0.5 * c;
    const double im = 0.5 * std::sqrt(-disc);
    return {{re, im}, {re, -im}};
  }
  // q = -(c + sign(c) sqrt(disc)) / 2 is the root of larger modulus; the other
  // is k / q (Vieta), free of the cancellation in (-c + sqrt(disc)) / 2.
  const double s = std::sqrt(disc);
  const double q = -0.5 * (c + std::copysign(s, c));
  if (q == 0.0) return {{0.0, 0.0}, {0.0, 0.0}};  // c = k = 0: a free rigid mode
  const double other = k / q;
  return std::abs(other) <= std::abs(q) ? std::make_pair(std::complex<double>(other, 0.0),
                                                         std::complex<double>(q, 0.0))
                                        : std::make_pair(std::complex<double>(q, 0.0),
                                                         std::complex<double>(other, 0.0));
}

std::pair<std::complex<double>, std::complex<double>> modal_roots(const ModalDynamics& mode) {
  return modal_roots(mode.c / mode.m, mode.k / mode.m);
}

double forward_euler_limit(const std::vector<std::complex<double>>& eigenvalues) {
  double h = std::numeric_limits<double>::infinity();
  for (const auto& l : eigenvalues) {
    const double m2 = std::norm(l);
    if (m2 == 0.0) continue;
    h = std::min(h, std::max(0.0, -2.0 * l.real() / m2));
  }
  return h;
}

StateSpectrum spectrum_from_eigenvalues(std::vector<std::complex<double>> eigenvalues) {
  std::stable_sort(eigenvalues.begin(), eigenvalues.end(),
                   [](const std::complex<double>& a, const std::complex<double>& b) {
                     const double ma = std::abs(a);
                     const double mb = std::abs(b);
                     if (ma != mb) return ma < mb;
                     return a.imag() > b.imag();
                   });
  StateSpectrum s;
  s.eigenvalues = std::move(eigenvalues);
  s.oscillatory_pairs = static_cast<int>(std::count_if(
      s.eigenvalues.begin(), s.eigenvalues.end(), [](const auto& l) { return l.imag() > 0.0; }));
  s.h_max_forward_euler = forward_euler_limit(s.eigenvalues);
  return s;
}

StateSpectrum state_spectrum(const std::vector<ModalDynamics>& modes, bool complete) {
  std::vector<std::complex<double>> ev;
  ev.reserve(2 * modes.size());
  for (const ModalDynamics& m : modes) {
    const auto [r1, r2] = modal_roots(m);
    ev.push_back(r1);
    ev.push_back(r2);
  }
  StateSpectrum s = spectrum_from_eigenvalues(std::move(ev));
  s.complete = complete;
  return s;
}

StateSpectrum rayleigh_spectrum(const ModalBasis& basis, double alpha, double beta) {
  return state_spectrum(rayleigh_modes(basis.omega, alpha, beta), basis.complete);
}

std::vector<std::complex<double>> dense_state_eigenvalues(const Eigen::MatrixXd& M,
                                                          const Eigen::MatrixXd& C,
                                                          const Eigen::MatrixXd& K) {
  const Eigen::Index n = M.rows();
  if (M.cols() != n || C.rows() != n || C.cols() != n || K.rows() != n || K.cols() != n) {
    throw std::invalid_argument("dense_state_eigenvalues: M, C, K must all be " +
                                std::to_string(n) + " x " + std::to_string(n));
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success) {
    throw std::runtime_error("dense_state_eigenvalues: M is not positive definite");
  }
  // A similarity transform of B that keeps the eigen-solver accurate over the
  // 1e-1 .. 1e8 range of the beam's spectrum: with M = L L^T and x = L^T q,
  // B ~ [[0, I], [-Kt, -Ct]] (Kt = L^-1 K L^-T, Ct = L^-1 C L^-T, symmetric),
  // then the displacement half is scaled by s = sqrt(max |Kt_ii|):
  // [[0, s I], [-Kt / s, -Ct]]. Without it, rounding of order eps ||M^-1 K||
  // turns dozens of near-critical real pairs complex.
  const Eigen::MatrixXd L = llt.matrixL();
  const auto Lt = L.triangularView<Eigen::Lower>();
  Eigen::MatrixXd Kt = Lt.solve(K);
  Kt = Lt.solve(Kt.transpose()).transpose();
  Eigen::MatrixXd Ct = Lt.solve(C);
  Ct = Lt.solve(Ct.transpose()).transpose();
  const double s = std::sqrt(std::max(Kt.diagonal().cwiseAbs().maxCoeff(), 1e-300));
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  B.topRightCorner(n, n) = s * Eigen::MatrixXd::Identity(n, n);
  B.bottomLeftCorner(n, n) = -Kt / s;
  B.bottomRightCorner(n, n) = -Ct;
  Eigen::EigenSolver<Eigen::MatrixXd> solver(B, /*computeEigenvectors=*/false);
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error("dense_state_eigenvalues: the eigen-solver did not converge");
  }
  const Eigen::VectorXcd ev = solver.eigenvalues();
  return {ev.data(), ev.data() + ev.size()};
}

std::vector<SpectrumRow> spectrum_rows(const StateSpectrum& spectrum) {
  std::vector<SpectrumRow> rows;
  const auto& ev = spectrum.eigenvalues;
  for (size_t i = 0; i < ev.size(); ++i) {
    SpectrumRow r;
    r.index = static_cast<int>(i) + 1;
    r.real = ev[i].real();
    r.imag = std::abs(ev[i].imag());
    if (ev[i].imag() != 0.0) {
      r.pair = true;
      const double mod = std::abs(ev[i]);
      r.f_damped_hz = r.imag / kTwoPi;
      r.zeta = mod > 0.0 ? -r.real / mod : 0.0;
      r.f_undamped_hz = mod / kTwoPi;
      // Skip the conjugate partner when it follows.
      if (i + 1 < ev.size() && ev[i + 1] == std::conj(ev[i])) ++i;
    }
    rows.push_back(r);
  }
  return rows;
}

}  // namespace mbfe::runtime
