// What the two formulations of a coupled model have in common, as the
// integrators and the simulation see them (docs/partitioning.md):
// PartitionedSystem (coordinate_partitioning.h, the paper's eqs (16)-(17)) and
// AugmentedSystem (augmented_system.h, the multipliers; a cross-check) and
// SplitBeamSystem (split_beam_system.h, low-rank beams in split coordinates).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "runtime/integrators/ode_system.h"
#include "runtime/coupled/coupled_dynamics.h"

namespace mbfe::runtime {

/// Common face of the two formulations.
class CoupledSystem : public OdeSystem {
 public:
  explicit CoupledSystem(std::shared_ptr<CoupledDynamics> dyn) : dyn_(std::move(dyn)) {}
  CoupledDynamics& dynamics() { return *dyn_; }

  /// A consistent initial y from full coordinates q = [q_b; q_c], qd (n each).
  /// Partitioned: keeps u, q_c, u', q_c' and closes v, v'. Augmented: as given.
  virtual Eigen::VectorXd initial_state(double t, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& qd) = 0;
  /// Full coordinates [q_b; q_c] and rates at y.
  virtual void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q,
                          Eigen::VectorXd& qd) = 0;
  /// Like full_state, where only the rigid coordinates and the beam
  /// coordinates `beam_dofs` (indices into q_c) must be exact: the others are
  /// whatever is cheapest (SplitBeamSystem leaves a split beam's uniform part).
  virtual void full_state_at(double t, const Eigen::VectorXd& y, const std::vector<int>& /*beam_dofs*/,
                             Eigen::VectorXd& q, Eigen::VectorXd& qd) {
    full_state(t, y, q, qd);
  }
  /// Multipliers, residuals and slider positions at (t, y).
  virtual const ContactReport& report(double t, const Eigen::VectorXd& y) = 0;

 protected:
  std::shared_ptr<CoupledDynamics> dyn_;
};

}  // namespace mbfe::runtime

