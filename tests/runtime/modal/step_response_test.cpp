// The closed-form step response of a mode against a fine RK4 integration of
// the same equation, in each of its three regimes.
#include "runtime/modal/step_response.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mbfe::runtime {
namespace {

// RK4 at h = 1e-4 s over 2 s on modes of 0.1..100 1/s: global error
// ~(h w)^4 w t ~ 1e-9 of the static value.
constexpr double kRk4Tol = 1e-8;

// eta'' + c eta' + k eta = p from rest, by RK4.
double integrate(double c, double k, double p, double t_end) {
  const double h = 1e-4;
  double x = 0.0, v = 0.0;
  auto acc = [&](double xx, double vv) { return p - c * vv - k * xx; };
  for (int i = 0; i < static_cast<int>(std::lround(t_end / h)); ++i) {
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  return x;
}

TEST(ModalStepResponse, MatchesIntegrationInEveryRegime) {
  // (c, k): underdamped (zeta 0.05), critically damped, overdamped (zeta 5).
  const double cases[][2] = {{2 * 0.05 * 20.0, 400.0}, {2 * 10.0, 100.0}, {2 * 5.0 * 3.0, 9.0}};
  for (const auto& ck : cases) {
    ModalStepResponse r;
    r.modes = {{std::sqrt(ck[1]), ck[0], ck[1]}};
    r.p = Eigen::VectorXd::Constant(1, 2.5);
    r.g = Eigen::VectorXd::Constant(1, 1.0);
    const double scale = r.w_static();
    EXPECT_DOUBLE_EQ(scale, 2.5 / ck[1]);
    EXPECT_EQ(r.w(0.0), 0.0);
    for (double t : {0.05, 0.3, 2.0})
      EXPECT_NEAR(r.w(t), integrate(ck[0], ck[1], 2.5, t), kRk4Tol * scale) << "c = " << ck[0] << ", t = " << t;
  }
}

TEST(ModalStepResponse, ReadsTheModalMass) {
  // m eta'' + c eta' + k eta = p with m = 4 (policy mass): against RK4 on
  // eta'' + (c/m) eta' + (k/m) eta = p/m, in each regime; the static value p/k
  // does not depend on m.
  constexpr double kMass = 4.0;
  const double cases[][2] = {{kMass * 2 * 0.05 * 20.0, kMass * 400.0}, {kMass * 2 * 10.0, kMass * 100.0},
                             {kMass * 2 * 5.0 * 3.0, kMass * 9.0}};
  for (const auto& ck : cases) {
    ModalStepResponse r;
    r.modes = {{std::sqrt(ck[1]), ck[0], ck[1], kMass}};
    r.p = Eigen::VectorXd::Constant(1, 2.5);
    r.g = Eigen::VectorXd::Constant(1, 1.0);
    const double scale = r.w_static();
    EXPECT_DOUBLE_EQ(scale, 2.5 / ck[1]);
    for (double t : {0.05, 0.3, 2.0})
      EXPECT_NEAR(r.w(t), integrate(ck[0] / kMass, ck[1] / kMass, 2.5 / kMass, t), kRk4Tol * scale)
          << "c = " << ck[0] << ", t = " << t;
  }
}

}  // namespace
}  // namespace mbfe::runtime
