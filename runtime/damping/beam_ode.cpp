#include "runtime/damping/beam_ode.h"

#include <Eigen/LU>
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

void ModalBeamOde::set_damping_remainder(const std::vector<std::pair<int, double>>& remainder) {
  const Eigen::Index n = k_.size();
  phi_r_.resize(static_cast<Eigen::Index>(remainder.size()), n);
  remainder_.resize(static_cast<Eigen::Index>(remainder.size()));
  for (std::size_t i = 0; i < remainder.size(); ++i) {
    const auto [dof, value] = remainder[i];
    if (dof < 0 || dof >= n)
      throw std::invalid_argument("ModalBeamOde: damping on DOF " + std::to_string(dof) + " of " +
                                  std::to_string(n));
    phi_r_.row(static_cast<Eigen::Index>(i)) = phi_.row(dof);
    remainder_[static_cast<Eigen::Index>(i)] = value;
  }
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
  if (remainder_.size() > 0) {
    v_r_.noalias() = phi_r_ * y.tail(n);
    v_r_.array() *= remainder_.array();
    ydot.tail(n).noalias() -= phi_r_.transpose() * v_r_;
  }
  if (!unit_mass_) ydot.tail(n).array() /= m_.array();
}

void ModalBeamOde::mult_c(const Eigen::VectorXd& x, Eigen::VectorXd& out) {
  out = c_.cwiseProduct(x);
  if (remainder_.size() == 0) return;
  const Eigen::VectorXd v = remainder_.cwiseProduct(phi_r_ * x);
  out.noalias() += phi_r_.transpose() * v;
}

void ModalBeamOde::solve_damped(const Eigen::VectorXd& d, double s, const Eigen::VectorXd& rhs,
                                Eigen::VectorXd& x) const {
  x = rhs.cwiseQuotient(d);
  if (remainder_.size() == 0 || s == 0.0) return;
  // Woodbury: x = D^-1 (rhs - Phi_r^T y), (I + s R Phi_r D^-1 Phi_r^T) y = s R Phi_r D^-1 rhs.
  const Eigen::MatrixXd scaled = phi_r_ * d.cwiseInverse().asDiagonal();  // Phi_r D^-1
  Eigen::MatrixXd capacity = s * remainder_.asDiagonal() * (scaled * phi_r_.transpose());
  capacity.diagonal().array() += 1.0;
  const Eigen::VectorXd y = capacity.partialPivLu().solve(s * remainder_.cwiseProduct(phi_r_ * x));
  x.noalias() -= scaled.transpose() * y;
}

void ModalBeamOde::solve_shifted(double, const Eigen::VectorXd&, double c, const Eigen::VectorXd& b,
                                 Eigen::VectorXd& x) {
  // (M + c C + c^2 K) x_v = M b_v - c K b_q, x_q = b_q + c x_v: per mode,
  // but for the discrete parts' damping.
  const Eigen::Index n = k_.size();
  x.resize(2 * n);
  Eigen::VectorXd v;
  solve_damped(m_.array() + c * c_.array() + (c * c) * k_.array(), c,
               m_.cwiseProduct(b.tail(n)) - c * k_.cwiseProduct(b.head(n)), v);
  x.tail(n) = v;
  x.head(n) = b.head(n) + c * x.tail(n);
}

void ModalBeamOde::load(double t, Eigen::VectorXd& out) { modal_load_at(t, out); }

void ModalBeamOde::solve_combination(double a, double b, double c, const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  solve_damped(a * m_.array() + b * c_.array() + c * k_.array(), b, r, x);
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
