// One adjusted structure as an operator: a beam, or beams joined by links,
// whose adjusted mass, damping and stiffness (docs/damping-adjustment.md,
// "Back to nodal coordinates") are each a multiple of one sparse base matrix
// B plus a low-rank part over the kept modes,
//
//   M_adj = mu_M B + U diag(d_M) U^T
//   C_adj = mu_C B + U diag(d_C) U^T          U = M Phi_L (n x m, never formed)
//   K_adj = mu_K B + U diag(d_K) U^T
//
// with Phi_L the kept modes (M-orthonormal, K Phi_L = M Phi_L diag(k_L)):
//
//   policy cap          B = M   (1, c*, k*)      d_M = 0, d_C = c_L - c*, d_K = k_L - k*
//   every mode, eq (27) B = M   (1, 0, 0)        d_M = 0, d_C = c,        d_K = k
//   policy mass         B = K   (1/k*, c*/k*, 1) d_M = 1 - k_L/k*, d_C = c_L - c* k_L/k*, d_K = 0
//
// B's modal value on kept mode j is b_j = 1 (B = M) or k_j (B = K), so any
// combination X = mu B + U diag(d) U^T has the inverse
//
//   X^-1 = B^-1 / mu + Phi_L diag(1 / (mu b + d) - 1 / (mu b)) Phi_L^T,
//
// one sparse solve and two passes over Phi_L: the free acceleration, the
// Newton block and the split coordinates all rest on it. (For B = K the
// closed form's 1 / (mu b) is large on the lowest modes; there the kept modes'
// part of B^-1 r / mu is taken out by projection instead: see
// free_acceleration.) The operator holds Phi_L once, row-major (the split
// coordinates read it a row at a time): a copy of the leading columns of the
// modal basis it was built from, which keeps its own.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "runtime/linalg/modal_block_solver.h"

namespace mbfe::runtime {

class LowRankStructure {
 public:
  using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  using Factor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

  /// Which sparse matrix the adjusted operators are multiples of.
  enum class Base { kMass, kStiffness };

  /// A block of the model's beam coordinates q_c that the structure covers;
  /// the structure's own (stacked) coordinates follow its ranges in order.
  struct Range {
    int offset = 0;  // first q_c index
    int size = 0;
  };

  /// mu B + U diag(d) U^T.
  struct Term {
    double mu = 0.0;
    Eigen::VectorXd d;  // m entries, always sized
  };

  /// What a builder hands over (structure/adjusted_structures.h builds them).
  struct Parts {
    std::string name;             // for messages: 'deck', or 'contact_wire+messenger'
    std::vector<Range> ranges;
    Eigen::SparseMatrix<double> M, K;  // stacked, n_s x n_s
    Eigen::VectorXd P;                 // N, the constant load, stacked (n_s)
    Base base = Base::kMass;
    RowMajorMatrix phi;           // n_s x m, the kept modes
    Eigen::VectorXd k;            // m, their modal stiffness omega_j^2 (1/s^2)
    Term mass, damping, stiffness;
    /// Eq (27): the kept modes are every mode and nothing is capped (the
    /// policies that change each mode on its own); false for the low-rank form.
    bool every_mode = false;
    /// Policy truncate: the beam moves in the kept modes alone (q = Phi_L eta);
    /// only split coordinates integrate it (CoupledDynamics::split_accelerations).
    bool truncated = false;
  };

  /// @throws std::invalid_argument when the parts do not fit together (the
  ///         message names the structure and the sizes), std::runtime_error when
  ///         B is not positive definite (a beam that nothing holds, for B = K).
  explicit LowRankStructure(Parts parts);

  const std::string& name() const { return name_; }
  int size() const { return size_; }                        // n_s
  int rank() const { return static_cast<int>(k_.size()); }  // m
  const std::vector<Range>& ranges() const { return ranges_; }
  Base base() const { return base_; }
  bool every_mode() const { return every_mode_; }
  bool truncated() const { return truncated_; }
  const Eigen::SparseMatrix<double>& M() const { return M_; }
  const Eigen::SparseMatrix<double>& K() const { return K_; }
  /// The constant load P (N), stacked, and its shares B^-1 P / mu_M and
  /// Phi_L^T P that every right-hand side starts from.
  const Eigen::VectorXd& loads() const { return P_; }
  const Eigen::VectorXd& base_load_response() const { return base_p_; }
  const Eigen::VectorXd& modal_loads() const { return phi_p_; }
  /// The sparse base matrix B (M or K).
  const Eigen::SparseMatrix<double>& B() const { return base_ == Base::kMass ? M_ : K_; }
  /// Its factorisation (shared: constant once built).
  const Factor& base_factor() const { return *factor_; }
  /// The same, to share: a beam that is a structure of its own on its M
  /// solves with it instead of a second factorisation (coupled_model.h).
  std::shared_ptr<const Factor> shared_base_factor() const { return factor_; }
  const RowMajorMatrix& phi() const { return phi_; }
  const Eigen::VectorXd& modal_stiffness() const { return k_; }
  /// b_j: B's modal value on each kept mode (1 or k_j).
  const Eigen::VectorXd& base_modal() const { return b_; }
  const Term& mass() const { return mass_; }
  const Term& damping() const { return damping_; }
  const Term& stiffness() const { return stiffness_; }

