// A coupled model whose low-rank adjusted beams move in split coordinates
// (CoupledDynamics::split_low_rank_beams; docs/damping-adjustment.md, "Split
// coordinates"): y = [q_b; q_c; e; q_b'; q_c'; e'], where a split beam's q_c
// slot holds its uniform part s and e stacks the split beams' kept-mode
// coordinates [eta; zeta]. The same ODE as the partitioned formulation's with
// nothing to partition (no constraint contacts), at a cost per right-hand side
// that no longer grows with the number of kept modes times the beam's DOFs.
// A truncated beam (policy truncate) has s = 0 and zeta = 0 at all times: y
// leaves those entries out, and each half of y holds the rest of [q; e] in
// order, so an integrator's vector work is the kept modes', not the DOFs'.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "runtime/coupled/coupled_system.h"

namespace mbfe::runtime {

class SplitBeamSystem : public CoupledSystem {
 public:
  /// @throws std::invalid_argument unless the model can be split (no
  ///         constraint contacts, no joined structures, a low-rank beam).
  explicit SplitBeamSystem(std::shared_ptr<CoupledDynamics> dyn);

  int size() const override { return 2 * half_; }
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;
  std::string name(int i) const override;

  /// y from nodal coordinates: s = q_c and eta = zeta = Phi_L^T M q_c per split
  /// beam; for a truncated beam (policy truncate) s = 0, zeta = 0 and
  /// eta = Phi_L^T M q_c, the projection of q_c on its kept modes.
  Eigen::VectorXd initial_state(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) override;
  /// Nodal coordinates: every DOF of a split beam costs a pass over its Phi_L.
  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& qd) override;
  /// Only the rigid coordinates and the listed beam DOFs made nodal.
  void full_state_at(double t, const Eigen::VectorXd& y, const std::vector<int>& beam_dofs, Eigen::VectorXd& q,
                     Eigen::VectorXd& qd) override;
  const ContactReport& report(double t, const Eigen::VectorXd& y) override;

 private:
  // A run of consecutive entries of [q; e] that y holds (each half of y
  // is these runs, packed in order).
  struct Run {
    int full = 0, size = 0;
  };
  // q_, qd_, e_, ed_ from y (q_c of split beams: their uniform part; the
  // entries y leaves out stay 0).
  void unpack(const Eigen::VectorXd& y);
  // One half of y from [q; e] given as its two parts.
  void pack(const Eigen::VectorXd& q, const Eigen::VectorXd& e, double* half) const;
  // The entry of [q; e] that entry i of a half of y holds.
  int full_index(int i) const;
  // Whether (t, y) is the state of the last report, still described by the dynamics.
  bool is_reported(double t, const Eigen::VectorXd& y) const;

  std::vector<Run> runs_;
  int half_ = 0;           // entries in each half of y
  Partition independent_;  // every rigid coordinate independent (m = 0)
  Eigen::VectorXd q_, qd_, e_, ed_, qdd_, lambda_, ydot_;
  // The last report, valid while no right-hand side has been evaluated since.
  ContactReport report_;
  Eigen::VectorXd report_y_;
  double report_t_ = 0.0;
  bool report_valid_ = false;
};

}  // namespace mbfe::runtime
