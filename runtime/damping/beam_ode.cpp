#include "runtime/damping/beam_ode.h"

#include <stdexcept>
#include <string>

namespace mbfe::runtime {

ModalBeamOde::ModalBeamOde(const ModalBasis& basis, const std::vector<ModalDynamics>& modes,
                           const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& P) {
  const int n = static_cast<int>(basis.phi.rows());
  if (!basis.complete || basis.phi.cols() != n)
    throw std::invalid_argument("modal coordinates need every mode (a complete basis)");
  if (static_cast<int>(modes.size()) != n || P.size() != n || M.rows() != n)
    throw std::invalid_argument("ModalBeamOde: " + std::to_string(modes.size()) + " modes and a load of " +
                                std::to_string(P.size()) + " entries, expected " + std::to_string(n) +
                                " (one per DOF)");
  phi_ = basis.phi;
  mphi_ = M * phi_;
  k_.resize(n);
  c_.resize(n);
  m_.resize(n);
  for (int j = 0; j < n; ++j) {
    k_[j] = modes[j].k;
    c_[j] = modes[j].c;
    m_[j] = modes[j].m;
    if (!(m_[j] > 0.0))
      throw std::invalid_argument("ModalBeamOde: mode " + std::to_string(j + 1) + " has modal mass " +
                                  std::to_string(m_[j]) + "; expected > 0");
  }
  unit_mass_ = (m_.array() == 1.0).all();
  p_ = phi_.transpose() * P;
}

void ModalBeamOde::modal_load_at(double t, Eigen::VectorXd& out) {
  out = p_;
  if (!time_loads_) return;
  time_loads_(t, forces_);
  // A few nodal forces: Phi^T f is a few rows of Phi, not a product with all of it.
  for (const NodalForce& f : forces_) out.noalias() += f.value * phi_.row(f.index).transpose();
}

void ModalBeamOde::rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  const Eigen::Index n = k_.size();
  ydot.resize(2 * n);
  ydot.head(n) = y.tail(n);
  if (time_loads_) {
    modal_load_at(t, pt_);
    ydot.tail(n) = pt_ - c_.cwiseProduct(y.tail(n)) - k_.cwiseProduct(y.head(n));
  } else {
    ydot.tail(n) = p_ - c_.cwiseProduct(y.tail(n)) - k_.cwiseProduct(y.head(n));
  }
  if (!unit_mass_) ydot.tail(n).array() /= m_.array();
}

void ModalBeamOde::solve_shifted(double, const Eigen::VectorXd&, double c, const Eigen::VectorXd& b,
                                 Eigen::VectorXd& x) {
  // (m_j + c c_j + c^2 k_j) x_v = m_j b_v - c k_j b_q, x_q = b_q + c x_v, per mode.
  const Eigen::Index n = k_.size();
  x.resize(2 * n);
  x.tail(n) = (m_.cwiseProduct(b.tail(n)) - c * k_.cwiseProduct(b.head(n))).array() /
              (m_.array() + c * c_.array() + (c * c) * k_.array());
  x.head(n) = b.head(n) + c * x.tail(n);
}

void ModalBeamOde::load(double t, Eigen::VectorXd& out) { modal_load_at(t, out); }

void ModalBeamOde::solve_combination(double a, double b, double c, const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  x = r.array() / (a * m_.array() + b * c_.array() + c * k_.array());
}

std::string ModalBeamOde::name(int i) const {
  const int n = static_cast<int>(k_.size());
  return (i < n ? "eta" : "etad") + std::to_string(i % n + 1);
}

Eigen::VectorXd ModalBeamOde::from_nodal(const Eigen::VectorXd& y) const {
  const Eigen::Index n = k_.size();
  Eigen::VectorXd out(2 * n);
  out.head(n) = mphi_.transpose() * y.head(n);
  out.tail(n) = mphi_.transpose() * y.tail(n);
  return out;
}

void ModalBeamOde::positions(const Eigen::VectorXd& y, Eigen::VectorXd& q) const {
  q.noalias() = phi_ * y.head(k_.size());
}

NodalBeamOde::NodalBeamOde(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                           const Eigen::SparseMatrix<double>& C, const Eigen::VectorXd& P)
    : M_(M), P_(P) {
  K_.S = K;
  C_.S = C;
  U_.resize(M.rows(), 0);
  phi_.resize(M.rows(), 0);
  init();
}

