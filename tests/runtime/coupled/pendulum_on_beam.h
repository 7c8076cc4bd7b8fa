// The double pendulum on its pinned-pinned beam (tests/reference/
// double_pendulum_beam.h) as the coupled-system tests build it: the beam, the
// dynamics, the pendulum angles that put the tip at a point of the beam, and
// one RK4 step with after_step.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <vector>

#include "runtime/coupled/coupled_dynamics.h"
#include "tests/reference/double_pendulum_beam.h"
#include "tests/runtime/coupled/test_beam.h"

namespace mbfe::runtime::pendulum_on_beam {

using reference::double_pendulum_beam_model;
using reference::double_pendulum_beam_params;
using reference::double_pendulum_beam_pin_model;

inline testing::TestBeam make_beam(int elements, bool damping) {
  const reference::DoublePendulumBeamParams& p = double_pendulum_beam_params();
  const double a = p.beam_side;
  const double EI = p.youngs_modulus * a * a * a * a / 12.0;
  const double rhoA = p.density * a * a;
  // Own weight on the transverse direction n = (0, 1) of a beam along x.
  const double qg = rhoA * p.pendulum.gravity.y();
  return testing::pinned_pinned_beam("beam1", p.beam_length, elements, EI, rhoA, qg,
                                     damping ? p.rayleigh_alpha : 0.0,
                                     damping ? p.rayleigh_beta : 0.0);
}

inline std::shared_ptr<CoupledDynamics> make_dynamics(const mbfe_model_v1& model,
                                               const testing::TestBeam& beam) {
  CoupledBeams beams;
  beams.beams.push_back(beam.beam);
  return std::make_shared<CoupledDynamics>(std::make_shared<const CoupledModel>(model, std::move(beams)));
}

// Tip of the pendulum placed at (x, 0) with the knee to the right.
inline Eigen::Vector2d pendulum_angles_for_tip(double x) {
  const reference::DoublePendulumBeamParams& p = double_pendulum_beam_params();
  const Eigen::Vector2d d = Eigen::Vector2d(x, 0.0) - p.pendulum.hinge;
  const double phi = std::atan2(d.y(), d.x());
  const double b = std::acos(d.norm() / (2.0 * p.pendulum.l1));  // l1 == l2
  return {phi + b, -2.0 * b};
}

inline void rk4_step(OdeSystem& sys, double t, double h, Eigen::VectorXd& y) {
  Eigen::VectorXd k1, k2, k3, k4;
  sys.rhs(t, y, k1);
  sys.rhs(t + h / 2, y + h / 2 * k1, k2);
  sys.rhs(t + h / 2, y + h / 2 * k2, k3);
  sys.rhs(t + h, y + h * k3, k4);
  y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  sys.after_step(t + h, y);
}

}  // namespace mbfe::runtime::pendulum_on_beam
