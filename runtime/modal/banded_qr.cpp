#include "runtime/modal/banded_qr.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mbfe::runtime {

BandedQr::BandedQr(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A) : n_(A.cols()) {
  struct Span {
    Eigen::Index row, first, last;
  };
  std::vector<Span> spans;
  spans.reserve(A.rows());
  for (Eigen::Index r = 0; r < A.rows(); ++r) {
    Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, r);
    if (!it) continue;
    Span sp{r, it.col(), it.col()};
    for (; it; ++it) sp.last = std::max<Eigen::Index>(sp.last, it.col());
    width_ = std::max<Eigen::Index>(width_, sp.last - sp.first + 1);
    spans.push_back(sp);
  }
  std::stable_sort(spans.begin(), spans.end(),
                   [](const Span& a, const Span& b) { return a.first < b.first; });
  band_.assign(static_cast<size_t>(n_ * width_), 0.0);
  std::vector<char> set(n_, 0);
  std::vector<double> v(static_cast<size_t>(width_));
  for (const Span& sp : spans) {
    std::fill(v.begin(), v.end(), 0.0);
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, sp.row); it; ++it)
      v[it.col() - sp.first] = it.value();
    // v holds columns j .. j + width - 1 as j advances (a rolling window).
    for (Eigen::Index j = sp.first; j < n_; ++j) {
      double* rj = &band_[static_cast<size_t>(j * width_)];
      if (!set[j]) {
        std::copy(v.begin(), v.end(), rj);
        set[j] = 1;
        break;
      }
      const double x = v[0];
      if (x != 0.0) {
        const double h = std::hypot(rj[0], x);
        const double c = rj[0] / h;
        const double s = x / h;
        for (Eigen::Index t = 0; t < width_; ++t) {
          const double a = rj[t];
          const double b = v[t];
          rj[t] = c * a + s * b;
          v[t] = -s * a + c * b;
        }
      }
      // Shift the window by one column: v and R row j + 1 both cover columns
      // j + 1 .. j + width, so every rotation stays inside the band.
      std::rotate(v.begin(), v.begin() + 1, v.end());
      v.back() = 0.0;
      bool any = false;
      for (double e : v) any = any || e != 0.0;
      if (!any) break;
    }
  }
  for (Eigen::Index j = 0; j < n_; ++j) {
    if (!set[j] || band_[static_cast<size_t>(j * width_)] == 0.0) {
      throw std::runtime_error("sparse modal analysis: K - sigma M is singular (column " +
                               std::to_string(j) + "); rigid modes need a shift < 0");
    }
  }
}

void BandedQr::solve_normal(const double* x, double* y) const {
  std::copy(x, x + n_, y);
  // R^T z = x (forward): z_j = (x_j - sum_{i<j} R(i,j) z_i) / R(j,j).
  for (Eigen::Index j = 0; j < n_; ++j) {
    double acc = y[j];
    for (Eigen::Index i = std::max<Eigen::Index>(0, j - width_ + 1); i < j; ++i)
      acc -= band_[static_cast<size_t>(i * width_ + (j - i))] * y[i];
    y[j] = acc / band_[static_cast<size_t>(j * width_)];
  }
  // R y = z (backward).
  for (Eigen::Index j = n_ - 1; j >= 0; --j) {
    double acc = y[j];
    const double* rj = &band_[static_cast<size_t>(j * width_)];
    for (Eigen::Index t = 1; t < width_ && j + t < n_; ++t) acc -= rj[t] * y[j + t];
    y[j] = acc / rj[0];
  }
}

}  // namespace mbfe::runtime
