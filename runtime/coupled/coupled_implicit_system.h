// A coupled model for the implicit steppers: the index-3 form of eqs (15),
//
//   M_b(q_b) q_b'' + F_b - Q_b + J_b^T lambda = 0
//   M_c q_c'' + C_c q_c' + K_c q_c - P_c + J_c^T lambda = 0
//   Phi(q_b, q_c) = 0
//
// as a SecondOrderSystem (second_order_system.h), y = [q_b; q_c; q_b'; q_c']
// as in the augmented formulation (whose explicit right-hand side, initial
// state and report it keeps). The Newton matrix keeps the structure
// (docs/implicit-integration.md): the beams' constant sparse M, C and K as
// they are, the rigid block dense from the closed-form Jacobian kernel of the
// generated solver, each slider_spring and each taut link as the rank-one
// term k g g^T (c g g^T for its damper), and the contact rows G = [J_b J_c] bordering it;
// the whole is one sparse LU. A low-rank adjusted beam (C = c* M + U diag(d_C) U^T,
// likewise K) puts its sparse part there and its low-rank part into a
// Woodbury correction of the solves; so does a joined structure, whose
// low-rank part spans its beams (coupled_beam.h). Without contact rows or
// joined structures, the low-rank beams are instead blocks of known inverse
// and the Woodbury correction runs over the rows the couplings touch
// (modal_block_solver.h): far cheaper when the beams keep many modes.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>
#include <vector>

#include "runtime/integrators/second_order_system.h"
#include "runtime/coupled/augmented_system.h"
#include "runtime/coupled/contact_springs.h"
#include "runtime/linalg/modal_block_solver.h"

namespace mbfe::runtime {

class CoupledImplicitSystem final : public AugmentedSystem, public SecondOrderSystem {
 public:
  /// @throws std::invalid_argument if a beam has no sparse C and K (an
  ///         adjustment that changes every mode on its own, eq (27)).
  /// `modal_blocks`: take the block form where it applies (false: always the
  /// Woodbury correction over the kept modes, the cross-check).
  explicit CoupledImplicitSystem(std::shared_ptr<CoupledDynamics> dyn, bool modal_blocks = true);
  /// Whether the low-rank beams are blocks of known inverse (see above).
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
  /// The Woodbury data of the low-rank beams after the sparse LU.
  /// @throws std::runtime_error if the capacity matrix is singular.
  void factorize_low_rank(double t, double c_q, double c_v);
  /// The entries of y ([q_b; q_c], or rates) on a joined structure's beams, stacked.
  void stack_joined(const JoinedLowRank& js, const Eigen::VectorXd& y, Eigen::VectorXd& out) const;
  /// tau = M_b a + F_b - Q_b at the rigid coordinates given (motion imposed by the caller).
  void rigid_residual(double t, const double* qb, const double* vb, const double* ab, Eigen::VectorXd& tau);

  ContactSprings springs_;
  BeamLinks links_;  // a copy: its states are this system's scratch
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  std::vector<Eigen::Triplet<double>> triplets_;
  Eigen::SparseMatrix<double> matrix_;
  Eigen::VectorXd qm_, vm_, motion_q_, motion_v_, motion_a_;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> mb_row_;
  Eigen::VectorXd fb_, qb_force_, fc_, tau_, tau2_, rhs_, sol_;
  Eigen::MatrixXd kb_, cb_;
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  std::vector<double> jac_k_, jac_c_;  // the kernel's row-major output
  ConstraintValues cv_;
  std::vector<NodalForce> nodal_;
  std::vector<bool> is_driven_;
  // Woodbury (factorize_low_rank): W (n + m x width), Z = B^-1 W, D, and the
  // LU of I + D W^T Z; one block of columns per low-rank beam.
  struct LowRankBlock {
    int beam = 0, row = 0, col = 0;
  };
  std::vector<LowRankBlock> low_rank_beams_;
  Eigen::MatrixXd low_rank_w_, low_rank_z_;
  Eigen::VectorXd low_rank_d_, low_rank_s_, low_rank_r_;
  Eigen::VectorXd joined_x_, joined_v_;
  Eigen::PartialPivLU<Eigen::MatrixXd> capacity_lu_;
  // The block form: its solver, and each low-rank beam's factored M.
  bool modal_blocks_ = false;
  ModalBlockSolver block_solver_;
  std::vector<std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>> block_mass_;
};

}  // namespace mbfe::runtime
