// A coupled model without constraint contacts linearised at one state from
// its own tangents, no difference quotient of the whole right-hand side:
//
//   y' = f(t, y),  y = [z; z'],   A = df/dy = [[0, I], [-M^-1 K_t, -M^-1 C_t]]
//
// over the free coordinates z: every coordinate of [q_b; q_c] but the driven
// ones. A driven coordinate follows its motion whatever the state says, so
// its column of the full Jacobian is zero, and so is its row (q'' is the
// motion's): each adds an exact zero pair and nothing else (the full matrix
// is block triangular), and is left out here.
//
//   M    the free rows and columns of M_b(q_b); each beam's M, or its adjusted
//        structure's M_adj (low_rank_structure.h)
//   K_t  d(M a + F - Q - f)/dq at the state's accelerations a: the rigid
//        block from the generated Jacobian kernel (central differences of the
//        rigid kernels where a solver has none); each beam's K or its
//        structure's K_adj; each force element's -df/dq
//   C_t  the same for q'
//
// A force element's Jacobian is taken by central differences of its own
// force over the coordinates it reads (its tangent for the Newton matrix may
// leave terms out: force_element.h). An element's force is a few terms, so
// the quotients carry round-off of eps |f| / h, not the cancellation of the
// whole right-hand side (the adjusted beams' operators subtract terms 1e4
// times their result). The beams' and structures' parts are exact: A is
// applied with round-off only.
//
// Products by A cost a product by C_t and K_t and one solve with M (block
// diagonal: the rigid block, each beam, each structure); solves with
// A - sigma I one solve with S = sigma^2 M + sigma C_t + K_t, factored by
// the implicit integrators' solvers (a sparse LU, the structures' low rank by
// Woodbury: runtime/linalg/). Nothing of size n x n is formed.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>
#include <vector>

#include "runtime/coupled/coupled_dynamics.h"
#include "runtime/coupled/state_operator.h"
#include "runtime/linalg/modal_block_solver.h"
#include "runtime/linalg/woodbury.h"

namespace mbfe::runtime {

class CoupledTangents final : public StateOperator {
 public:
  /// The linearisation of `dynamics`' model at (t, q, qd) (n entries each;
  /// the driven coordinates are taken from their motion at t). `dynamics` is
  /// evaluated there (its data is left at that state) and must outlive this object.
  /// @throws std::invalid_argument for a model with constraint contacts (their
  ///         Jacobian on the constraint manifold is the partitioned system's:
  ///         linearization.h differentiates that), or vectors of the wrong size;
  ///         what CoupledDynamics::evaluate and solve_augmented throw.
  CoupledTangents(CoupledDynamics& dynamics, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd);

  /// Free coordinates (n_f): the rigid ones that are not driven, then every beam DOF.
  int size() const override { return nf_; }
  /// The free rigid coordinates: the first of the free coordinates.
  int rigid_size() const { return nfb_; }
  /// Their indices in [q_b; q_c], ascending.
  const std::vector<int>& free_coordinates() const { return free_; }
  /// Driven coordinates left out: each is a zero pair of the full A.
  int num_driven() const override { return num_driven_; }

  /// y = M x, C_t x, K_t x over the free coordinates (n_f entries each).
  void apply_mass(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  void apply_damping(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  void apply_stiffness(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// x = M^-1 r.
  void solve_mass(const Eigen::VectorXd& r, Eigen::VectorXd& x) const;

  /// out = A in (2 n_f entries each, [z; z']).
  void apply_state_matrix(const double* in, double* out) const override;

  /// Factors S = sigma^2 M + sigma C_t + K_t for solve_shifted (sigma in 1/s).
  /// @throws std::runtime_error when S is singular (sigma an eigenvalue: a
  ///         zero mode for sigma = 0).
  void factorize_shifted(double sigma) override;
  double shift() const override { return sigma_; }
  /// out = (A - sigma I)^-1 in, sigma of the last factorize_shifted.
  void solve_shifted(const double* in, double* out) const override;

  /// A as a dense matrix (2 n_f square; small models and tests).
  Eigen::MatrixXd dense_state_matrix() const override;

  /// M, C_t and K_t without the structures' parts (the rigid block, the
  /// beams outside structures, the force elements), over the free
  /// coordinates: what a projection on a structure's modes adds to the
  /// structures' own modal terms (truncated_tangents.h).
  const Eigen::SparseMatrix<double>& mass_without_structures() const { return mass_; }
  const Eigen::SparseMatrix<double>& damping_without_structures() const { return damping_; }
  const Eigen::SparseMatrix<double>& stiffness_without_structures() const { return stiffness_; }
  /// The model the tangents are of.
  const CoupledModel& model() const { return model_; }


 private:
  enum class Part { kMass, kDamping, kStiffness };
  void apply(Part part, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd& y) const;
  // y = P1 x1 + P2 x2, the structures' low-rank parts in one pass over their
  // kept modes each way (a product by A reads Phi_L twice, not four times).
  void apply_sum(Part p1, const Eigen::Ref<const Eigen::VectorXd>& x1, Part p2,
                 const Eigen::Ref<const Eigen::VectorXd>& x2, Eigen::VectorXd& y) const;
  void element_tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                        std::vector<Eigen::Triplet<double>>& k, std::vector<Eigen::Triplet<double>>& c) const;

  const CoupledModel& model_;
  int nb_ = 0, nfb_ = 0, nf_ = 0, num_driven_ = 0;
  std::vector<int> free_, free_of_;  // free -> full, full -> free (-1: driven)
  // Everything but the structures, over the free coordinates.
  Eigen::SparseMatrix<double> mass_, damping_, stiffness_;
  Eigen::PartialPivLU<Eigen::MatrixXd> rigid_mass_lu_;
  // The structures' workspaces (mutable scratch of the const operations).
  mutable std::vector<LowRankStructure::Workspace> ws_;
  mutable Eigen::VectorXd gx_, gy_, tmp_, tmp2_, rhs_, sol_;
  mutable Eigen::MatrixXd pair_, modal_pair_;
  // The shifted matrix: blocks of known inverse, or a sparse LU with the
  // structures' low rank by Woodbury.
  double sigma_ = 0.0;
  bool factored_ = false, blocks_ = false;
  mutable ModalBlockSolver block_solver_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  mutable WoodburyCorrection woodbury_;
};

}  // namespace mbfe::runtime
