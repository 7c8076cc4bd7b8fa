// Eigenvalues of the state matrix of eq (28),
//   B = [[0, I], [-M^-1 K, -M^-1 C]],
// their table (the paper's Table 1) and the forward-Euler step limit.
//
// For a model that decouples in mass-normalised modes (Rayleigh damping, or
// a modally adjusted one), each mode j obeys m_j q'' + c_j q' + k_j q = p and
// contributes the two roots of m_j r^2 + c_j r + k_j = 0; state_spectrum()
// works from those per-mode coefficients, so the original model (m_j = 1,
// k_j = omega_j^2, c_j = alpha + beta omega_j^2) and an adjusted one (policy
// mass raises m_j of the capped modes) go through the same code.
// dense_state_eigenvalues() is the general path (eig of B, any C), used as an
// independent oracle.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <vector>

#include "runtime/modal/modal_basis.h"

namespace mbfe::runtime {

/// One decoupled mode of a mass-normalised basis: m q'' + c q' + k q = p,
/// with p = phi^T f the modal load (N for a unit modal mass).
struct ModalDynamics {
  double omega = 0.0;  // rad/s, the original undamped natural frequency (a label)
  double c = 0.0;      // 1/s, modal damping (per unit of the original modal mass)
  double k = 0.0;      // 1/s^2, modal stiffness (omega^2 unless adjusted)
  double m = 1.0;      // modal mass relative to the original one (1 unless policy mass raised it), > 0
};

/// Rayleigh damping per mode: c_j = alpha + beta omega_j^2, k_j = omega_j^2.
std::vector<ModalDynamics> rayleigh_modes(const Eigen::VectorXd& omega, double alpha, double beta);

/// The two roots of r^2 + c r + k = 0, computed without cancellation (the slow
/// root of a heavily overdamped mode, ~ -k/c, keeps its digits). For a complex
/// pair, first has the positive imaginary part; for real roots, first is the
/// slower (smaller modulus).
std::pair<std::complex<double>, std::complex<double>> modal_roots(double c, double k);

/// The two roots of m r^2 + c r + k = 0 (modal_roots(c / m, k / m)), ordered as above.
std::pair<std::complex<double>, std::complex<double>> modal_roots(const ModalDynamics& mode);

struct StateSpectrum {
  /// Sorted by modulus ascending; a conjugate pair adjacent, +imag first.
  std::vector<std::complex<double>> eigenvalues;
  int oscillatory_pairs = 0;  // pairs with a nonzero imaginary part
  /// Forward Euler: min over eigenvalues of -2 Re(lambda) / |lambda|^2 (s);
  /// 0 when some nonzero eigenvalue has Re >= 0 (no stable step); +inf when
  /// there is no nonzero eigenvalue. Zero eigenvalues (rigid modes) are skipped.
  double h_max_forward_euler = 0.0;
  /// False when built from only some of the modes (a partial spectrum).
  bool complete = true;
};

/// The spectrum of a set of decoupled modes (2 roots each, of m r^2 + c r + k).
StateSpectrum state_spectrum(const std::vector<ModalDynamics>& modes, bool complete = true);

/// The spectrum of a Rayleigh-damped model from its modal basis.
StateSpectrum rayleigh_spectrum(const ModalBasis& basis, double alpha, double beta);

/// Sorts, pairs and summarises eigenvalues obtained any other way.
StateSpectrum spectrum_from_eigenvalues(std::vector<std::complex<double>> eigenvalues);

/// -2 Re(lambda)/|lambda|^2 minimised over the nonzero eigenvalues (see
/// StateSpectrum::h_max_forward_euler).
double forward_euler_limit(const std::vector<std::complex<double>>& eigenvalues);

/// Dense eigenvalues of B (2n x 2n) for any symmetric M (positive definite), C, K.
/// O(n^3); meant for small models and as a test oracle. @throws
/// std::invalid_argument on mismatched sizes, std::runtime_error if M is not
/// positive definite or the eigen-solver fails.
std::vector<std::complex<double>> dense_state_eigenvalues(const Eigen::MatrixXd& M,
                                                          const Eigen::MatrixXd& C,
                                                          const Eigen::MatrixXd& K);

/// One row of the paper's Table 1: a real eigenvalue, or a conjugate pair
/// shown once (imag = |Im|).
struct SpectrumRow {
  int index = 0;         // 1-based position of the (first) eigenvalue in the sorted list
  bool pair = false;     // a conjugate pair: rows index and index + 1
  double real = 0.0;     // 1/s
  double imag = 0.0;     // 1/s, >= 0
  double f_damped_hz = 0.0;    // |Im| / 2 pi (pairs only)
  double zeta = 0.0;           // -Re / |lambda| (pairs only), a fraction
  double f_undamped_hz = 0.0;  // |lambda| / 2 pi (pairs only)
};

std::vector<SpectrumRow> spectrum_rows(const StateSpectrum& spectrum);

}  // namespace mbfe::runtime
