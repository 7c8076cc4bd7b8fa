#include "runtime/coupled/coupled_implicit_system.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "runtime/multibody/rigid_system.h"

namespace mbfe::runtime {

namespace {

// Central-difference step of the rigid tangents where the solver has no
// Jacobian kernel: the cube root of machine epsilon balances truncation
// (h^2) against round-off (eps / h), relative to the coordinate's size.
constexpr double kDifferenceStep = 6e-6;

}  // namespace

CoupledImplicitSystem::CoupledImplicitSystem(std::shared_ptr<CoupledDynamics> dyn, bool modal_blocks)
    : AugmentedSystem(std::move(dyn)), model_(dyn_->model()) {
  for (const auto& s : model_.structures()) {
    if (s->every_mode()) {
      throw std::invalid_argument("beam '" + s->name() +
                                  "': the implicit integrators take a beam's sparse C and K, with a low-rank part "
                                  "for the adjustment's cap; this adjustment changes every mode on its own (policy "
                                  "keep_slow or paper_eq25): run it explicitly, or with adjust off");
    }
  }
  const int nb = model_.nb(), nc = model_.nc();
  for (const auto& f : model_.forces()) states_.push_back(f->make_state());
  for (const auto& s : model_.structures()) structure_ws_.push_back(s->make_workspace());
  motion_ = model_.driven().make_motion();
  mb_row_.resize(nb, nb);
  fb_.resize(nb);
  qb_force_.resize(nb);
  fc_.resize(nc);
  kb_.resize(nb, nb);
  cb_.resize(nb, nb);
  jac_k_.resize(nb * nb);
  jac_c_.resize(nb * nb);
  // The block form needs every adjusted structure to be one beam's, and
  // nothing that spans beams inside the matrix (contact rows).
  bool single = true;
  for (const auto& s : model_.structures()) single = single && s->ranges().size() == 1;
  modal_blocks_ = modal_blocks && !model_.structures().empty() && single && model_.m() == 0;
}

void CoupledImplicitSystem::rigid_residual(double t, const double* qb, const double* vb, const double* ab,
                                           Eigen::VectorXd& tau) {
  const int nb = model_.nb();
  evaluate_dynamics(model_.kernels(), qb, vb, t, mb_row_.data(), fb_.data(), qb_force_.data());
  tau = mb_row_ * Eigen::Map<const Eigen::VectorXd>(ab, nb) + fb_ - qb_force_;
}

void CoupledImplicitSystem::element_forces(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  const int nb = model_.nb();
  fc_.setZero();
  const ForceArgs args{t, q.data(), v.data(), q.data() + nb, v.data() + nb};
  ForceSink sink{qb_force_.data(), fc_.data()};
  const auto& forces = model_.forces();
  for (std::size_t e = 0; e < forces.size(); ++e) forces[e]->add_force(args, *states_[e], sink);
  dyn_->add_applied_loads(t, fc_.data());
}

void CoupledImplicitSystem::residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                     const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double c_q,
                                     Eigen::VectorXd& r, Eigen::VectorXd& c) {
  const int nb = model_.nb(), n = model_.n(), m = model_.m();
  qm_ = q;
  vm_ = v;
  model_.driven().impose(t, qm_.data(), vm_.data(), motion_);
  r.resize(n);
  Eigen::Ref<Eigen::VectorXd> rb = r.head(nb);
  Eigen::Ref<Eigen::VectorXd> rc = r.tail(n - nb);
  // Rigid: M_b a + F_b - Q_b - f_b.
  evaluate_dynamics(model_.kernels(), qm_.data(), vm_.data(), t, mb_row_.data(), fb_.data(), qb_force_.data());
  element_forces(t, qm_, vm_);
  rb.noalias() = mb_row_ * a.head(nb);
  rb += fb_ - qb_force_;
  // Beams of their own: M_c a + C v + K q - P - f_c.
  for (const CoupledBeam& b : model_.beams()) {
    if (b.structure >= 0) continue;
    const int off = b.offset, nk = b.mesh.num_free;
    Eigen::Ref<Eigen::VectorXd> rk = rc.segment(off, nk);
    rk.noalias() = b.M * a.segment(nb + off, nk);
    rk.noalias() += b.C * v.segment(nb + off, nk);
    rk.noalias() += b.K * q.segment(nb + off, nk);
    rk -= b.P + fc_.segment(off, nk);
  }
  // Adjusted structures: M_adj a + C_adj v + K_adj q - P - f_c over their ranges.
  const auto& structures = model_.structures();
  for (std::size_t s = 0; s < structures.size(); ++s) {
    for (const LowRankStructure::Range& range : structures[s]->ranges())
      rc.segment(range.offset, range.size) =
          -(model_.loads().segment(range.offset, range.size) + fc_.segment(range.offset, range.size));
    structures[s]->add_inertia(a.data() + nb, rc.data(), structure_ws_[s]);
    structures[s]->add_internal_force(q.data() + nb, v.data() + nb, rc.data(), structure_ws_[s]);
  }
  // Contacts: + G^T lambda, and the scaled constraint rows.
  c.resize(m);
  if (m > 0) {
    model_.constraints().evaluate(t, qm_.data(), qm_.data() + nb, nullptr, nullptr, cv_);
    rb.noalias() += cv_.jb.transpose() * lambda;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < 4; ++j)
        if (cv_.jcol(i, j) >= 0) rc[cv_.jcol(i, j)] += cv_.je(i, j) * lambda[i];
    c = cv_.phi / c_q;
  }
  // Driven coordinates: their acceleration is the motion's.
  const std::vector<int>& driven = model_.driven().indices();
  for (std::size_t k = 0; k < driven.size(); ++k) r[driven[k]] = a[driven[k]] - motion_.qdd[static_cast<Eigen::Index>(k)];
}

