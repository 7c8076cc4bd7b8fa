// Which integrator, by name: the names of `--integrator` and their parameters.
//
// Names accepted by parse_integrator() (and `--integrator`):
//   forward_euler      y_n = y_{n-1} + h f_{n-1}                      order 1, explicit
//   backward_euler     y_n = y_{n-1} + h f_n                          order 1, implicit, A-stable
//   explicit_midpoint  y_n = y_{n-2} + 2 h f_{n-1}                    order 2, explicit, two-step;
//                      the first step is one forward-Euler step (as the paper's Fig. 3)
//   trapezoid          y_n = y_{n-1} + h/2 (f_n + f_{n-1})            order 2, implicit, A-stable
//   rk4                classical 4-stage Runge-Kutta                  order 4, explicit
//   ab2, bdf2          Adams-Bashforth 2 and BDF2 (presets of lmm)
//   lmm:alpha=a0,..,ak:beta=b0,..,bk
//                      a general linear multistep method
//                      sum_{i=0..k} alpha_i y_{n+i} = h sum_{i=0..k} beta_i f_{n+i}
//                      (explicit when beta_k = 0); the first k-1 steps are taken with RK4
//   generalized_alpha  Chung-Hulbert for M q'' + C q' + K q = P(t) (a LinearSecondOrderSystem
//                      only); order 2, A-stable; spectral radius at infinity rho_inf in [0, 1]
//                      (default 0.9)
#pragma once

#include <string>
#include <vector>

namespace mbfe::runtime {

/// Coefficients of sum_{i=0..k} alpha_i y_{n+i} = h sum_{i=0..k} beta_i f_{n+i};
/// alpha and beta have k + 1 entries each, alpha_k != 0.
struct LmmCoefficients {
  std::vector<double> alpha;
  std::vector<double> beta;
  bool explicit_method() const { return beta.empty() || beta.back() == 0.0; }
  int steps() const { return static_cast<int>(alpha.size()) - 1; }
};

enum class IntegratorKind {
  kForwardEuler,
  kBackwardEuler,
  kExplicitMidpoint,
  kTrapezoid,
  kRk4,
  kLinearMultistep,
  kGeneralizedAlpha,
};

/// Which integrator, with its parameters.
struct IntegratorSpec {
  IntegratorKind kind = IntegratorKind::kRk4;
  std::string name = "rk4";  // canonical name, used in messages ("forward_euler", "lmm", ...)
  LmmCoefficients lmm;       // kLinearMultistep only
  double rho_inf = 0.9;      // kGeneralizedAlpha only, in [0, 1]
  /// Order of accuracy (global error ~ h^order).
  int order() const;
  bool implicit() const;
};

/// Parses an integrator name (see the list above). @throws std::invalid_argument
/// with a message naming the accepted names for anything else.
IntegratorSpec parse_integrator(const std::string& text);

/// @throws std::invalid_argument unless alpha and beta have the same number
/// (k + 1 >= 2) of entries and alpha_k != 0.
void validate_lmm(const LmmCoefficients& c);

/// The names parse_integrator() accepts (without the lmm:... form), for help texts.
std::vector<std::string> integrator_names();

}  // namespace mbfe::runtime
