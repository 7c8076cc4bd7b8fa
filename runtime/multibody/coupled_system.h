// What the two formulations of a coupled model have in common, as the
// integrators and the simulation see them (docs/partitioning.md):
// PartitionedSystem (coordinate_partitioning.h, the paper's eqs (16)-(17)) and
// AugmentedSystem (augmented_system.h, the multipliers; a cross-check).
#pragma once

#include <Eigen/Core>
#include <memory>

#include "runtime/integrators/ode_system.h"
#include "runtime/multibody/coupled_dynamics.h"

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
  /// Multipliers, residuals and slider positions at (t, y).
  virtual ContactReport report(double t, const Eigen::VectorXd& y) = 0;

 protected:
  std::shared_ptr<CoupledDynamics> dyn_;
};

}  // namespace mbfe::runtime

