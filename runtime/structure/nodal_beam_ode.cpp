#include "runtime/structure/nodal_beam_ode.h"

#include <stdexcept>

namespace mbfe::runtime {

NodalBeamOde::NodalBeamOde(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                           const Eigen::SparseMatrix<double>& C, const Eigen::VectorXd& P)
    : M_(M), K_(K), C_(C), P_(P) {
  const Eigen::Index n = M_.rows();
  if (M_.cols() != n || K_.rows() != n || K_.cols() != n || C_.rows() != n || C_.cols() != n || P_.size() != n)
    throw std::invalid_argument("NodalBeamOde: M is " + std::to_string(M_.rows()) + " x " + std::to_string(M_.cols()) +
                                ", K " + std::to_string(K_.rows()) + ", C " + std::to_string(C_.rows()) +
                                " rows, load " + std::to_string(P_.size()) + " entries; expected matching sizes");
  m_factor_.compute(M_);
  if (m_factor_.info() != Eigen::Success) throw std::runtime_error("the beam's mass matrix is not positive definite");
}

NodalBeamOde::NodalBeamOde(std::shared_ptr<const LowRankStructure> adjusted)
    : adjusted_(std::move(adjusted)), P_(adjusted_->loads()) {
  const LowRankStructure& s = *adjusted_;
  if (s.ranges().size() != 1 || s.ranges().front().offset != 0)
    throw std::invalid_argument("NodalBeamOde: the structure '" + s.name() + "' covers " + std::to_string(s.size()) +
                                " coordinates in " + std::to_string(s.ranges().size()) +
                                " ranges; expected one range from 0");
  ws_ = s.make_workspace();
}

void NodalBeamOde::rhs(double, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  const Eigen::Index n = P_.size();
  ydot.resize(2 * n);
  ydot.head(n) = y.tail(n);
  if (adjusted_) {
    w1_ = y.head(n);
    w2_ = y.tail(n);
    adjusted_->free_acceleration(w1_.data(), w2_.data(), nullptr, ydot.data() + n, ws_);
    return;
  }
  w1_.noalias() = C_ * y.tail(n);
  w1_.noalias() += K_ * y.head(n);
  w1_ = P_ - w1_;
  ydot.tail(n) = m_factor_.solve(w1_);
}

void NodalBeamOde::mult_m(const Eigen::VectorXd& x, Eigen::VectorXd& out) {
  if (adjusted_) adjusted_->apply(adjusted_->mass(), x, out, ws_);
  else out.noalias() = M_ * x;
}

void NodalBeamOde::mult_c(const Eigen::VectorXd& x, Eigen::VectorXd& out) {
  if (adjusted_) adjusted_->apply(adjusted_->damping(), x, out, ws_);
  else out.noalias() = C_ * x;
}

void NodalBeamOde::mult_k(const Eigen::VectorXd& x, Eigen::VectorXd& out) {
  if (adjusted_) adjusted_->apply(adjusted_->stiffness(), x, out, ws_);
  else out.noalias() = K_ * x;
}

void NodalBeamOde::solve_combination(double a, double b, double c, const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  if (adjusted_) {
    // (mu B + U diag(d) U^T)^-1 = B^-1 / mu + Phi_L diag(1/(mu b + d) - 1/(mu b)) Phi_L^T.
    const LowRankStructure& s = *adjusted_;
    const LowRankStructure::Term t = s.combination(a, b, c);
    const Eigen::ArrayXd base = t.mu * s.base_modal().array();  // implicit steps only
    if (!(t.mu > 0.0) || !((base + t.d.array()).abs() > 0.0).all())
      throw std::runtime_error("implicit step: a M + b C + c K is singular");
    s.solve_base(r, x, ws_);
    x /= t.mu;
    if (s.rank() > 0) {
      ws_.modal.noalias() = s.phi().transpose() * r;
      ws_.modal = (((base + t.d.array()).inverse() - base.inverse()) * ws_.modal.array()).matrix();
      x.noalias() += s.phi() * ws_.modal;
    }
    return;
  }
  if (!cached_ || a != ca_ || b != cb_ || c != cc_) {
    Eigen::SparseMatrix<double> as = a * M_;
    if (b != 0.0) as += b * C_;
    if (c != 0.0) as += c * K_;
    a_factor_.compute(as);
    if (a_factor_.info() != Eigen::Success)
      throw std::runtime_error("implicit step: a M + b C + c K could not be factorised");
    ca_ = a;
    cb_ = b;
    cc_ = c;
    cached_ = true;
  }
  x = a_factor_.solve(r);
}

std::string NodalBeamOde::name(int i) const {
  const int n = static_cast<int>(P_.size());
  return (i < n ? "q" : "qd") + std::to_string(i % n + 1);
}

}  // namespace mbfe::runtime
