#include "runtime/structure/low_rank_structure.h"

#include <sstream>
#include <stdexcept>

#include "runtime/linalg/row_products.h"
#include "runtime/linalg/sparse_ldlt_solve.h"

namespace mbfe::runtime {

namespace {

std::string shape(const Eigen::SparseMatrix<double>& a) {
  return std::to_string(a.rows()) + " x " + std::to_string(a.cols());
}

}  // namespace

LowRankStructure::LowRankStructure(Parts parts)
    : name_(std::move(parts.name)),
      ranges_(std::move(parts.ranges)),
      base_(parts.base),
      M_(std::move(parts.M)),
      K_(std::move(parts.K)),
      P_(std::move(parts.P)),
      phi_(std::move(parts.phi)),
      k_(std::move(parts.k)),
      mass_(std::move(parts.mass)),
      damping_(std::move(parts.damping)),
      stiffness_(std::move(parts.stiffness)),
      every_mode_(parts.every_mode),
      truncated_(parts.truncated) {
  for (const Range& r : ranges_) size_ += r.size;
  const Eigen::Index m = k_.size();
  std::ostringstream problem;
  if (M_.rows() != size_ || M_.cols() != size_ || K_.rows() != size_ || K_.cols() != size_)
    problem << "M is " << shape(M_) << " and K " << shape(K_) << ", expected " << size_ << " x " << size_
            << " (the sum of its ranges)";
  else if (P_.size() != size_)
    problem << "P has " << P_.size() << " entries, expected " << size_;
  else if (phi_.rows() != size_ || phi_.cols() != m)
    problem << "Phi_L is " << phi_.rows() << " x " << phi_.cols() << ", expected " << size_ << " x " << m;
  else if (mass_.d.size() != m || damping_.d.size() != m || stiffness_.d.size() != m)
    problem << "d_M, d_C and d_K have " << mass_.d.size() << ", " << damping_.d.size() << " and "
            << stiffness_.d.size() << " entries, expected " << m << " (one per kept mode)";
  else if (!(mass_.mu > 0.0))
    problem << "mu_M is " << mass_.mu << ", expected > 0";
  if (!problem.str().empty())
    throw std::invalid_argument("adjusted structure '" + name_ + "': " + problem.str());
  b_ = base_ == Base::kMass ? Eigen::VectorXd::Ones(m) : k_;
  const Eigen::ArrayXd base_modal = mass_.mu * b_.array();
  const Eigen::ArrayXd modal_mass = base_modal + mass_.d.array();
  if (m > 0 && (!(base_modal > 0.0).all() || !(modal_mass > 0.0).all()))
    throw std::invalid_argument("adjusted structure '" + name_ +
                                "': a kept mode has no positive modal mass (a mode of zero frequency under the "
                                "policy mass needs a beam held by its supports)");
  auto factor = std::make_shared<Factor>(B());
  if (factor->info() != Eigen::Success || (size_ > 0 && !(factor->vectorD().minCoeff() > 0.0))) {
    throw std::runtime_error("adjusted structure '" + name_ + "': its " +
                             std::string(base_ == Base::kMass ? "mass" : "stiffness") +
                             " matrix is not positive definite" +
                             (base_ == Base::kMass ? " (a lumped mass matrix without rotary inertia cannot carry "
                                                     "a contact)"
                                                   : " (nothing holds the beam: the policy mass needs supports)"));
  }
  factor_ = std::move(factor);
  base_p_ = factor_->solve(P_) / mass_.mu;
  phi_p_ = phi_.transpose() * P_;
  // The free acceleration, a = M_adj^-1 (r - C_adj v - K_adj q), with
  // M_adj^-1 = B^-1 / mu_M + Phi_L diag(w) Phi_L^T, w = 1/(mu_M b + d_M) - 1/(mu_M b),
  // B^-1 U = Phi_L diag(1/b) and Phi_L^T B z = diag(b) U^T z, is
  //   B^-1 r / mu_M - (mu_C v + mu_K q) / mu_M + Phi_L (w .* g + e_v .* x_v + e_q .* x_q)
  // with g = Phi_L^T r, x_v = U^T v, x_q = U^T q and
  //   e_v = -(d_C / (mu_M b) + w (mu_C b + d_C)),  e_q = -(d_K / (mu_M b) + w (mu_K b + d_K)).
  const Eigen::ArrayXd w = modal_mass.inverse() - base_modal.inverse();
  w_g_ = w.matrix();
  e_v_ = (-(damping_.d.array() / base_modal + w * (damping_.mu * b_.array() + damping_.d.array()))).matrix();
  e_q_ = (-(stiffness_.d.array() / base_modal + w * (stiffness_.mu * b_.array() + stiffness_.d.array()))).matrix();
  uses_g_ = !(w == 0.0).all();
}

LowRankStructure::Workspace LowRankStructure::make_workspace() const {
  Workspace ws;
  const Eigen::Index n = size_, m = rank();
  for (Eigen::VectorXd* v : {&ws.x, &ws.v, &ws.r, &ws.a, &ws.bx, &ws.bv, &ws.base_solve}) v->setZero(n);
  ws.modal.setZero(m);
  ws.modal_g.setZero(m);
  ws.three.setZero(n, 4);
  ws.projected3.setZero(m, 4);
  for (auto* v : {&ws.row_x, &ws.row_v}) v->reserve(static_cast<std::size_t>(n));
  ws.rows.reserve(static_cast<std::size_t>(n));
  ws.row_listed.assign(static_cast<std::size_t>(n), 0);
  return ws;
}

void LowRankStructure::gather(const double* qc, Eigen::VectorXd& x) const {
  x.resize(size_);
  Eigen::Index row = 0;
  for (const Range& r : ranges_) {
    x.segment(row, r.size) = Eigen::Map<const Eigen::VectorXd>(qc + r.offset, r.size);
    row += r.size;
  }
}

void LowRankStructure::scatter_add(const Eigen::VectorXd& x, double* qc) const {
  Eigen::Index row = 0;
  for (const Range& r : ranges_) {
    Eigen::Map<Eigen::VectorXd>(qc + r.offset, r.size) += x.segment(row, r.size);
    row += r.size;
  }
}

void LowRankStructure::scatter(const Eigen::VectorXd& x, double* qc) const {
  Eigen::Index row = 0;
  for (const Range& r : ranges_) {
    Eigen::Map<Eigen::VectorXd>(qc + r.offset, r.size) = x.segment(row, r.size);
    row += r.size;
  }
}

void LowRankStructure::add_internal_force(const double* qc, const double* vc, double* fc, Workspace& ws) const {
  gather(qc, ws.x);
  gather(vc, ws.v);
  // B (mu_C v + mu_K q) + M Phi_L (d_C .* Phi_L^T M v + d_K .* Phi_L^T M q)
  ws.r = damping_.mu * ws.v + stiffness_.mu * ws.x;
  ws.a.noalias() = B() * ws.r;
  if (rank() > 0) {
    ws.three.col(0).noalias() = M_ * ws.v;
    ws.three.col(1).noalias() = M_ * ws.x;
    transposed_product(phi_.data(), phi_.rows(), phi_.cols(), ws.three.data(), 2, ws.projected3.data());
    ws.modal = damping_.d.cwiseProduct(ws.projected3.col(0)) + stiffness_.d.cwiseProduct(ws.projected3.col(1));
    ws.bx.noalias() = phi_ * ws.modal;
    ws.a.noalias() += M_ * ws.bx;
  }
  scatter_add(ws.a, fc);
}

void LowRankStructure::add_inertia(const double* ac, double* rc, Workspace& ws) const {
  gather(ac, ws.x);
  ws.a.noalias() = B() * ws.x;
  ws.a *= mass_.mu;
  if (rank() > 0 && !(mass_.d.array() == 0.0).all()) {
    ws.bx.noalias() = M_ * ws.x;
    ws.modal.noalias() = phi_.transpose() * ws.bx;
    ws.modal = mass_.d.cwiseProduct(ws.modal);
    ws.bx.noalias() = phi_ * ws.modal;
    ws.a.noalias() += M_ * ws.bx;
  }
  scatter_add(ws.a, rc);
}

void LowRankStructure::free_acceleration(const double* qc, const double* vc, const double* fc, double* ac,
                                         Workspace& ws) const {
  gather(qc, ws.x);
  gather(vc, ws.v);
  // y: every mode as if it had the base's modal values,
  // B^-1 (P + f) / mu_M - (mu_C v + mu_K q) / mu_M; B^-1 P / mu_M is kept.
  const double inv_mu = 1.0 / mass_.mu;
  ws.a = base_p_ - (inv_mu * damping_.mu) * ws.v - (inv_mu * stiffness_.mu) * ws.x;
  bool loaded = false;
  if (fc != nullptr) {
    gather(fc, ws.r);
    loaded = !ws.r.isZero(0.0);
  }
  if (loaded) {
    solve_ldlt(*factor_, ws.r, ws.base_solve, ws.ldlt);
    ws.a += inv_mu * ws.base_solve;
  }
  if (rank() == 0) {
    scatter(ws.a, ac);
    return;
  }
  ws.three.col(0).noalias() = M_ * ws.v;
  ws.three.col(1).noalias() = M_ * ws.x;
  if (base_ == Base::kMass) {
    // B = M: U^T y is known in closed form, and the correction of the kept
    // modes is a fixed combination of x_v, x_q (and g): one pass over Phi_L
    // for them, one for the sum.
    const int columns = uses_g_ && loaded ? 3 : 2;
    if (columns == 3) ws.three.col(2) = ws.r;
    transposed_product(phi_.data(), phi_.rows(), phi_.cols(), ws.three.data(), columns, ws.projected3.data());
    ws.modal = e_v_.cwiseProduct(ws.projected3.col(0)) + e_q_.cwiseProduct(ws.projected3.col(1));
    if (uses_g_) ws.modal += w_g_.cwiseProduct(columns == 3 ? Eigen::VectorXd(phi_p_ + ws.projected3.col(2)) : phi_p_);
  } else {
    // B = K: the closed form of U^T y holds k* / k_j, which for the lowest
    // modes is (omega_l / omega_1)^2 ~ 1e4 and would amplify the modes'
    // rounding as much. Instead, take y's kept-mode part out as it is,
    // U^T y = Phi_L^T M y, and put in their exact acceleration a_L:
    //   a = y + Phi_L (a_L - U^T y),
    //   a_L = (g - (mu_C b + d_C) x_v - (mu_K b + d_K) x_q) / (mu_M b + d_M).
    if (loaded) ws.three.col(2) = ws.r;
    else ws.three.col(2).setZero();
    ws.three.col(3).noalias() = M_ * ws.a;
    transposed_product(phi_.data(), phi_.rows(), phi_.cols(), ws.three.data(), 4, ws.projected3.data());
    const Eigen::ArrayXd b = b_.array();
    ws.modal = (((phi_p_ + ws.projected3.col(2)).array() -
                 (damping_.mu * b + damping_.d.array()) * ws.projected3.col(0).array() -
                 (stiffness_.mu * b + stiffness_.d.array()) * ws.projected3.col(1).array()) /
                    (mass_.mu * b + mass_.d.array()) -
                ws.projected3.col(3).array())
                   .matrix();
  }
  ws.a.noalias() += phi_ * ws.modal;
  scatter(ws.a, ac);
}

void LowRankStructure::apply(const Term& term, const Eigen::VectorXd& x, Eigen::VectorXd& y, Workspace& ws) const {
  y.noalias() = B() * x;
  y *= term.mu;
  if (rank() > 0 && !(term.d.array() == 0.0).all()) {
    ws.bx.noalias() = M_ * x;
    ws.modal.noalias() = phi_.transpose() * ws.bx;
    ws.modal = term.d.cwiseProduct(ws.modal);
    ws.bx.noalias() = phi_ * ws.modal;
    y.noalias() += M_ * ws.bx;
  }
}

void LowRankStructure::solve_base(const Eigen::VectorXd& r, Eigen::VectorXd& x, Workspace& ws) const {
  x.resize(r.size());
  solve_ldlt(*factor_, r, x, ws.ldlt);
}

void LowRankStructure::solve_mass(const Eigen::VectorXd& r, Eigen::VectorXd& x, Workspace& ws) const {
  x.resize(r.size());
  solve_ldlt(*factor_, r, x, ws.ldlt);
  x /= mass_.mu;
  if (rank() == 0 || !uses_g_) return;
  if (base_ == Base::kMass) {
    ws.modal.noalias() = phi_.transpose() * r;
    ws.modal = w_g_.cwiseProduct(ws.modal);
  } else {
    // As in free_acceleration: x = y + Phi_L (g / (mu_M b + d_M) - U^T y), y = B^-1 r / mu_M.
    ws.three.col(0) = r;
    ws.three.col(1).noalias() = M_ * x;
    transposed_product(phi_.data(), phi_.rows(), phi_.cols(), ws.three.data(), 2, ws.projected3.data());
    ws.modal = (ws.projected3.col(0).array() / (mass_.mu * b_.array() + mass_.d.array()) -
                ws.projected3.col(1).array())
                   .matrix();
  }
  x.noalias() += phi_ * ws.modal;
}

LowRankStructure::Term LowRankStructure::combination(double c_a, double c_v, double c_q) const {
  Term t;
  t.mu = c_a * mass_.mu + c_v * damping_.mu + c_q * stiffness_.mu;
  t.d = c_a * mass_.d + c_v * damping_.d + c_q * stiffness_.d;
  return t;
}

ModalBlock LowRankStructure::modal_block(int row, const Term& term) const {
  ModalBlock block;
  block.row = row;
  block.base_factor = &base_factor();
  block.phi = &phi();
  block.base_modal = base() == Base::kMass ? nullptr : &base_modal();
  block.alpha = term.mu;
  block.d = term.d;
  return block;
}

Eigen::MatrixXd LowRankStructure::mass_times_phi() const { return M_ * Eigen::MatrixXd(phi_); }

Eigen::MatrixXd LowRankStructure::dense(const Term& term) const {
  const Eigen::MatrixXd u = mass_times_phi();
  return term.mu * Eigen::MatrixXd(B()) + u * term.d.asDiagonal() * u.transpose();
}

}  // namespace mbfe::runtime
