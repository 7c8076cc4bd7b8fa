// LU factorisation of the small square systems of the partitioned solver (the
// m x m J_v, the nb x nb reduced matrix of eqs (16)-(17)) with exact
// conditioning figures, and no allocation once sized.
//
// Why not Eigen::PartialPivLU: at these sizes (a few rows, solved several
// times per step) its dynamic-size path goes through the blocked level-3
// kernels (packing, blocking heuristics, heap work space), and rcond()
// allocates and adds several solves; together they cost more than the
// arithmetic. This is the textbook algorithm (Golub & Van Loan, Alg. 3.4.1,
// partial pivoting) on a preallocated matrix.
//
// The inverse is cheap here, so the conditioning figures are bounds instead
// of estimates (rigorous for the matrix actually factored, which is A plus a
// rounding error of ~n eps ||A||; the callers' 1e-13 thresholds leave ~1e3
// ulps of margin):
//   sigma_min(A) >= 1 / ||A^-1||_F,
//   rcond_2(A) = 1 / (||A||_2 ||A^-1||_2) >= 1 / (||A||_F ||A^-1||_F).
// A singular A (a zero or NaN pivot) makes both bounds 0, and a NaN elsewhere
// makes them NaN, which fails every `>=` test: compare them that way.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mbfe::runtime {

class SmallLu {
 public:
  /// Factors the square matrix `a`: P A = L U, L unit lower triangular.
  void compute(const Eigen::MatrixXd& a);

  int size() const { return static_cast<int>(lu_.rows()); }
  /// False after a zero pivot (exactly singular): solves then give inf/NaN.
  bool nonsingular() const { return nonsingular_; }

  /// x = A^-1 b (x resized if needed; x may not alias b).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  /// X = A^-1 B column by column (X resized if needed; X may not alias B).
  void solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) const;

  /// ||A^-1||_F, exact up to rounding (computed once per compute()).
  double inverse_norm();

  /// Cheaper, looser bounds from the pivots alone (no solve):
  ///   sigma_min(A) >= |det A| / ||A||_F^(n-1),  rcond_2(A) >= |det A| / ||A||_F^n,
  /// since sigma_min = |det A| / (sigma_1 ... sigma_(n-1)) and sigma_i <= ||A||_F.
  /// Tight for well-conditioned matrices; 0 after an underflow (fall back on
  /// the bounds below).
  double sigma_min_lower_cheap() const;
  double rcond_lower_cheap() const;

  /// A lower bound of the smallest singular value: 1 / ||A^-1||_F (1 for an
  /// empty matrix, 0 for a singular one).
  double sigma_min_lower() {
    if (size() == 0) return 1.0;
    return nonsingular_ ? 1.0 / inverse_norm() : 0.0;
  }

  /// A lower bound of the reciprocal 2-norm condition number (1 for an empty
  /// matrix, 0 for a singular one): 1 / (||A||_F ||A^-1||_F).
  double rcond_lower() {
    if (size() == 0) return 1.0;
    return nonsingular_ ? 1.0 / (norm_ * inverse_norm()) : 0.0;
  }

 private:
  // In-place: x <- U^-1 L^-1 P x for one column of length n.
  void solve_in_place(double* x) const;

  Eigen::MatrixXd lu_;      // L below the diagonal (unit diagonal implied), U on and above
  std::vector<int> perm_;   // row i of P A is row perm_[i] of A
  mutable std::vector<double> work_;
  Eigen::VectorXd inverse_column_;
  double norm_ = 0.0, inverse_norm_ = 0.0, det_abs_ = 0.0;
  bool nonsingular_ = true, inverse_valid_ = false;
};

}  // namespace mbfe::runtime
