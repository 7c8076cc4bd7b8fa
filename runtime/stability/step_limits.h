// The stability advisor: the largest stable step of each integrator for a
// given spectrum (the eigenvalues lambda of the linear(ised) state matrix).
//
// A step h is stable for y' = lambda y when h lambda lies in the method's
// absolute-stability region:
//   forward_euler      |1 + z| <= 1 (a disk): h < -2 Re(lambda) / |lambda|^2
//   rk4                |R(z)| <= 1, R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24; along
//                      the ray z = s lambda/|lambda| the crossings are the positive
//                      roots of the degree-8 polynomial |R|^2 - 1 (exact)
//   explicit_midpoint, ab2, bdf2, lmm:...
//                      root condition of rho(zeta) - z sigma(zeta) (every root in
//                      the closed unit disk, those on the circle simple); the
//                      crossings of the ray with the boundary locus
//                      z = rho(e^{i theta}) / sigma(e^{i theta}) are the candidates,
//                      each interval between them is checked by the root condition
//   backward_euler, trapezoid, generalized_alpha
//                      A-stable: "unconditional" when every Re(lambda) <= 0
// The limit of a spectrum is the largest H with every h in (0, H] stable for
// every eigenvalue. Zero eigenvalues (rigid modes) are skipped. "none": no
// positive step is stable (explicit midpoint with any eigenvalue off the
// imaginary axis, forward Euler with an undamped mode, any method for an
// eigenvalue with Re > 0).
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "runtime/integrators/integrator_spec.h"

namespace mbfe::runtime {

struct StepLimit {
  enum class Kind { kFinite, kUnconditional, kNone };
  Kind kind = Kind::kUnconditional;
  double h = 0.0;                   // s (kFinite)
  std::complex<double> critical{};  // the eigenvalue that sets the limit (kFinite, kNone)
  /// "1.4597e-05" (5 significant digits), "unconditional" or "none".
  std::string text() const;
};

/// True when z = h lambda is inside (or on the boundary of) the method's
/// stability region. generalized_alpha: Re z <= 0 (it is A-stable on the
/// second-order form; this first-order test is only its summary).
bool stable_at(const IntegratorSpec& method, std::complex<double> z);

/// Largest stable step for one eigenvalue.
StepLimit stable_step(const IntegratorSpec& method, std::complex<double> lambda);

/// Largest stable step for a whole spectrum.
StepLimit stable_step(const IntegratorSpec& method, const std::vector<std::complex<double>>& spectrum);

/// The integrators the advisor reports by default, in report order:
/// forward_euler, rk4, explicit_midpoint, ab2, backward_euler, trapezoid, bdf2, generalized_alpha.
std::vector<IntegratorSpec> advisor_integrators();

/// Roots of sum_i c[i] x^i (c.back() != 0), by the eigenvalues of the companion matrix.
std::vector<std::complex<double>> polynomial_roots(const std::vector<std::complex<double>>& c);

}  // namespace mbfe::runtime
