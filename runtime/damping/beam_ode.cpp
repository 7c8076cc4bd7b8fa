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

}  // namespace mbfe::runtime
