// The double pendulum hinged above a pinned-pinned beam, its tip sliding on the
// beam (models/double_pendulum_beam.yaml), written by hand in the solver ABI
// (mbfe_model_v1 with C function pointers): M, F, Q of the pendulum and, per
// contact, s(q), Phi, J_b, the element-local J_e and gamma, derived on paper in
// double_pendulum_beam.cpp. The independent oracle for the generated kernels of
// that model and the test model of the coupled-system tests.
#pragma once

#include <Eigen/Core>

#include "runtime/abi/mbfe_model_abi.h"
#include "tests/reference/double_pendulum.h"

namespace mbfe::reference {

/// The numbers of models/double_pendulum_beam.yaml.
struct DoublePendulumBeamParams {
  DoublePendulumParams pendulum;  // hinge [1.0, 1.2], links 0.7 m, 1 kg, COM mid-link
  double l2 = 0.7;                // m, tip of link 2 at [l2, 0] in its frame
  // Beam: origin, axis angle, length, elements, square section, steel.
  Eigen::Vector2d beam_origin{0.0, 0.0};
  double beam_angle = 0.0;     // rad
  double beam_length = 1.0;    // m
  int beam_elements = 50;
  double beam_side = 0.005;    // m
  double youngs_modulus = 2.1e11;  // Pa
  double density = 7860.0;         // kg/m^3
  double rayleigh_alpha = 3.0e-3;  // 1/s
  double rayleigh_beta = 1.5e-4;   // s
  /// Initial angles: tip on the undeformed beam at x = 0.65 m, knee to the right
  /// of the hinge-tip line. The static equilibrium of this branch has the tip
  /// near x = 0.51 m; released from rest the tip swings over about 0.39..0.65 m.
  Eigen::Vector2d q0{-1.3874443249943893, -0.9342922220176699};
};

const DoublePendulumBeamParams& double_pendulum_beam_params();

/// The model: 2 coordinates (link1, link2), one slider_pin contact "tip_slider"
/// (link2's tip on beam 0). Static storage; never null.
const mbfe_model_v1* double_pendulum_beam_model();

/// The same pendulum with its tip PINNED to the beam at s = kPinAt instead
/// (contact "tip_pin", 2 rows): a test model for the pin kernels.
const mbfe_model_v1* double_pendulum_beam_pin_model();
constexpr double kPinAt = 0.62;  // m along the beam

/// Hermite cubic shape functions on an element of length le at xi = (s - s0)/le,
/// w = N . [w1, w1', w2, w2']: value, d/ds and d2/ds2.
Eigen::Vector4d hermite_n(double xi, double le);
Eigen::Vector4d hermite_dn(double xi, double le);
Eigen::Vector4d hermite_ddn(double xi, double le);

}  // namespace mbfe::reference
