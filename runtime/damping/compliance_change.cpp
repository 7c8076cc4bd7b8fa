#include "runtime/damping/compliance_change.h"

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

namespace mbfe::runtime {

namespace {

using Complex = std::complex<double>;
using Factor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

std::shared_ptr<Factor> factor(const Eigen::SparseMatrix<double>& A, const char* what) {
  auto f = std::make_shared<Factor>(A);
  if (f->info() != Eigen::Success || !(f->vectorD().array() > 0.0).all())
    throw std::runtime_error(std::string("the accuracy estimate needs ") + what +
                             " positive definite (a structure its supports hold)");
  return f;
}

/// 1 / (k - m Omega^2 + i Omega c): one mode's receptance per unit p^2.
Complex receptance(const ModalDynamics& mode, double omega) {
  return 1.0 / Complex(mode.k - mode.m * omega * omega, omega * mode.c);
}

}  // namespace

ComplianceChangeEstimator::ComplianceChangeEstimator(const Eigen::SparseMatrix<double>& M,
                                                     const Eigen::SparseMatrix<double>& K,
                                                     const Eigen::SparseMatrix<double>& C, const ModalBasis& basis,
                                                     std::vector<ModalDynamics> original)
    : M_(M), C_(C), basis_(basis), original_(std::move(original)) {
  const Eigen::Index n = M.rows();
  if (M.cols() != n || K.rows() != n || K.cols() != n || C.rows() != n || C.cols() != n ||
      basis.phi.rows() != n || basis.phi.cols() != basis.omega.size() ||
      static_cast<Eigen::Index>(original_.size()) != basis.omega.size())
    throw std::invalid_argument("compliance estimate: M, K, C (" + std::to_string(n) + " rows), the basis (" +
                                std::to_string(basis.phi.rows()) + " x " + std::to_string(basis.phi.cols()) +
                                ") and its " + std::to_string(original_.size()) + " modal dynamics do not fit");
  k_factor_ = factor(K, "K");
  if (!basis_.complete) m_factor_ = factor(M, "M");
}

ComplianceChangeEstimator::Point ComplianceChangeEstimator::point(const CompliancePoint& p) const {
  if (p.e.size() != M_.rows())
    throw std::invalid_argument("compliance estimate: a point's weights have " + std::to_string(p.e.size()) +
                                " entries, the structure " + std::to_string(M_.rows()) + " coordinates");
  Point out;
  out.series_compliance = p.series_compliance;
  out.omega = p.omega;
  const Eigen::VectorXd x = k_factor_->solve(p.e);  // K^-1 e
  out.compliance = p.e.dot(x);
  out.p2 = (basis_.phi.transpose() * p.e).array().square().matrix();
  if (!basis_.complete) {
    // The moments of the modes beyond the basis: the whole structure's minus
    // the basis' share. Over every mode (M^-1 = Phi Phi^T, K^-1 = Phi
    // diag(1/k) Phi^T): sum p^2 = e^T M^-1 e, sum p^2 / k = e^T K^-1 e,
    // sum p^2 / k^2 = e^T K^-1 M K^-1 e, and sum p^2 c / k^2 = e^T K^-1 C K^-1 e
    // when Phi^T C Phi is diagonal (Rayleigh; otherwise it is the nodal
    // receptance's own first-order term).
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, sd = 0.0;
    for (Eigen::Index j = 0; j < out.p2.size(); ++j) {
      const double k = original_[j].k;
      s0 += out.p2[j];
      s1 += out.p2[j] / k;
      s2 += out.p2[j] / (k * k);
      sd += out.p2[j] * original_[j].c / (k * k);
    }
    const Eigen::VectorXd y = m_factor_->solve(p.e);  // M^-1 e
    // Each difference is a sum of non-negative terms: round-off may leave a
    // tiny negative one, which means none.
    out.tail0 = std::max(0.0, p.e.dot(y) - s0);
    out.tail1 = std::max(0.0, out.compliance - s1);
    out.tail2 = std::max(0.0, x.dot(M_ * x) - s2);
    out.tail_damping = std::max(0.0, x.dot(C_ * x) - sd);
  }
  return out;
}

ComplianceChange ComplianceChangeEstimator::evaluate(const Point& point, const AdjustedModes& adjusted) const {
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
      const Complex original = point.tail1 + omega * omega * point.tail2 - Complex(0.0, omega * point.tail_damping);
      const Complex now = mass ? point.tail1 / Complex(1.0 - omega * omega / k_star, omega * c_star / k_star)
                               : point.tail0 / Complex(k_star - omega * omega, omega * c_star);
      d += now - original;
    }
    return std::abs(d);
  };

  ComplianceChange out;
  out.compliance = point.compliance;
  double faster = 0.0, changed = 0.0;
  for (Eigen::Index j = 0; j < m; ++j) {
    const double share = point.p2[j] / original_[j].k;
    if (original_[j].omega > point.omega) faster += share;
    if (adjusted.change[j] != ModeChange::kKept) changed += share;
  }
  faster += point.tail1;
  changed += point.tail1;
  out.quasi_static = point.series_compliance + faster;
  out.changed_share = out.quasi_static > 0.0 ? changed / out.quasi_static : 0.0;
  const double static_scale = point.series_compliance + point.compliance;
  out.static_change = static_scale > 0.0 ? change_at(0.0) / static_scale : 0.0;
  out.change = out.quasi_static > 0.0 ? change_at(point.omega) / out.quasi_static : 0.0;
  return out;
}

}  // namespace mbfe::runtime
