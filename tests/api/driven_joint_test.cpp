// Driven joints (`joint.motion`): a cart-pendulum whose cart follows
// x(t) = 0.3 sin(2 t), against the pendulum's own equation integrated here and
// the drive force derived by hand (Lagrange, theta the rod's angle from the x
// axis, c the hinge-to-centre-of-mass distance):
//
//   (I + m c^2) theta'' - m c sin(theta) x'' + m g c cos(theta) = 0
//   R = (M + m) x'' - m c (theta'' sin(theta) + theta'^2 cos(theta))
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "tests/support/recorded_rows.h"

namespace mbfe {
namespace {

constexpr double kCartMass = 2.0, kRodMass = 0.5, kCom = 0.4, kRodInertia = 0.02666666666666667, kG = 9.81;
constexpr double kTheta0 = -1.2;
constexpr double kStep = 1e-3, kEnd = 2.0;
// Both sides take the same RK4 steps of the same equation; what differs is the
// order of the floating-point operations: ~1e-13 rad after 2000 steps, with a margin.
constexpr double kAngleTol = 1e-10;
// The drive force adds products of O(1) terms: round-off relative to ~30 N.
constexpr double kForceTol = 1e-9;
// The motion kernel is the exact derivative printed as C++: round-off only.
constexpr double kMotionTol = 1e-14;
// s: the row's time and this loop's, 2000 sums of the step in other orders.
constexpr double kTimeTol = 1e-12;

const std::string kModel = R"yaml(model: driven_cart_pendulum
gravity: [0, -9.81]
bodies:
  - name: cart
    parent: ground
    joint: {type: prismatic, axis: [1, 0], at: [0, 0], motion: "0.3*sin(2*t)"}
    mass: 2.0
    inertia: 0
  - name: pendulum
    parent: cart
    joint: {type: revolute, at: [0, 0]}
    mass: 0.5
    inertia: 0.02666666666666667
    com: [0.4, 0]
initial: {q: {pendulum: -1.2}}
)yaml";

double x_dd(double t) { return -1.2 * std::sin(2.0 * t); }

double theta_dd(double t, double th, double) {
  return (kRodMass * kCom * std::sin(th) * x_dd(t) - kRodMass * kG * kCom * std::cos(th)) /
         (kRodInertia + kRodMass * kCom * kCom);
}

using Rows = test::RecordedRows;

TEST(DrivenJoint, CartPendulumFollowsTheMotionWithTheHandDerivedDriveForce) {
  const Model model = Model::parse(kModel, "driven_cart_pendulum.yaml");
  // The motion kernel: q, q', q'' of the expression.
  for (double t : {0.0, 0.37, 1.9}) {
    double q = 0, qd = 0, qdd = 0;
    ASSERT_EQ(model.solver()->num_driven, 1);
    EXPECT_EQ(model.solver()->driven_coordinates[0], 0);
    model.solver()->motion(t, &q, &qd, &qdd);
    EXPECT_NEAR(q, 0.3 * std::sin(2 * t), kMotionTol);
    EXPECT_NEAR(qd, 0.6 * std::cos(2 * t), kMotionTol);
    EXPECT_NEAR(qdd, x_dd(t), kMotionTol);
  }
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("rk4");
  request.step = kStep;
  request.t_end = kEnd;
  request.every = 1;
  Rows rows;
  const runtime::SimulationReport report = model.simulate(request, rows);
  ASSERT_TRUE(report.message.empty()) << report.message;
  ASSERT_EQ(rows.columns,
            (std::vector<std::string>{"t", "cart", "pendulum", "cart_dot", "pendulum_dot", "cart_drive"}));

  // The pendulum equation alone, RK4 with the same steps.
  double th = kTheta0, w = 0.0, t = 0.0;
  for (std::size_t i = 0; i < rows.values.size(); ++i) {
    const std::vector<double>& r = rows.values[i];
    ASSERT_NEAR(r[0], t, kTimeTol);
    EXPECT_NEAR(r[1], 0.3 * std::sin(2 * t), kMotionTol) << "t = " << t;
    EXPECT_NEAR(r[3], 0.6 * std::cos(2 * t), kMotionTol) << "t = " << t;
    EXPECT_NEAR(r[2], th, kAngleTol) << "t = " << t;
    EXPECT_NEAR(r[4], w, kAngleTol) << "t = " << t;
    const double a = theta_dd(t, th, w);
    const double drive = (kCartMass + kRodMass) * x_dd(t) -
                         kRodMass * kCom * (a * std::sin(th) + w * w * std::cos(th));
    EXPECT_NEAR(r[5], drive, kForceTol) << "t = " << t;
    // One RK4 step.
    const double h = kStep;
    const double k1t = w, k1w = theta_dd(t, th, w);
    const double k2t = w + 0.5 * h * k1w, k2w = theta_dd(t + 0.5 * h, th + 0.5 * h * k1t, k2t);
    const double k3t = w + 0.5 * h * k2w, k3w = theta_dd(t + 0.5 * h, th + 0.5 * h * k2t, k3t);
    const double k4t = w + h * k3w, k4w = theta_dd(t + h, th + h * k3t, k4t);
    th += h / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    w += h / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
    t = (i + 1) * kStep;
  }
}

}  // namespace
}  // namespace mbfe
