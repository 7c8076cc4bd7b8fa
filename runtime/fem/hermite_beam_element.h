// Planar Euler-Bernoulli bending element with Hermite cubic interpolation
// (hermite_shape.h). DOFs [w1, w1', w2, w2'].
#pragma once

#include "runtime/fem/beam_element.h"

namespace mbfe::runtime {

class HermiteBeamElement final : public BeamElement {
 public:
  /// @param le element length (m) @param EI bending stiffness (N m^2)
  /// @param rhoA mass per length (kg/m) @param lumping consistent mass
  /// rho A le / 420 [156 ...] or lumped (row-sum-free HRZ diagonal: rho A le / 2
  /// on w, rho A le^3 / 78 on w'). All must be > 0 (asserted by the factory).
  /// @param tension axial pre-tension T (N, >= 0): the stiffness gains the
  /// consistent geometric matrix T int(N'^T N') ds = T / (30 le) [36 3le ...].
  HermiteBeamElement(double le, double EI, double rhoA, ir::MassLumping lumping, double tension = 0.0);

  int node_dofs() const override { return 2; }
  Eigen::MatrixXd stiffness() const override;
  Eigen::MatrixXd mass() const override;
  Eigen::VectorXd uniform_load(double q) const override;
  /// sqrt(EI le) [mean curvature; (curvature change) / sqrt(12)] (2 x 4):
  /// the bending energy EI le (k0^2 + k0 k1 + k1^2) / 3 of the linear
  /// curvature k(xi) = k0 (1 - xi) + k1 xi as a sum of two squares; with a
  /// tension, three more rows sqrt(T w_g) N'(xi_g) (3-point Gauss, exact for
  /// the quartic N'^T N').
  Eigen::MatrixXd stiffness_factor() const override;

 private:
  double le_;
  double EI_;
  double rhoA_;
  ir::MassLumping lumping_;
  double tension_;
};

}  // namespace mbfe::runtime
