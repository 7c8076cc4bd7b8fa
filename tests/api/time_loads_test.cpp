// Loads that change with time on the rigid part, through the generated
// kernels: an expression in t with a start/stop window on a force, a torque
// and a spring-damper, against the same expressions evaluated here.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "api/mbfe.h"

namespace mbfe {
namespace {

// The kernel prints the same expression as C++: round-off of O(1e4) values.
constexpr double kTol = 1e-9;

const std::string kModel = R"yaml(model: timed_loads
bodies:
  - name: slider
    parent: ground
    joint: {type: prismatic, axis: [0, 1]}
    mass: 1.0
    inertia: 0
  - name: wheel
    parent: slider
    joint: {type: revolute}
    mass: 1.0
    inertia: 0.5
    points: {hub: [0, 0]}
loads:
  - {type: force, body: wheel, point: hub, value: ["0", "-9810*(1 + 0.1*sin(12*t))"], start: 0.5, stop: 2.0}
  - {type: torque, body: wheel, value: "max(0, 3 - t)*step(t - 1) + abs(t - 4)^2 + exp(-t)*sqrt(t + 1)/log(t + 2) + min(t, 1)*pi/tan(t + 1)*cos(t)"}
  - {type: spring_damper, joint: slider, stiffness: 100.0, damping: 10.0, rest: 0.1, start: 1.0}
)yaml";

TEST(TimeLoads, GeneratedKernelsFollowTheExpressionsAndTheirWindows) {
  const Model model = Model::parse(kModel, "timed_loads.yaml");
  for (double t : {0.0, 0.49, 0.5, 0.9, 1.0, 1.7, 1.99, 2.0, 3.5, 5.0}) {
    State state;
    state.q = {0.3, 0.0};
    state.qd = {2.0, 0.0};
    state.t = t;
    const Evaluation e = model.evaluate(state);
    const double force = (t >= 0.5 && t < 2.0) ? -9810.0 * (1 + 0.1 * std::sin(12 * t)) : 0.0;
    const double spring = t >= 1.0 ? -100.0 * (0.3 - 0.1) - 10.0 * 2.0 : 0.0;
    const double torque = std::max(0.0, 3 - t) * (t >= 1 ? 1.0 : 0.0) + std::pow(std::abs(t - 4), 2) +
                          std::exp(-t) * std::sqrt(t + 1) / std::log(t + 2) +
                          std::min(t, 1.0) * 3.14159265358979323846 / std::tan(t + 1) * std::cos(t);
    EXPECT_NEAR(e.Q[0], force + spring, kTol) << "t = " << t;
    EXPECT_NEAR(e.Q[1], torque, kTol) << "t = " << t;
  }
}

}  // namespace
}  // namespace mbfe
