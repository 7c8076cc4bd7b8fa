// The running surface of a beam: what a slider contact (slider_pin,
// slider_spring) rides on, the beam's deflection plus an offset,
//
//   surface(s) = w(s) + r(s) - w_dead(s)                       (m, along +w)
//
// with r the `profile:` (an expression in s, a table interpolated linearly,
// or a random profile from a track spectrum) and w_dead the beam's static
// deflection under its own weight when `camber: static` (the rail laid
// straight on the loaded bridge). docs/profiles.md.
//
// The generated contact kernels know only w(s) = N(xi) q_e on the element
// under the point. The offset reaches them through q_e: for a point at s, the
// element's DOFs get those of the quadratic p(x) = r(s) + r'(s) (x - s) +
// r''(s) (x - s)^2 / 2, which the Hermite cubic holds exactly, so the kernels
// see the surface's value, slope and curvature at s exactly: Phi, J_b (the
// slope in w'(s) ds/dq_b) and gamma (the curvature in w''(s) s'^2) all take
// the profile in, and J_e = N(xi) does not change. The camber is a Hermite
// field on the same mesh and is subtracted from q_e as it is.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "ir/model.h"
#include "runtime/fem/expression_jet.h"
#include "runtime/fem/track_spectrum.h"

namespace mbfe::runtime {

class RunningSurface {
 public:
  /// The surface of a beam of `length` (m) with `elements` equal elements.
  /// `camber_full`: w_dead at every node, [w, w'] per node (2 (elements + 1)
  /// entries), or empty without camber. A spectrum profile is drawn here and
  /// tabulated (r and r' every wavelength_min / 32, cubic between: relative
  /// error below 4e-6 at the shortest wavelength).
  /// @throws std::invalid_argument on a table that is not strictly increasing
  /// in s or has fewer than 2 rows, or a camber vector of the wrong size.
  RunningSurface(const ir::BeamProfile& profile, double length, int elements, Eigen::VectorXd camber_full);

  /// r(s), r'(s), r''(s) of the profile alone (m, 1, 1/m); zero without one.
  Jet profile(double s) const;
  /// The offset r(s) - w_dead(s) (m).
  double offset(double s) const;
  /// w_dead at the nodes, [w, w'] per node; empty without camber.
  const Eigen::VectorXd& camber() const { return camber_; }

  /// Adds to the local DOFs qe = (w1, w1', w2, w2') of `element`, which spans
  /// [s0, s0 + le], those of the offset around s: the kernels evaluated at s
  /// on the sum see the surface's value, slope and curvature there.
  void add_to_element(int element, double s, double s0, double le, double* qe) const;

 private:
  ir::ProfileKind kind_;
  ir::Expression expression_;
  std::vector<double> table_s_, table_r_;      // linear table (kTable)
  double grid_step_ = 0.0;                     // tabulated spectrum: step (m)
  std::vector<double> grid_r_, grid_dr_;       // r, r' at s = k grid_step_
  Eigen::VectorXd camber_;
  double element_length_ = 0.0;
  int elements_ = 0;
};

/// The running surface of `beam` under `gravity` (m/s^2), or none when the
/// beam has neither a profile nor a camber. The camber is w_dead = K^-1 P_dead
/// with K the beam's stiffness (its supports and spring supports) and P_dead
/// its own weight and the weight of its point masses and support masses (not
/// its point or moving loads).
/// @throws std::invalid_argument when `camber: static` is asked of a beam whose
/// own supports do not hold it (K singular: a wire hung from droppers).
std::optional<RunningSurface> running_surface(const ir::Beam& beam, const ir::Vec2& gravity);

}  // namespace mbfe::runtime