  /// Scratch of the operations below, one per thread: sized by
  /// make_workspace, never reallocated by them.
  struct Workspace {
    Eigen::VectorXd x, v, r, a, bx, bv, base_solve, modal, modal_g;
    Eigen::VectorXd ldlt;  // the sparse solves' workspace
    Eigen::Matrix<double, Eigen::Dynamic, 4> three, projected3;
    // Rows of Phi_L a split evaluation reads or loads, and their products
    // (coupled/split_coordinates.cpp); at most one per DOF, and reserved
    // for that many, so a step allocates nothing.
    std::vector<int> rows;
    std::vector<double> row_x, row_v;
    std::vector<char> row_listed;  // per DOF: already in `rows`
  };
  Workspace make_workspace() const;

  /// Gathers the structure's stacked coordinates from q_c (nc entries), and
  /// scatters (adds, or writes) them back.
  void gather(const double* qc, Eigen::VectorXd& x) const;
  void scatter_add(const Eigen::VectorXd& x, double* qc) const;
  void scatter(const Eigen::VectorXd& x, double* qc) const;

  /// fc += C_adj v + K_adj q on the structure's ranges (qc, vc, fc: the
  /// model's beam coordinates).
  void add_internal_force(const double* qc, const double* vc, double* fc, Workspace& ws) const;
  /// rc += M_adj a.
  void add_inertia(const double* ac, double* rc, Workspace& ws) const;
  /// ac = M_adj^-1 (P + f - C_adj v - K_adj q) on its ranges: the free
  /// acceleration under its constant load P and the loads f (N, over q_c;
  /// null: none), one sparse solve (none without f) and two passes over Phi_L.
  void free_acceleration(const double* qc, const double* vc, const double* fc, double* ac, Workspace& ws) const;
  /// y = (mu B + U diag(d) U^T) x over the stacked coordinates, for any term.
  void apply(const Term& term, const Eigen::VectorXd& x, Eigen::VectorXd& y, Workspace& ws) const;
  /// x = M_adj^-1 r over the stacked coordinates (r may alias nothing in ws).
  void solve_mass(const Eigen::VectorXd& r, Eigen::VectorXd& x, Workspace& ws) const;
  /// x = B^-1 r over the stacked coordinates.
  void solve_base(const Eigen::VectorXd& r, Eigen::VectorXd& x, Workspace& ws) const;

  /// c_a M_adj + c_v C_adj + c_q K_adj = mu B + U diag(d) U^T: its mu and d.
  Term combination(double c_a, double c_v, double c_q) const;
  /// `term` as a block of a larger matrix for ModalBlockSolver, its first row
  /// `row`; it points into this structure, which must outlive the solver's
  /// use of it. Needs a structure over one range.
  ModalBlock modal_block(int row, const Term& term) const;
  /// U = M Phi_L, dense n_s x m: the columns of a Woodbury correction
  /// (formed when asked, never kept).
  Eigen::MatrixXd mass_times_phi() const;
  /// Dense n_s x n_s matrix of a term (tests and small structures only).
  Eigen::MatrixXd dense(const Term& term) const;

 private:
  std::string name_;
  std::vector<Range> ranges_;
  int size_ = 0;
  Base base_;
  Eigen::SparseMatrix<double> M_, K_;
  Eigen::VectorXd P_, base_p_, phi_p_;
  std::shared_ptr<const Factor> factor_;
  RowMajorMatrix phi_;
  Eigen::VectorXd k_, b_;
  Term mass_, damping_, stiffness_;
  bool every_mode_ = false;
  bool truncated_ = false;
  // The free acceleration's modal weights (see free_acceleration):
  // a = B^-1 r / mu_M - (mu_C v + mu_K q) / mu_M + Phi_L (w_g .* g + e_v .* x_v + e_q .* x_q),
  // r = P + f, g = Phi_L^T r.
  Eigen::VectorXd w_g_, e_v_, e_q_;
  bool uses_g_ = false;  // w_g != 0 (not for B = M with d_M = 0)
};

}  // namespace mbfe::runtime
