// A planar double pendulum written by hand (equations derived on paper, not by
// the generator): the independent oracle for the generated solver of
// models/double_pendulum.yaml.
//
// Coordinates (the model-file convention, relative joint angles):
//   q1: angle of link 1, CCW from the ground x axis (joint at `hinge`);
//   q2: angle of link 2 RELATIVE to link 1 (joint at [l1, 0] in link 1's frame).
// Absolute angles th1 = q1, th2 = q1 + q2. Each link's centre of mass lies on its
// own x axis, at c1 resp. c2 from its joint.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>

namespace mbfe::reference {

struct DoublePendulumParams {
  double m1 = 1.0;       // kg
  double m2 = 1.0;       // kg
  double l1 = 1.0;       // m, joint of link 2 at [l1, 0] in link 1's frame
  double c1 = 0.5;       // m, COM of link 1 at [c1, 0] in its frame
  double c2 = 0.5;       // m, COM of link 2 at [c2, 0] in its frame
  double I1 = 1.0 / 12;  // kg m^2 about the COM
  double I2 = 1.0 / 12;  // kg m^2 about the COM
  Eigen::Vector2d gravity{0.0, -9.81};  // m/s^2, ground frame
  Eigen::Vector2d hinge{0.0, 0.0};      // m, joint of link 1 in the ground frame
};

/// M(q), 2 x 2 (kg m^2).
Eigen::Matrix2d mass_matrix(const DoublePendulumParams& p, const Eigen::Vector2d& q);
/// F(q, q'): velocity-dependent inertial terms (N m).
Eigen::Vector2d inertial_forces(const DoublePendulumParams& p, const Eigen::Vector2d& q,
                                const Eigen::Vector2d& qd);
/// Q(q): gravity only (N m).
Eigen::Vector2d generalized_forces(const DoublePendulumParams& p, const Eigen::Vector2d& q);
/// Potential energy of gravity (J), zero with both COMs at the hinge height.
double potential_energy(const DoublePendulumParams& p, const Eigen::Vector2d& q);
/// Ground-frame position of the point [x, 0] of link 2 (x = l2 gives the tip).
Eigen::Vector2d link2_point(const DoublePendulumParams& p, const Eigen::Vector2d& q, double x);

}  // namespace mbfe::reference