NodalBeamOde::NodalBeamOde(const Eigen::SparseMatrix<double>& M, const NodalAdjusted& adjusted,
                           const Eigen::VectorXd& P)
    : M_(M), K_(adjusted.K), C_(adjusted.C), U_(adjusted.U), phi_(adjusted.phi), P_(P) {
  init();
}

void NodalBeamOde::init() {
  const Eigen::Index n = M_.rows();
  if (M_.cols() != n || P_.size() != n || U_.rows() != n)
    throw std::invalid_argument("NodalBeamOde: M is " + std::to_string(M_.rows()) + " x " +
                                std::to_string(M_.cols()) + ", load has " + std::to_string(P_.size()) +
                                " entries; expected matching sizes");
  sparse_free_ = K_.S.size() == 0 && C_.S.size() == 0;
  m_factor_.compute(M_);
  if (m_factor_.info() != Eigen::Success) throw std::runtime_error("the beam's mass matrix is not positive definite");
  m_factored_ = true;
  minv_p_ = m_factor_.solve(P_);
  const Eigen::Index m = U_.cols();
  for (auto* v : {&mx_, &w1_, &w2_, &w3_}) v->resize(n);
  ux_.resize(m);
  um_.resize(m);
}

void NodalBeamOde::apply(const NodalOperator& op, const Eigen::VectorXd& x, Eigen::VectorXd& out) {
  if (op.s != 0.0) mx_.noalias() = M_ * x;
  if (op.d.size() > 0) ux_.noalias() = U_.transpose() * x;
  op.apply(x, mx_, ux_, U_, out);
}

void NodalBeamOde::solve_m(const Eigen::VectorXd& r, Eigen::VectorXd& x) { x = m_factor_.solve(r); }

void NodalBeamOde::rhs(double, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  const Eigen::Index n = P_.size();
  ydot.resize(2 * n);
  ydot.head(n) = y.tail(n);
  if (sparse_free_) {
    // M^-1 (s M x + U diag(d) U^T x) = s x + Phi diag(d) U^T x, since M^-1 U = Phi:
    // no solve with M at all.
    auto acc = ydot.tail(n);
    acc = minv_p_ - C_.s * y.tail(n) - K_.s * y.head(n);
    if (U_.cols() > 0) {
      ux_.noalias() = U_.transpose() * y.tail(n);
      um_ = C_.d.cwiseProduct(ux_);
      ux_.noalias() = U_.transpose() * y.head(n);
      um_ += K_.d.cwiseProduct(ux_);
      acc.noalias() -= phi_ * um_;
    }
    return;
  }
  w1_ = y.tail(n);
  apply(C_, w1_, w2_);
  w1_ = P_ - w2_;
  w2_ = y.head(n);
  apply(K_, w2_, w3_);
  w1_ -= w3_;
  ydot.tail(n) = m_factor_.solve(w1_);
}

void NodalBeamOde::solve_combination(double a, double b, double c, const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  if (!cached_ || a != ca_ || b != cb_ || c != cc_) {
    const double s = a + b * C_.s + c * K_.s;
    Eigen::SparseMatrix<double> as = s * M_;
    if (b != 0.0 && C_.S.size() > 0) as += b * C_.S;
    if (c != 0.0 && K_.S.size() > 0) as += c * K_.S;
    a_factor_.compute(as);
    if (a_factor_.info() != Eigen::Success)
      throw std::runtime_error("implicit step: a M + b C + c K could not be factorised");
    const Eigen::Index m = U_.cols();
    if (m > 0) {
      dd_ = Eigen::VectorXd::Zero(m);
      if (C_.d.size() > 0) dd_ += b * C_.d;
      if (K_.d.size() > 0) dd_ += c * K_.d;
      z_ = a_factor_.solve(U_);
      Eigen::MatrixXd small = Eigen::MatrixXd::Identity(m, m);
      small.noalias() += dd_.asDiagonal() * (U_.transpose() * z_);
      small_.compute(small);
    }
    ca_ = a;
    cb_ = b;
    cc_ = c;
    cached_ = true;
  }
  x = a_factor_.solve(r);
  if (U_.cols() > 0) {
    // (A_s + U D U^T) x = r: x = y - Z (I + D U^T Z)^-1 D U^T y, y = A_s^-1 r.
    um_.noalias() = U_.transpose() * x;
    um_ = dd_.cwiseProduct(um_);
    ux_ = small_.solve(um_);
    x.noalias() -= z_ * ux_;
  }
}

std::string NodalBeamOde::name(int i) const {
  const int n = static_cast<int>(P_.size());
  return (i < n ? "q" : "qd") + std::to_string(i % n + 1);
}

}  // namespace mbfe::runtime