void CoupledImplicitSystem::rigid_tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                           const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                           Eigen::MatrixXd& K_b, Eigen::MatrixXd& C_b, bool force_differences) {
  const int nb = dyn_->nb(), m = dyn_->m();
  qm_ = q;
  vm_ = v;
  model_.driven().impose(t, qm_.data(), vm_.data(), motion_);
  K_b.setZero(nb, nb);
  C_b.setZero(nb, nb);
  const ContactConstraints& cc = model_.constraints();
  const auto kernel = model_.kernels().dynamics_jacobians;
  if (kernel != nullptr && !force_differences) {
    // Closed form (row-major from the kernel), then d(J_b^T lambda)/dq_b below.
    kernel(qm_.data(), vm_.data(), a.data(), t, jac_k_.data(), jac_c_.data());
    K_b = Eigen::Map<const RowMajor>(jac_k_.data(), nb, nb);
    C_b = Eigen::Map<const RowMajor>(jac_c_.data(), nb, nb);
  }
  for (int j = 0; j < nb; ++j) {
    if (model_.driven().is_driven(j)) {
      // The motion overrides the state: the driven coordinate moves nothing.
      K_b.col(j).setZero();
      C_b.col(j).setZero();
      continue;
    }
    for (int pass = 0; pass < 2; ++pass) {
      const bool closed_form = kernel != nullptr && !force_differences;
      if (closed_form && (pass == 1 || m == 0)) continue;
      Eigen::VectorXd& x = pass == 0 ? qm_ : vm_;
      const double x0 = x[j];
      const double step = kDifferenceStep * (1.0 + std::abs(x0));
      x[j] = x0 + step;
      if (closed_form) tau_.setZero(nb);
      else rigid_residual(t, qm_.data(), vm_.data(), a.data(), tau_);
      if (pass == 0 && m > 0) {
        cc.evaluate(t, qm_.data(), qm_.data() + nb, nullptr, nullptr, cv_);
        tau_.noalias() += cv_.jb.transpose() * lambda;
      }
      x[j] = x0 - step;
      if (closed_form) tau2_.setZero(nb);
      else rigid_residual(t, qm_.data(), vm_.data(), a.data(), tau2_);
      if (pass == 0 && m > 0) {
        cc.evaluate(t, qm_.data(), qm_.data() + nb, nullptr, nullptr, cv_);
        tau2_.noalias() += cv_.jb.transpose() * lambda;
      }
      x[j] = x0;
      (pass == 0 ? K_b : C_b).col(j) += (tau_ - tau2_) / (2.0 * step);
    }
  }
}

