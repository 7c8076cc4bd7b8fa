// A model of bodies with closed loops (`constraints:`), M(q) v' + F = Q +
// J^T lambda, Phi(q) = 0, as a first-order system for the integrators, in two
// formulations (docs/partitioning.md, "Closed loops"):
//
// Driven joints (`motion:`) are rows of the closure too (loop_closure.h):
// their coordinates are dependent, J v = nu(t) carries their rates, and the
// multipliers of their rows are the drives' reactions.
//
// LoopPartitionedSystem: y = [q; v_u], the nq position coordinates and the
// nv - nc independent velocities. Every evaluation closes the dependent
// directions of q by Newton (|Phi| <= 1e-13 m), takes v_d from J v = nu and
// the accelerations from the reduced equations B^T M B v_u' = B^T (Q - F -
// M c) (v = B v_u, v' = B v_u' + c, J c = gamma); after each step q is
// closed in place and the partition chosen again when J_d has become
// ill-conditioned. Loop residuals stay at round-off.
//
// LoopAugmentedSystem: y = [q; v], accelerations and multipliers from
// [[M, J^T], [J, 0]] [v'; -lambda] = [Q - F; gamma]; after each step q is
// projected back onto Phi = 0 (least-norm Newton) and v onto J v = nu. A
// cross-check of the partitioned formulation.
//
// Both renormalise quaternions after each step.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/integrators/ode_system.h"
#include "runtime/multibody/loop_closure.h"
#include "runtime/multibody/rigid_system.h"

namespace mbfe::runtime {

/// What both loop systems share: the kernels, M F Q at a full state.
class LoopSystem : public OdeSystem {
 public:
  /// @param model a solver with loop kernels; must outlive this object.
  /// @param rows_at where the loop rows that repeat the others are found
  ///        (LoopClosure); null keeps every row.
  /// @throws std::invalid_argument as LoopClosure.
  LoopSystem(const mbfe_model_v1& model, std::vector<BodyInertia> bodies, RigidCoordinates coordinates,
             const double* rows_at = nullptr);

  const LoopClosure& closure() const { return closure_; }
  int num_coordinates() const { return nq_; }
  int num_velocities() const { return nv_; }

  /// A consistent state from (q, v) (nq, nv): the dependent coordinates of
  /// the partition chosen at q (coordinates with a non-zero velocity kept
  /// independent where J allows) closed by Newton (the independent ones kept)
  /// and the dependent velocities solved from J v = nu (0 in the loops'
  /// rows, the motion's rate in a drive's); quaternions renormalised and the
  /// driven coordinates set to their motion first. q and v are overwritten
  /// with it.
  /// @throws NewtonClosureError, SingularConstraintError.
  void make_consistent(double t, Eigen::VectorXd& q, Eigen::VectorXd& v) const;

  /// The y of a consistent full state (q, v).
  virtual Eigen::VectorXd state_of(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v) = 0;
  /// The full state (q closed, v) of y.
  virtual void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& v) = 0;
  /// The generalized force (N or N m) each driven joint exerts at (t, y) to
  /// follow its motion, model order: minus its row's multiplier.
  virtual void drive_reactions(double t, const Eigen::VectorXd& y, Eigen::VectorXd& out) = 0;

 protected:
  /// M, F, Q at (q, v, t) into m_, f_, q_force_. @throws SingularMassMatrixError.
  void dynamics(const double* q, const double* v, double t);
  void position_rates(const double* q, const double* v, double* qdot) const;

  const mbfe_model_v1& model_;
  std::vector<BodyInertia> bodies_;
  LoopClosure closure_;
  int nq_, nv_, nc_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m_row_;
  Eigen::MatrixXd m_;
  Eigen::VectorXd f_, q_force_;
};

class LoopPartitionedSystem final : public LoopSystem {
 public:
  LoopPartitionedSystem(const mbfe_model_v1& model, std::vector<BodyInertia> bodies, RigidCoordinates coordinates,
                        const double* rows_at = nullptr);

  int size() const override { return nq_ + nv_ - nc_; }
  /// @throws NewtonClosureError, SingularConstraintError, SingularMassMatrixError.
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;
  void after_step(double t, Eigen::VectorXd& y) override;
  std::string name(int i) const override;
  /// Chooses the partition at q (which must be consistent).
  Eigen::VectorXd state_of(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v) override;
  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& v) override;
  void drive_reactions(double t, const Eigen::VectorXd& y, Eigen::VectorXd& out) override;

  const LoopPartition& partition() const { return part_; }
  int repartitions() const { return repartitions_; }

  /// Choose the partition again when sigma_min(J_d) falls below this
  /// fraction of the best partition's (hysteresis against flip-flop).
  static constexpr double kRepartitionRatio = 0.1;

 private:
  // q_ closed from y, J_d factored, v_ = B v_u + w.
  void close(double t, const Eigen::VectorXd& y);

  LoopPartition part_;
  int repartitions_ = 0;
  Eigen::VectorXd q_, v_, gamma_, nu_, c_, rhs_, a_u_;
  Eigen::MatrixXd j_, jd_, ju_, b_, reduced_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
};

class LoopAugmentedSystem final : public LoopSystem {
 public:
  LoopAugmentedSystem(const mbfe_model_v1& model, std::vector<BodyInertia> bodies, RigidCoordinates coordinates,
                      const double* rows_at = nullptr);

  int size() const override { return nq_ + nv_; }
  /// @throws SingularConstraintError, SingularMassMatrixError.
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;
  /// Projects q onto Phi = 0 and v onto J v = nu. @throws NewtonClosureError.
  void after_step(double t, Eigen::VectorXd& y) override;
  std::string name(int i) const override;
  Eigen::VectorXd state_of(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v) override;
  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& v) override;
  void drive_reactions(double t, const Eigen::VectorXd& y, Eigen::VectorXd& out) override;

 private:
  Eigen::VectorXd q_, gamma_, rhs_, x_;
  Eigen::MatrixXd j_, saddle_;
};

}  // namespace mbfe::runtime
