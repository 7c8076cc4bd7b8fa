#include "runtime/damping/compliance_change.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <exception>
#include <stdexcept>
#include <string>
#include <thread>

#include "runtime/platform/thread_budget.h"

namespace mbfe::runtime {

namespace {

using Complex = std::complex<double>;
using Factor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

// Frequencies over the band [0, omega], spaced omega / 512: the change
// varies on the scale of the spacing of the structure's modes, and the
// kept modes (every one below omega under cap) contribute nothing to it.
constexpr int kBandSamples = 512;

// Points per block of ComplianceChangeEstimator::points: wide enough that a
// product with the basis runs as a matrix product (about twice the speed of
// one matrix-vector product per point, both bound by reading the basis),
// narrow enough that a wire's few hundred points give both cores work.
constexpr std::size_t kPointBlock = 32;

std::shared_ptr<Factor> factor(const Eigen::SparseMatrix<double>& A, const char* what) {
  auto f = std::make_shared<Factor>(A);
  if (f->info() != Eigen::Success || !(f->vectorD().array() > 0.0).all())
    throw std::runtime_error(std::string("the accuracy estimate needs ") + what +
                             " positive definite (a structure its supports hold)");
  return f;
}

/// 1 / (k - m Omega^2 + i Omega c): one mode's receptance per unit p^2,
/// as (a - i b) / (a^2 + b^2): std::complex's division guards infinities
/// and NaN by a library call that was most of a point figure's time, and
/// a and b here are finite and far from overflow in their squares.
Complex receptance(const ModalDynamics& mode, double omega) {
  const double a = mode.k - mode.m * omega * omega, b = omega * mode.c;
  const double norm = a * a + b * b;
  return Complex(a / norm, -b / norm);
}

}  // namespace

ComplianceChangeEstimator::ComplianceChangeEstimator(const Eigen::SparseMatrix<double>& M,
                                                     const Eigen::SparseMatrix<double>& K,
                                                     const Eigen::SparseMatrix<double>& C, const ModalBasis& basis,
                                                     std::vector<ModalDynamics> original)
    : M_(M), basis_(basis), original_(std::move(original)) {
  const Eigen::Index n = M.rows();
  if (M.cols() != n || K.rows() != n || K.cols() != n || C.rows() != n || C.cols() != n ||
      basis.phi.rows() != n || basis.phi.cols() != basis.omega.size() ||
      static_cast<Eigen::Index>(original_.size()) != basis.omega.size())
    throw std::invalid_argument("compliance estimate: M, K, C (" + std::to_string(n) + " rows), the basis (" +
                                std::to_string(basis.phi.rows()) + " x " + std::to_string(basis.phi.cols()) +
                                ") and its " + std::to_string(original_.size()) + " modal dynamics do not fit");
  k_factor_ = factor(K, "K");
  if (!basis_.complete) {
    m_factor_ = factor(M, "M");
    // The modes beyond the basis are damped as c = alpha + beta k
    // (Rayleigh): alpha and beta by least squares over the basis' modes.
    double sk = 0, skk = 0, sc = 0, skc = 0;
    const double count = static_cast<double>(original_.size());
    for (const ModalDynamics& mode : original_) {
      sk += mode.k;
      skk += mode.k * mode.k;
      sc += mode.c;
      skc += mode.k * mode.c;
    }
    const double det = count * skk - sk * sk;
    if (original_.size() >= 2 && det > 0.0) {
      beta_ = (count * skc - sk * sc) / det;
      alpha_ = (sc - beta_ * sk) / count;
    } else if (!original_.empty()) {
      beta_ = original_[0].c / original_[0].k;
    }
  }
}

ComplianceChangeEstimator::Point ComplianceChangeEstimator::point(const CompliancePoint& p) const {
  return points({p}).front();
}

std::vector<ComplianceChangeEstimator::Point> ComplianceChangeEstimator::points(
    const std::vector<CompliancePoint>& given) const {
  for (const CompliancePoint& p : given)
    if (p.e.size() != M_.rows())
      throw std::invalid_argument("compliance estimate: a point's weights have " + std::to_string(p.e.size()) +
                                  " entries, the structure " + std::to_string(M_.rows()) + " coordinates");
  std::vector<Point> out(given.size());
  const std::size_t blocks = (given.size() + kPointBlock - 1) / kPointBlock;
  const std::size_t threads = std::min<std::size_t>(blocks, static_cast<std::size_t>(thread_budget()));
  const auto block = [&](std::size_t b) {
    const std::size_t first = b * kPointBlock;
    point_block(given, first, std::min(kPointBlock, given.size() - first), out);
  };
  if (threads > 1) {
    std::atomic<std::size_t> next{0};
    std::vector<std::exception_ptr> failures(blocks);
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < threads; ++t)
      pool.emplace_back([&]() {
        for (std::size_t b = next++; b < blocks; b = next++) {
          try {
            block(b);
          } catch (...) {
            failures[b] = std::current_exception();
          }
        }
      });
    for (std::thread& t : pool) t.join();
    for (const std::exception_ptr& failure : failures)
      if (failure) std::rethrow_exception(failure);
  } else {
    for (std::size_t b = 0; b < blocks; ++b) block(b);
  }
  return out;
}

