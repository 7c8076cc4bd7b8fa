// The damping of a beam's discrete parts (point masses, spring supports and
// their dampers) that its modal form leaves out, as a force element.
//
// An adjusted or truncated beam damps each kept mode by Rayleigh's
// alpha + beta omega_j^2, which is Phi^T (alpha M + beta K) Phi with M and K
// holding the discrete parts. The original model's C is Rayleigh over the
// elements alone, with the supports' dampers added as they are
// (runtime/fem/beam_system.h). The difference, R = C - (alpha M + beta K),
// is diagonal over the discrete parts' DOFs (a damper c, a mass m and a spring
// k on one DOF give c - alpha m - beta k there); this element adds
//
//   f_c = -R q_c'
//
// so that the kept modes' damping is the original model's, coupling terms
// included (docs/damping-adjustment.md, "The discrete parts' damping"). It is
// exact and linear: its tangent is c_v R.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "runtime/coupled/force_element.h"

namespace mbfe::runtime {

class DiscreteDampingForce final : public ForceElement {
 public:
  /// The remainder of beam `beam_name` (free DOF index within the beam, N s/m),
  /// whose free DOFs start at `offset` in q_c; q_c starts at `nb` in [q_b; q_c].
  DiscreteDampingForce(const std::string& beam_name, std::vector<std::pair<int, double>> remainder, int offset,
                       int nb);

  const std::string& name() const override { return name_; }
  std::unique_ptr<ForceState> make_state() const override { return std::make_unique<ForceState>(); }
  void add_force(const ForceArgs& x, ForceState& state, ForceSink& out) const override;
  void add_tangent(const ForceArgs& x, const ForceState& state, double c_q, double c_v,
                   TangentSink& out) const override;
  void beam_dofs_read(const double* qb, std::vector<int>& out) const override;

 private:
  std::vector<std::pair<int, double>> remainder_;  // q_c index, N s/m
  int nb_;                                         // where q_c starts in [q_b; q_c]
  std::string name_;
};

}  // namespace mbfe::runtime
