// `mbfe stability` of rigid-only models (bodies, no beams): the ODE
// y' = [q'; M(q)^-1 (Q - F)] linearised at the initial state, checked end to
// end (the built binary, --json) against closed-form eigenvalues.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/process.h"
#include "runtime/integrators/integrator.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::test {
namespace {

// The Jacobian is formed by central differences (rel_step 1e-6): exact up to
// round-off for the linear spring-damper, truncation ~1e-12 and round-off
// ~1e-10 relative for the pendulum's cos; --json prints 17 digits.
constexpr double kRel = 1e-7;
constexpr double kGravity = 9.81;
const double kPi = std::acos(-1.0);

nlohmann::json stability_json(const TempDir& dir, const std::string& model_yaml) {
  const fs::path path = dir / "model.yaml";
  spit(path, model_yaml);
  const RunResult r = run_mbfe(dir, "stability " + quote(path.string()) + " --json");
  EXPECT_EQ(r.status, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

double finite(const nlohmann::json& limits, const char* integrator) {
  EXPECT_TRUE(limits.at(integrator).is_number()) << integrator << ": " << limits.at(integrator);
  return limits.at(integrator).is_number() ? limits.at(integrator).get<double>() : NAN;
}

TEST(CmdStabilityRigid, PrismaticSpringDamper) {
  // m x'' + c x' + k x = 0: lambda = (-c +- sqrt(c^2 - 4 m k)) / (2 m).
  const double m = 2.0, k = 50.0, c = 3.0;
  TempDir dir;
  const auto j = stability_json(dir, "model: smd\ngravity: [0, 0]\nbodies:\n"
                                     "  - {name: x, parent: ground, joint: {type: prismatic, axis: [1, 0]},"
                                     " mass: 2.0, inertia: 0}\n"
                                     "loads:\n  - {type: spring_damper, joint: x, stiffness: 50, damping: 3, rest: 0}\n"
                                     "initial: {q: {x: 0.1}}\n");
  EXPECT_TRUE(j.at("adjusted").is_null());
  const auto& o = j.at("original");
  // Forward Euler: h < -2 Re(lambda) / |lambda|^2 = (c / m) / (k / m) = c / k.
  EXPECT_NEAR(finite(o, "forward_euler"), c / k, kRel * c / k);
  const std::complex<double> lambda(-c / (2 * m), std::sqrt(4 * m * k - c * c) / (2 * m));
  const double rk4 = runtime::stable_step(runtime::parse_integrator("rk4"), lambda).h;
  EXPECT_NEAR(finite(o, "rk4"), rk4, kRel * rk4);
  EXPECT_EQ(o.at("explicit_midpoint"), "none");  // damped: off the imaginary axis
  for (const char* a : {"backward_euler", "trapezoid", "bdf2", "generalized_alpha"})
    EXPECT_EQ(o.at(a), "unconditional") << a;
}

TEST(CmdStabilityRigid, PendulumAtRestAtTheBottom) {
  // Angle from the ground x axis (docs/model-format.md), gravity -y: the bottom
  // is q = -pi/2, where theta'' = -omega^2 (theta + pi/2) with
  // omega^2 = m g c / (I + m c^2).
  const double m = 1.5, inertia = 0.02, c = 0.4;
  const double omega = std::sqrt(m * kGravity * c / (inertia + m * c * c));
  TempDir dir;
  char yaml[512];
  std::snprintf(yaml, sizeof yaml,
                "model: pendulum\ngravity: [0, -9.81]\nbodies:\n"
                "  - {name: p, parent: ground, joint: {type: revolute, at: [0, 0]}, mass: %.17g, inertia: %.17g,"
                " com: [%.17g, 0]}\ninitial: {q: {p: %.17g}}\n",
                m, inertia, c, -kPi / 2);
  const auto j = stability_json(dir, yaml);
  const auto& o = j.at("original");
  EXPECT_EQ(o.at("forward_euler"), "none");  // undamped oscillation
  // RK4 reaches 2 sqrt(2) on the imaginary axis.
  EXPECT_NEAR(finite(o, "rk4"), 2.0 * std::sqrt(2.0) / omega, kRel * 2.0 * std::sqrt(2.0) / omega);
  EXPECT_NEAR(finite(o, "explicit_midpoint"), 1.0 / omega, kRel / omega);  // |h lambda| <= 1 on the axis
  EXPECT_EQ(o.at("trapezoid"), "unconditional");
}

TEST(CmdStabilityRigid, DoublePendulumAndTextReport) {
  TempDir dir;
  const RunResult text = run_mbfe(dir, "stability models/double_pendulum.yaml");
  ASSERT_EQ(text.status, 0) << text.err;
  // Released far from equilibrium: judged at the equilibrium it swings about.
  EXPECT_NE(text.out.find("linearised at its static equilibrium"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("forward_euler none: an undamped mode"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("local estimate"), std::string::npos) << text.out;
  const RunResult js = run_mbfe(dir, "stability models/double_pendulum.yaml --json");
  ASSERT_EQ(js.status, 0) << js.err;
  const auto j = nlohmann::json::parse(js.out);
  const double rk4 = finite(j.at("original"), "rk4");
  EXPECT_TRUE(std::isfinite(rk4) && rk4 > 0.0) << rk4;
  EXPECT_TRUE(j.at("adjusted").is_null());
}

TEST(CmdStabilityRigid, FreeBodyWithoutGravityReportsZeroModesNotGrowth) {
  // Nothing pulls a free body back: twelve zero eigenvalues (six defective
  // pairs), neither growth nor a mode that limits a step.
  TempDir dir;
  const fs::path path = dir / "tumbler.yaml";
  spit(path, "model: tumbler\ndimension: 3\ngravity: [0, 0, 0]\nbodies:\n"
             "  - {name: box, parent: ground, joint: {type: free}, mass: 2, inertia: [1, 2, 2.5, 0, 0, 0]}\n");
  const RunResult r = run_mbfe(dir, "stability " + quote(path.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("rigid, 6 DOF, 12 state eigenvalues"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("Re > 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("fastest eigenvalue 0 1/s"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace mbfe::test
