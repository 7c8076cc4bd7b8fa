// Coordinate partitioning, eqs (16)-(17) of the paper (docs/partitioning.md):
// q_b = (u, v), the m dependent coordinates v chosen among q_b by the largest
// pivots of J_b and chosen again when J_v becomes ill-conditioned. The state is
// y = [u; q_c; u'; q_c']; v is closed by Newton on Phi at every evaluation
// (|Phi| <= closure_tol, in practice ~1e-15 m), v' by the velocity constraint:
// an ODE in (u, q_c) that explicit integrators step as is.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "runtime/coupled/coupled_system.h"

namespace mbfe::runtime {

struct PartitionOptions {
  double closure_tol = 1e-10;   // m: Newton must bring max |Phi| below this
  int max_newton = 30;          // iterations per closure
  /// Choose the partition again when sigma_min of the current J_v falls below
  /// this fraction of the best partition's (hysteresis: 0.1 avoids flip-flop).
  double repartition_ratio = 0.1;
  /// Dependent coordinates to start with (rigid indices, m of them); empty =
  /// chosen automatically. Checked by initial_state().
  std::vector<int> initial_dependent;
};

/// Coordinate partitioning, eqs (16)-(17). y = [u; q_c; u'; q_c'].
class PartitionedSystem : public CoupledSystem {
 public:
  PartitionedSystem(std::shared_ptr<CoupledDynamics> dyn, PartitionOptions opt = {});

  int size() const override { return 2 * nz_; }
  /// @throws NewtonClosureError, SingularConstraintError, SliderOffBeamError.
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;
  /// Closes v at the accepted y, keeps it as the next Newton start and chooses
  /// the partition again if J_v has become ill-conditioned (then y is rewritten
  /// in the new independent coordinates: size unchanged, meaning changed).
  void after_step(double t, Eigen::VectorXd& y) override;
  std::string name(int i) const override;

  Eigen::VectorXd initial_state(double t, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& qd) override;
  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q,
                  Eigen::VectorXd& qd) override;
  const ContactReport& report(double t, const Eigen::VectorXd& y) override;

  const Partition& partition() const { return part_; }
  /// How many times the partition was chosen again since construction.
  int repartitions() const { return repartitions_; }
  /// Newton iterations of the last closure.
  int last_newton_iterations() const { return last_iters_; }

 private:
  ContactReport report_;  // what report() returns, reused
  Eigen::VectorXd report_ydot_;
  ConstraintValues report_cv_;
  // Fills q_, qd_ (full) from y with v closed and v' projected.
  void close(double t, const Eigen::VectorXd& y);
  void set_partition(const Partition& p);

  PartitionOptions opt_;
  Partition part_;
  int nu_ = 0, nz_ = 0;
  int repartitions_ = 0, last_iters_ = 0;
  // Newton's start for v: the v and v' of the last accepted state (after_step)
  // at time t, extrapolated to the time asked for (error O(h^2) instead of
  // O(h): one Newton iteration fewer per step) when that time is within a few
  // accepted steps h of t.
  struct Guess {
    Eigen::VectorXd v, vd;
    double t = 0.0, h = 0.0;  // h: the last accepted step (0: none yet)
    bool valid = false;       // v, vd, t describe an accepted state
  };
  // The accepted, closed state q_, qd_ at t becomes the next Newton start.
  void remember_start(double t);
  Guess guess_;
  Eigen::VectorXd q_, qd_, qdd_, lambda_;
  Eigen::MatrixXd jv_;
  SmallLu jv_lu_;  // of jv_ at the last closed state
  ConstraintValues cv_close_;  // of close(), at the last closed state (after_step reads it)
  Eigen::VectorXd dv_, r_, vd_;   // workspace of close()
  // The y of the last successful closure: an integrator evaluates f at the
  // state after_step() has just closed, which need not be closed again.
  Eigen::VectorXd closed_y_;
  bool closed_valid_ = false;
};

}  // namespace mbfe::runtime
