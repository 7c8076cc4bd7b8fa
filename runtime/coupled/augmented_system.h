// The augmented (multiplier) formulation of a coupled model: y = [q_b; q_c;
// q_b'; q_c'], accelerations and multipliers from the saddle-point system
// [[M, J^T], [J, 0]] [q''; lambda] = [Q - F; gamma]. No drift correction, so
// |Phi| drifts with the integration error (reported): a cross-check of the
// partitioned formulation (docs/partitioning.md).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "runtime/coupled/coupled_system.h"

namespace mbfe::runtime {

/// The augmented (multiplier) formulation. y = [q_b; q_c; q_b'; q_c'].
class AugmentedSystem : public CoupledSystem {
 public:
  explicit AugmentedSystem(std::shared_ptr<CoupledDynamics> dyn);
  int size() const override { return 2 * dyn_->n(); }
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;
  std::string name(int i) const override;
  Eigen::VectorXd initial_state(double t, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& qd) override;
  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q,
                  Eigen::VectorXd& qd) override;
  const ContactReport& report(double t, const Eigen::VectorXd& y) override;

 private:
  ContactReport report_;  // what report() returns, reused
  Eigen::VectorXd report_ydot_;
  Eigen::VectorXd q_, qd_, qdd_, lambda_;
};

}  // namespace mbfe::runtime
