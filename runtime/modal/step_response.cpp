#include "runtime/modal/step_response.h"

#include <cmath>

namespace mbfe::runtime {

namespace {

// Two real roots closer than this (relative) take the critically damped
// form: the overdamped one divides by b - a and loses every digit there.
constexpr double kCriticalTol = 1e-7;

}  // namespace

double ModalStepResponse::eta(int j, double t) const {
  const double st = p[j] / modes[j].k;
  const auto r = modal_roots(modes[j]);  // of m r^2 + c r + k
  if (r.first.imag() != 0.0) {
    const double s = -r.first.real(), wd = r.first.imag();
    return st * (1.0 - std::exp(-s * t) * (std::cos(wd * t) + s / wd * std::sin(wd * t)));
  }
  const double a = std::abs(r.first.real()), b = std::abs(r.second.real());  // slow, fast
  if (b - a <= kCriticalTol * b) return st * (1.0 - (1.0 + a * t) * std::exp(-a * t));
  return st * (1.0 - (b * std::exp(-a * t) - a * std::exp(-b * t)) / (b - a));
}

double ModalStepResponse::w(double t) const {
  double s = 0.0;
  for (int j = 0; j < static_cast<int>(modes.size()); ++j) s += g[j] * eta(j, t);
  return s;
}

double ModalStepResponse::w_static() const {
  double s = 0.0;
  for (int j = 0; j < static_cast<int>(modes.size()); ++j) s += g[j] * p[j] / modes[j].k;
  return s;
}

}  // namespace mbfe::runtime
