// A banded QR factorisation for the sparse modal analysis's shift-invert
// solves with a stiffness factor (modal_analysis.cpp, FactorQrShiftInvert).
#pragma once

#include <Eigen/SparseCore>
#include <vector>

namespace mbfe::runtime {

/// Upper-triangular banded R of a QR factorisation A = Q R of a sparse matrix
/// whose rows each span a few consecutive columns, by Givens rotations that
/// add one row at a time (rows taken in order of their first column; R's
/// band is as wide as the widest row). O(rows x width^2) time, O(n width)
/// memory.
class BandedQr {
 public:
  /// @throws std::runtime_error if A has rank < cols (singular A^T A).
  explicit BandedQr(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A);

  /// y = (R^T R)^{-1} x = (A^T A)^{-1} x (x, y: cols() entries).
  void solve_normal(const double* x, double* y) const;

  Eigen::Index cols() const { return n_; }
  /// The band's width: the widest row of A.
  Eigen::Index width() const { return width_; }

 private:
  Eigen::Index n_ = 0;
  Eigen::Index width_ = 1;
  std::vector<double> band_;  // row j: R(j, j .. j + width - 1)
};

}  // namespace mbfe::runtime
