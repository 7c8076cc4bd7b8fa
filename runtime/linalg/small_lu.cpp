#include "runtime/linalg/small_lu.h"

#include "runtime/linalg/inverse_norm.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace mbfe::runtime {

void SmallLu::compute(const Eigen::MatrixXd& a) {
  if (a.rows() != a.cols()) throw std::invalid_argument("SmallLu: matrix is not square");
  const int n = static_cast<int>(a.rows());
  lu_ = a;  // same size as last time: no allocation
  perm_.resize(n);
  work_.resize(n);
  norm_ = a.norm();
  inverse_valid_ = false;
  nonsingular_ = true;
  for (int i = 0; i < n; ++i) perm_[i] = i;
  det_abs_ = 1.0;
  for (int k = 0; k < n; ++k) {
    int pivot = k;
    double biggest = std::abs(lu_(k, k));
    for (int i = k + 1; i < n; ++i) {
      if (std::abs(lu_(i, k)) > biggest) {
        biggest = std::abs(lu_(i, k));
        pivot = i;
      }
    }
    if (pivot != k) {
      lu_.row(k).swap(lu_.row(pivot));
      std::swap(perm_[k], perm_[pivot]);
    }
    const double diag = lu_(k, k);
    det_abs_ *= std::abs(diag);
    if (diag == 0.0 || !std::isfinite(diag)) {
      nonsingular_ = false;
      continue;  // column already zero below the diagonal (or NaN): nothing to eliminate
    }
    for (int i = k + 1; i < n; ++i) {
      const double l = lu_(i, k) / diag;
      lu_(i, k) = l;
      for (int j = k + 1; j < n; ++j) lu_(i, j) -= l * lu_(k, j);
    }
  }
}

void SmallLu::solve_in_place(double* x) const {
  const int n = size();
  for (int i = 0; i < n; ++i) work_[i] = x[perm_[i]];
  for (int i = 0; i < n; ++i) {
    double s = work_[i];
    for (int j = 0; j < i; ++j) s -= lu_(i, j) * work_[j];
    work_[i] = s;
  }
  for (int i = n - 1; i >= 0; --i) {
    double s = work_[i];
    for (int j = i + 1; j < n; ++j) s -= lu_(i, j) * x[j];
    x[i] = s / lu_(i, i);
  }
}

void SmallLu::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  if (b.size() != size()) throw std::invalid_argument("SmallLu::solve: size mismatch");
  x = b;
  solve_in_place(x.data());
}

void SmallLu::solve(const Eigen::MatrixXd& b, Eigen::MatrixXd& x) const {
  if (b.rows() != size()) throw std::invalid_argument("SmallLu::solve: size mismatch");
  x = b;
  for (Eigen::Index c = 0; c < x.cols(); ++c) solve_in_place(x.col(c).data());
}

double SmallLu::sigma_min_lower_cheap() const {
  const int n = size();
  if (n == 0) return 1.0;
  if (!nonsingular_) return 0.0;
  double power = 1.0;  // ||A||_F^(n-1); std::pow costs more than the LU at n = 3
  for (int i = 1; i < n; ++i) power *= norm_;
  // An underflowed or overflowed power would turn the bound into inf or 0/0: no bound then.
  return power > 0.0 && std::isfinite(power) ? det_abs_ / power : 0.0;
}

double SmallLu::rcond_lower_cheap() const {
  const int n = size();
  if (n == 0) return 1.0;
  if (!nonsingular_) return 0.0;
  double power = 1.0;
  for (int i = 0; i < n; ++i) power *= norm_;
  return power > 0.0 && std::isfinite(power) ? det_abs_ / power : 0.0;
}

double SmallLu::inverse_norm() {
  if (inverse_valid_) return inverse_norm_;
  inverse_norm_ = nonsingular_ ? inverse_frobenius_norm(size(), inverse_column_,
                                                         [this](Eigen::Index c, Eigen::VectorXd& x) {
                                                           x[c] = 1.0;
                                                           solve_in_place(x.data());
                                                         })
                               : INFINITY;
  inverse_valid_ = true;
  return inverse_norm_;
}

}  // namespace mbfe::runtime