void CoupledImplicitSystem::factorize(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                      const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double c_q,
                                      double c_v) {
  const int nb = model_.nb(), n = model_.n(), m = model_.m();
  rigid_tangents(t, q, v, a, lambda, kb_, cb_);
  // Mass matrix and contacts at the state (rigid_tangents left the motion imposed in qm_, vm_).
  evaluate_dynamics(model_.kernels(), qm_.data(), vm_.data(), t, mb_row_.data(), fb_.data(), qb_force_.data());
  triplets_.clear();
  const std::vector<bool>& driven = model_.driven().mask();
  TangentSink sink(triplets_, &driven);  // a driven row is a_d = motion''
  auto add = [&](int i, int j, double value) { sink.add(i, j, value); };
  for (int i = 0; i < nb; ++i) {
    if (driven[i]) triplets_.emplace_back(i, i, 1.0);
    for (int j = 0; j < nb; ++j) add(i, j, mb_row_(i, j) + c_v * cb_(i, j) + c_q * kb_(i, j));
  }
  for (const CoupledBeam& b : model_.beams()) {
    if (b.structure >= 0) continue;
    const int off = nb + b.offset;
    for (const auto* mat : {&b.M, &b.C, &b.K}) {
      const double scale = mat == &b.M ? 1.0 : (mat == &b.C ? c_v : c_q);
      for (int col = 0; col < mat->outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(*mat, col); it; ++it)
          add(off + static_cast<int>(it.row()), off + static_cast<int>(it.col()), scale * it.value());
    }
  }
  // Adjusted structures: alpha B + U diag(d) U^T; the sparse part joins the
  // matrix unless the structure is a block of known inverse.
  const auto& structures = model_.structures();
  std::vector<LowRankStructure::Term> terms;
  for (const auto& s : structures) terms.push_back(s->combination(1.0, c_v, c_q));
  if (!modal_blocks_) {
    for (std::size_t k = 0; k < structures.size(); ++k) {
      const LowRankStructure& s = *structures[k];
      // Stacked coordinate -> global row.
      std::vector<int> global;
      for (const LowRankStructure::Range& r : s.ranges())
        for (int i = 0; i < r.size; ++i) global.push_back(nb + r.offset + i);
      const Eigen::SparseMatrix<double>& B = s.B();
      for (int col = 0; col < B.outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(B, col); it; ++it)
          add(global[it.row()], global[it.col()], terms[k].mu * it.value());
    }
  }
  // Every force element's tangent, at the state its force is taken at.
  element_forces(t, qm_, vm_);
  const ForceArgs args{t, qm_.data(), vm_.data(), qm_.data() + nb, vm_.data() + nb};
  const auto& forces = model_.forces();
  for (std::size_t e = 0; e < forces.size(); ++e) forces[e]->add_tangent(args, *states_[e], c_q, c_v, sink);
  const ContactConstraints& cc = model_.constraints();
  if (m > 0) {
    // The contacts' geometric stiffness d(G^T lambda)/dq that rigid_tangents
    // leaves out: the beam rows against q_b (the slider's position moves its
    // shape functions) and every row against the beam DOFs the contacts
    // touch, by central differences of the contact kernels.
    std::vector<int> columns;
    cc.evaluate(t, qm_.data(), qm_.data() + nb, nullptr, nullptr, cv_);
    for (int j = 0; j < nb; ++j)
      if (!model_.driven().is_driven(j)) columns.push_back(j);
    for (int r = 0; r < m; ++r)
      for (int j = 0; j < 4; ++j)
        if (cv_.jcol(r, j) >= 0) columns.push_back(nb + cv_.jcol(r, j));
    std::sort(columns.begin(), columns.end());
    columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
    auto contact_force = [&](Eigen::VectorXd& out) {
      cc.evaluate(t, qm_.data(), qm_.data() + nb, nullptr, nullptr, cv_);
      out.setZero(n);
      out.head(nb).noalias() = cv_.jb.transpose() * lambda;
      for (int r = 0; r < m; ++r)
        for (int j = 0; j < 4; ++j)
          if (cv_.jcol(r, j) >= 0) out[nb + cv_.jcol(r, j)] += cv_.je(r, j) * lambda[r];
    };
    for (int j : columns) {
      const double x0 = qm_[j];
      const double step = kDifferenceStep * (1.0 + std::abs(x0));
      qm_[j] = x0 + step;
      contact_force(tau_);
      qm_[j] = x0 - step;
      contact_force(tau2_);
      qm_[j] = x0;
      for (int i = j < nb ? nb : 0; i < n; ++i) {  // q_b columns: the rigid rows are in rigid_tangents
        const double d = (tau_[i] - tau2_[i]) / (2.0 * step);
        if (d != 0.0) add(i, j, c_q * d);
      }
    }
    cc.evaluate(t, qm_.data(), qm_.data() + nb, nullptr, nullptr, cv_);
    for (int r = 0; r < m; ++r) {
      for (int j = 0; j < nb; ++j) {
        if (cv_.jb(r, j) == 0.0) continue;
        triplets_.emplace_back(n + r, j, cv_.jb(r, j));
        add(j, n + r, cv_.jb(r, j));
      }
      for (int j = 0; j < 4; ++j) {
        if (cv_.jcol(r, j) < 0 || cv_.je(r, j) == 0.0) continue;
        triplets_.emplace_back(n + r, nb + cv_.jcol(r, j), cv_.je(r, j));
        triplets_.emplace_back(nb + cv_.jcol(r, j), n + r, cv_.je(r, j));
      }
    }
  }
  if (modal_blocks_) {
    std::vector<ModalBlock> blocks;
    for (std::size_t k = 0; k < structures.size(); ++k) {
      const LowRankStructure& s = *structures[k];
      blocks.push_back(s.modal_block(nb + s.ranges().front().offset, terms[k]));
    }
    try {
      block_solver_.factorize(n, triplets_, std::move(blocks));
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("implicit step at t = " + std::to_string(t) + " s: " + e.what());
    }
    return;
  }
  matrix_.resize(n + m, n + m);
  matrix_.setFromTriplets(triplets_.begin(), triplets_.end());
  lu_.analyzePattern(matrix_);
  lu_.factorize(matrix_);
  if (lu_.info() != Eigen::Success) {
    std::ostringstream os;
    os << "implicit step at t = " << t << " s: the Newton matrix is singular (" << lu_.lastErrorMessage()
       << "); are the contacts independent?";
    throw std::runtime_error(os.str());
  }
  // The structures' low rank: W = U on each one's rows, D its term's d.
  int width = 0;
  for (const auto& s : structures) width += s->rank();
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n + m, width);
  Eigen::VectorXd D(width);
  std::vector<WoodburyCorrection::Block> blocks;
  int col = 0;
  for (std::size_t k = 0; k < structures.size(); ++k) {
    const LowRankStructure& s = *structures[k];
    const Eigen::MatrixXd u = s.mass_times_phi();
    Eigen::Index row = 0;
    for (const LowRankStructure::Range& r : s.ranges()) {
      W.block(nb + r.offset, col, r.size, s.rank()) = u.middleRows(row, r.size);
      blocks.push_back({nb + r.offset, r.size, col, s.rank()});
      row += r.size;
    }
    D.segment(col, s.rank()) = terms[k].d;
    col += s.rank();
  }
  Eigen::MatrixXd Z = width > 0 ? Eigen::MatrixXd(lu_.solve(W)) : Eigen::MatrixXd(n + m, 0);
  woodbury_.factorize(std::move(W), std::move(D), std::move(Z), blocks,
                      "implicit step at t = " + std::to_string(t) + " s: the Newton matrix");
}

void CoupledImplicitSystem::solve(const Eigen::VectorXd& r, const Eigen::VectorXd& c, Eigen::VectorXd& da,
                                  Eigen::VectorXd& dlambda) {
  const int n = model_.n(), m = model_.m();
  rhs_.resize(n + m);
  rhs_.head(n) = r;
  rhs_.tail(m) = c;
  if (modal_blocks_) {  // m = 0
    block_solver_.solve(rhs_, sol_);
    da = sol_;
    dlambda.resize(0);
    return;
  }
  sol_ = lu_.solve(rhs_);
  woodbury_.correct(sol_);
  da = sol_.head(n);
  dlambda = sol_.tail(m);
}

void CoupledImplicitSystem::accelerations(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                          Eigen::VectorXd& a, Eigen::VectorXd& lambda) {
  dyn_->evaluate(t, q, v);
  dyn_->solve_augmented(t, a, lambda);
}

}  // namespace mbfe::runtime