void ComplianceChangeEstimator::point_block(const std::vector<CompliancePoint>& given, std::size_t first,
                                            std::size_t count, std::vector<Point>& out) const {
  const Eigen::Index n = M_.rows(), cols = static_cast<Eigen::Index>(count);
  Eigen::MatrixXd E(n, cols);
  for (Eigen::Index c = 0; c < cols; ++c) E.col(c) = given[first + static_cast<std::size_t>(c)].e;
  const Eigen::MatrixXd X = k_factor_->solve(E);  // K^-1 e
  // p_j over the basis, from the few rows of Phi a point's weights touch.
  const Eigen::SparseMatrix<double> E_sparse = E.sparseView();
  const Eigen::MatrixXd P = basis_.phi.transpose() * E_sparse;
  Eigen::MatrixXd E_t, X_t, MX_t, ME_t;
  if (!basis_.complete) {
    // The moments of the modes beyond the basis, from the point's load
    // without the basis' share, e_t = e - M Phi p (Phi^T e_t = 0 and
    // M^-1 e_t = sum over the tail of phi_j p_j): x_t = K^-1 e_t is the
    // tail's static answer sum phi_j p_j / k_j, so sum p^2 = e_t^T M^-1 e_t,
    // sum p^2 / k = e^T x_t and sum p^2 / k^2 = x_t^T M x_t. Subtracting the
    // basis' share from the whole structure's sums instead would lose the
    // tail of sum p^2 / k^2 to round-off: the lowest mode dominates it by
    // (k_tail / k_1)^2 (1e13 on the paper beam). The solve's error lies in
    // the low modes (K^-1 amplifies them), so x_t is projected off the
    // basis once more.
    const Eigen::MatrixXd basis_share = basis_.phi * P;
    E_t = E - M_ * basis_share;
    X_t = k_factor_->solve(E_t);
    const Eigen::MatrixXd on_basis = basis_.phi.transpose() * (M_ * X_t);
    X_t -= basis_.phi * on_basis;
    MX_t = M_ * X_t;
    ME_t = m_factor_->solve(E_t);
  }
  for (Eigen::Index c = 0; c < cols; ++c) {
    const CompliancePoint& p = given[first + static_cast<std::size_t>(c)];
    Point& o = out[first + static_cast<std::size_t>(c)];
    o.series_compliance = p.series_compliance;
    o.omega = p.omega;
    o.compliance = p.e.dot(X.col(c));
    o.p2 = P.col(c).array().square().matrix();
    if (!basis_.complete) {
      o.tail0 = std::max(0.0, E_t.col(c).dot(ME_t.col(c)));
      o.tail1 = std::max(0.0, p.e.dot(X_t.col(c)));
      o.tail2 = std::max(0.0, X_t.col(c).dot(MX_t.col(c)));
    }
  }
}

