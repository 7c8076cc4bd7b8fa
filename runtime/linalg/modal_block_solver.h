// Solves with a Newton matrix whose low-rank adjusted beams are diagonal
// blocks of known inverse (docs/implicit-integration.md, "Low-rank beams as
// blocks"):
//
//   N = A + E,   A = blockdiag(A_rest, A_1, ..., A_L),
//   A_k = alpha_k B_k + U_k diag(d_k) U_k^T,   U_k = M_k Phi_k,   Phi_k^T M_k Phi_k = I,
//   A_k^-1 = B_k^-1 / alpha_k + Phi_k diag(1/(alpha_k b_k + d_k) - 1/(alpha_k b_k)) Phi_k^T,
//
// B_k the block's base matrix, M_k or K_k, with modal values b_k on Phi_k (1,
// or the modes' stiffness: runtime/structure/low_rank_structure.h),
// A_rest the rest of N (rigid coordinates, other beams; sparse LU) and E the
// couplings (contacts, links, rigid-beam terms), nonzero on a few rows R and
// columns S. Woodbury over them, not over the kept modes:
//
//   N^-1 = A^-1 - A^-1 P_R (I + E_RS (A^-1)_SR)^-1 E_RS P_S^T A^-1,
//
// so factorising costs |R| solves with each M_k and a dense |R| x |R| LU, and
// a solve three passes over each Phi_k; no matrix as wide as the kept modes is
// ever formed or factored. Rows and columns are kept apart so that a row E
// leaves alone (a driven coordinate's) keeps its solution exactly.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <vector>

namespace mbfe::runtime {

/// One block alpha B + U diag(d) U^T of N, U = M Phi.
struct ModalBlock {
  int row = 0;  // its first row (and column) in N
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>* base_factor = nullptr;       // of B, n_k x n_k
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>* phi = nullptr;  // n_k x m_k
  const Eigen::VectorXd* base_modal = nullptr;  // b, m_k entries; null: all 1 (B = M)
  double alpha = 0.0;  // > 0
  Eigen::VectorXd d;   // m_k, alpha b_j + d_j != 0
};

class ModalBlockSolver {
 public:
  /// `entries`: every entry of N (size x size, summed where repeated) except
  /// the blocks' own alpha B + U diag(d) U^T. The pointers in `blocks` must
  /// outlive the solves.
  /// @throws std::runtime_error naming what is singular (the rest, a block, or the couplings).
  void factorize(int size, const std::vector<Eigen::Triplet<double>>& entries, std::vector<ModalBlock> blocks);
  /// x = N^-1 b.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// The coupled rows R of the last factorisation (the capacity matrix's size).
  int num_coupled() const { return static_cast<int>(rows_.list.size()); }

 private:
  // A set of rows (or columns) of N: ascending, each one's position in it,
  // and per block its members (local indices; consecutive in the list, from
  // position `first`).
  struct Coupled {
    std::vector<int> list, pos, first;
    std::vector<std::vector<int>> in_block;
  };
  void index(std::vector<int> members, Coupled& out) const;
  // x = A^-1 b; `sparse_at_rows`: b is zero outside R (one pass fewer).
  void apply_block_inverse(const Eigen::VectorXd& b, Eigen::VectorXd& x, bool sparse_at_rows);

  int size_ = 0;
  std::vector<ModalBlock> blocks_;
  std::vector<Eigen::VectorXd> weights_;  // per block: 1/(alpha + d) - 1/alpha
  std::vector<int> block_of_, rest_index_, rest_global_;
  Coupled rows_, cols_;  // R and S
  Eigen::SparseMatrix<double> rest_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> rest_lu_;
  Eigen::MatrixXd coupling_;  // E_RS
  Eigen::PartialPivLU<Eigen::MatrixXd> capacity_lu_;  // of D_r (I + E_RS G) D_c, G = (A^-1)_SR
  Eigen::VectorXd row_scale_, col_scale_;
  Eigen::VectorXd rest_b_, rest_x_, block_b_, block_x_, modal_, y_, v_, z_;
};

}  // namespace mbfe::runtime
