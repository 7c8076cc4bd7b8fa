#include "runtime/damping/compliance_change.h"

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

namespace mbfe::runtime {

namespace {

using Complex = std::complex<double>;
using Factor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

// Frequencies over the band [0, omega], spaced omega / 512: the change
// varies on the scale of the spacing of the structure's modes, and the
// kept modes (every one below omega under cap) contribute nothing to it.
constexpr int kBandSamples = 512;

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
    const Eigen::VectorXd e_t = p.e - M_ * (basis_.phi * (basis_.phi.transpose() * p.e));
    Eigen::VectorXd x_t = k_factor_->solve(e_t);
    x_t -= basis_.phi * (basis_.phi.transpose() * (M_ * x_t));
    out.tail0 = std::max(0.0, e_t.dot(m_factor_->solve(e_t)));
    out.tail1 = std::max(0.0, p.e.dot(x_t));
    out.tail2 = std::max(0.0, x_t.dot(M_ * x_t));
  }
  return out;
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