ComplianceChange ComplianceChangeEstimator::evaluate(const Point& point, const AdjustedModes& adjusted,
                                                     bool band) const {
  const Eigen::Index m = point.p2.size();
  if (static_cast<Eigen::Index>(adjusted.modes.size()) != m || static_cast<Eigen::Index>(original_.size()) != m)
    throw std::invalid_argument("compliance estimate: " + std::to_string(adjusted.modes.size()) +
                                " adjusted modes for a basis of " + std::to_string(m));
  const bool tail = !basis_.complete;
  const bool mass = adjusted.policy == ir::AdjustmentPolicy::kMass;
  if (tail && adjusted.policy != ir::AdjustmentPolicy::kCap && !mass)
    throw std::invalid_argument("compliance estimate: beyond a partial basis only the policies cap and mass are known");
  const double k_star = adjusted.k_star, c_star = adjusted.c_star;

  // H_adj - H at omega: the changed modes of the basis, then the tail.
  const auto change_at = [&](double omega) {
    Complex d = 0.0;
    for (Eigen::Index j = 0; j < m; ++j)
      if (adjusted.change[j] != ModeChange::kKept)
        d += point.p2[j] * (receptance(adjusted.modes[j], omega) - receptance(original_[j], omega));
    if (tail) {
      // sum p^2 / (k (1 + i Omega beta) - Omega^2 + i Omega alpha) to first
      // order in (Omega^2 - i Omega alpha) / (k (1 + i Omega beta)): the
      // Rayleigh part i Omega beta is kept whole (Omega beta is not small
      // for a beam's stiffness-proportional damping).
      const Complex rb(1.0, omega * beta_);
      const Complex original = (point.tail1 + Complex(omega * omega, -omega * alpha_) / rb * point.tail2) / rb;
      const Complex now = mass ? point.tail1 / Complex(1.0 - omega * omega / k_star, omega * c_star / k_star)
                               : point.tail0 / Complex(k_star - omega * omega, omega * c_star);
      d += now - original;
    }
    return std::abs(d);
  };
  // The quasi-static compliance at omega: the spring and the faster modes.
  const auto quasi_static_at = [&](double omega) {
    double faster = point.series_compliance + point.tail1;
    for (Eigen::Index j = 0; j < m; ++j)
      if (original_[j].omega > omega) faster += point.p2[j] / original_[j].k;
    return faster;
  };

  ComplianceChange out;
  out.compliance = point.compliance;
  double changed = point.tail1;
  for (Eigen::Index j = 0; j < m; ++j)
    if (adjusted.change[j] != ModeChange::kKept) changed += point.p2[j] / original_[j].k;
  out.quasi_static = quasi_static_at(point.omega);
  out.changed_share = out.quasi_static > 0.0 ? changed / out.quasi_static : 0.0;
  const double static_scale = point.series_compliance + point.compliance;
  out.static_change = static_scale > 0.0 ? change_at(0.0) / static_scale : 0.0;
  out.change = out.quasi_static > 0.0 ? change_at(point.omega) / out.quasi_static : 0.0;
  // The band [0, omega]: a force there has content at every frequency up
  // to omega (a wheel crossing elements, a strip passing droppers), not at
  // omega alone; the largest change over it, each against the quasi-static
  // compliance at its own frequency.
  out.band_change = out.static_change;
  if (band && point.omega > 0.0) {
    for (int i = 1; i <= kBandSamples; ++i) {
      const double omega = point.omega * i / kBandSamples;
      const double scale = quasi_static_at(omega);
      const double here = scale > 0.0 ? change_at(omega) / scale : 0.0;
      if (here > out.band_change) {
        out.band_change = here;
        out.band_omega = omega;
      }
    }
  }
  return out;
}

}  // namespace mbfe::runtime
