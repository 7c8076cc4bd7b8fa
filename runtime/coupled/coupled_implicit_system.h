// A coupled model for the implicit steppers: the index-3 form of eqs (15),
//
//   M_b(q_b) q_b'' + F_b - Q_b - f_b + J_b^T lambda = 0
//   M_c q_c'' + C_c q_c' + K_c q_c - P_c - f_c + J_c^T lambda = 0
//   Phi(q_b, q_c) = 0
//
// as a SecondOrderSystem (second_order_system.h), y = [q_b; q_c; q_b'; q_c']
// as in the augmented formulation (whose explicit right-hand side, initial
// state and report it keeps). The residual and the Newton matrix go over the
// model's parts once each (docs/implicit-integration.md): the rigid block
// dense from the closed-form Jacobian kernel of the generated solver, every
// force element's force and tangent (slider springs, links, time loads:
// force_element.h), the beams' own sparse M, C and K, each adjusted
// structure's alpha B + U diag(d) U^T (low_rank_structure.h), and the
// contact rows G = [J_b J_c] bordering it, driven rows replaced by their
// motion's. The sparse part is one sparse LU; an adjusted structure's low
// rank joins by a Woodbury correction of the solves. Without contact rows or
// joined structures, the adjusted beams are instead blocks of known inverse
// and the Woodbury correction runs over the rows the couplings touch
// (runtime/linalg/modal_block_solver.h): far cheaper when they keep many modes.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>
#include <vector>

#include "runtime/coupled/augmented_system.h"
#include "runtime/integrators/second_order_system.h"
#include "runtime/linalg/modal_block_solver.h"
#include "runtime/linalg/woodbury.h"

namespace mbfe::runtime {

class CoupledImplicitSystem final : public AugmentedSystem, public SecondOrderSystem {
 public:
  /// @throws std::invalid_argument if a beam has no sparse form (an
  ///         adjustment that changes every mode on its own, eq (27)).
  /// `modal_blocks`: take the block form where it applies (false: always the
  /// Woodbury correction over the kept modes, the cross-check).
  explicit CoupledImplicitSystem(std::shared_ptr<CoupledDynamics> dyn, bool modal_blocks = true);
  /// Whether the adjusted beams are blocks of known inverse (see above).
  bool uses_modal_blocks() const { return modal_blocks_; }

  int dof() const override { return dyn_->n(); }
  int num_multipliers() const override { return dyn_->m(); }
  void residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                const Eigen::VectorXd& lambda, double c_q, Eigen::VectorXd& r, Eigen::VectorXd& c) override;
  void factorize(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                 const Eigen::VectorXd& lambda, double c_q, double c_v) override;
  void solve(const Eigen::VectorXd& r, const Eigen::VectorXd& c, Eigen::VectorXd& da,
             Eigen::VectorXd& dlambda) override;
  void accelerations(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, Eigen::VectorXd& a,
                     Eigen::VectorXd& lambda) override;

  /// The rigid block's tangents at (t, q_b, q_b', a_b, lambda) with q_c from
  /// q: K_b = d(M_b a + F_b - Q_b + J_b^T lambda)/dq_b and C_b = d(F_b - Q_b)/dq_b'
  /// (nb x nb each): the generated kernel `dynamics_jacobians` where the
  /// solver has one (and not force_differences), else central differences;
  /// the contact term d(J_b^T lambda)/dq_b by central differences of the
  /// contact kernels either way. Public for the tests that check one by the other.
  void rigid_tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                      const Eigen::VectorXd& lambda, Eigen::MatrixXd& K_b, Eigen::MatrixXd& C_b,
                      bool force_differences = false);

 private:
  /// The force elements' forces at (t, q, v) (motion imposed) into fb_force_ and fc_.
  void element_forces(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v);
  /// tau = M_b a + F_b - Q_b at the rigid coordinates given (motion imposed by the caller).
  void rigid_residual(double t, const double* qb, const double* vb, const double* ab, Eigen::VectorXd& tau);

  const CoupledModel& model_;
  std::vector<std::unique_ptr<ForceState>> states_;  // the elements' states: this system's scratch
  std::vector<LowRankStructure::Workspace> structure_ws_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  std::vector<Eigen::Triplet<double>> triplets_;
  Eigen::SparseMatrix<double> matrix_;
  Eigen::VectorXd qm_, vm_;
  DrivenCoordinates::Motion motion_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> mb_row_;
  Eigen::VectorXd fb_, qb_force_, fc_, tau_, tau2_, rhs_, sol_;
  Eigen::MatrixXd kb_, cb_;
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  std::vector<double> jac_k_, jac_c_;  // the kernel's row-major output
  ConstraintValues cv_;
  // The sparse matrix's correction for the adjusted structures' low rank.
  WoodburyCorrection woodbury_;
  // The block form: its solver, and the blocks' terms (their d lives here).
  bool modal_blocks_ = false;
  ModalBlockSolver block_solver_;
};

}  // namespace mbfe::runtime
