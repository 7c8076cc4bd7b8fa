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
// The Woodbury capacity matrix I + D W^T B^-1 W is taken as singular below this
// reciprocal condition number (Eigen's 1-norm estimate; a margin of ~1e3 ulps).
constexpr double kSingularCapacityRcond = 1e-13;

}  // namespace

CoupledImplicitSystem::CoupledImplicitSystem(std::shared_ptr<CoupledDynamics> dyn, bool modal_blocks)
    : AugmentedSystem(std::move(dyn)), springs_(dyn_->model(), dyn_->constraints()), links_(dyn_->links()) {
  for (const CoupledBeam& b : dyn_->beams()) {
    if (b.mesh.num_free > 0 && (b.C.rows() != b.mesh.num_free || b.K.rows() != b.mesh.num_free)) {
      throw std::invalid_argument("beam '" + b.mesh.name +
                                  "': the implicit integrators take a beam's sparse C and K, with a low-rank part "
                                  "for the adjustment's cap; this adjustment changes every mode on its own (policy "
                                  "keep_slow or paper_eq25): run it explicitly, or with --adjust off");
    }
  }
  const int nb = dyn_->nb(), nc = dyn_->nc();
  is_driven_.assign(nb, false);
  for (int d : dyn_->driven()) is_driven_[d] = true;
  const int nd = static_cast<int>(dyn_->driven().size());
  motion_q_.resize(nd);
  motion_v_.resize(nd);
  motion_a_.resize(nd);
  mb_row_.resize(nb, nb);
  fb_.resize(nb);
  qb_force_.resize(nb);
  fc_.resize(nc);
  kb_.resize(nb, nb);
  cb_.resize(nb, nb);
  jac_k_.resize(nb * nb);
  jac_c_.resize(nb * nb);
  // The block form needs every low-rank beam with its Phi_L by rows, and
  // nothing that spans beams inside the matrix (contact rows, joined structures).
  const std::vector<CoupledBeam>& beams = dyn_->beams();
  const bool any_low_rank = std::any_of(beams.begin(), beams.end(), [](const CoupledBeam& b) { return b.low_rank != nullptr; });
  const bool all_by_rows = std::all_of(beams.begin(), beams.end(), [](const CoupledBeam& b) {
    return !b.low_rank || (b.low_rank->phi_rows.rows() == b.mesh.num_free && b.low_rank->phi_rows.cols() == b.low_rank->U.cols());
  });
  modal_blocks_ = modal_blocks && any_low_rank && all_by_rows && dyn_->m() == 0 && dyn_->joined().empty();
  block_mass_.resize(beams.size());
  for (std::size_t k = 0; modal_blocks_ && k < beams.size(); ++k) {
    if (!beams[k].low_rank) continue;
    block_mass_[k] = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(beams[k].M);
    if (block_mass_[k]->info() != Eigen::Success) modal_blocks_ = false;  // CoupledDynamics reports the mass matrix
  }
}

void CoupledImplicitSystem::rigid_residual(double t, const double* qb, const double* vb, const double* ab,
                                           Eigen::VectorXd& tau) {
  const int nb = dyn_->nb();
  evaluate_dynamics(dyn_->model(), qb, vb, t, mb_row_.data(), fb_.data(), qb_force_.data());
  tau = mb_row_ * Eigen::Map<const Eigen::VectorXd>(ab, nb) + fb_ - qb_force_;
}

void CoupledImplicitSystem::residual(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                     const Eigen::VectorXd& a, const Eigen::VectorXd& lambda, double c_q,
                                     Eigen::VectorXd& r, Eigen::VectorXd& c) {
  const int nb = dyn_->nb(), n = dyn_->n(), m = dyn_->m();
  qm_ = q;
  vm_ = v;
  dyn_->impose_motion(t, qm_, vm_);
  r.resize(n);
  Eigen::Ref<Eigen::VectorXd> rb = r.head(nb);
  Eigen::Ref<Eigen::VectorXd> rc = r.tail(n - nb);
  // Rigid: M_b a + F_b - Q_b, spring forces in Q_b.
  evaluate_dynamics(dyn_->model(), qm_.data(), vm_.data(), t, mb_row_.data(), fb_.data(), qb_force_.data());
  fc_.setZero();
  if (springs_.count() > 0)
    springs_.apply(qm_.data(), qm_.data() + nb, vm_.data(), vm_.data() + nb, qb_force_, fc_);
  if (links_.count() > 0) links_.apply(q.data() + nb, v.data() + nb, fc_);
  rb.noalias() = mb_row_ * a.head(nb);
  rb += fb_ - qb_force_;
  // Beams: M_c a + C v + K q - P - (time loads, springs).
  const std::vector<CoupledBeam>& beams = dyn_->beams();
  const ContactConstraints& cc = dyn_->constraints();
  for (std::size_t k = 0; k < beams.size(); ++k) {
    const CoupledBeam& b = beams[k];
    const int off = cc.beam_offset(static_cast<int>(k));
    const int nk = b.mesh.num_free;
    Eigen::Ref<Eigen::VectorXd> rk = rc.segment(off, nk);
    rk.noalias() = b.M * a.segment(nb + off, nk);
    rk.noalias() += b.C * v.segment(nb + off, nk);
    rk.noalias() += b.K * q.segment(nb + off, nk);
    if (b.low_rank) {
      const BeamLowRank& lr = *b.low_rank;
      low_rank_r_.noalias() = lr.d_C.cwiseProduct(lr.U.transpose() * v.segment(nb + off, nk));
      low_rank_r_.noalias() += lr.d_K.cwiseProduct(lr.U.transpose() * q.segment(nb + off, nk));
      rk.noalias() += lr.U * low_rank_r_;
    }
    rk -= b.P + fc_.segment(off, nk);
    if (b.time_loads) {
      b.time_loads(t, nodal_);
      for (const NodalForce& f : nodal_) rk[f.index] -= f.value;
    }
  }
  // Joined structures: U (d_C .* U^T v + d_K .* U^T q) over their stacked beams.
  for (const auto& js : dyn_->joined()) {
    stack_joined(*js, v, joined_v_);
    stack_joined(*js, q, joined_x_);
    low_rank_r_.noalias() = js->d_C.cwiseProduct(js->U.transpose() * joined_v_);
    low_rank_r_.noalias() += js->d_K.cwiseProduct(js->U.transpose() * joined_x_);
    Eigen::Index row = 0;
    for (int b : js->beams) {
      const int nk = beams[b].mesh.num_free;
      rc.segment(cc.beam_offset(b), nk).noalias() += js->U.middleRows(row, nk) * low_rank_r_;
      row += nk;
    }
  }
  // Contacts: + G^T lambda, and the scaled constraint rows.
  c.resize(m);
  if (m > 0) {
    cc.evaluate(t, qm_.data(), qm_.data() + nb, nullptr, nullptr, cv_);
    rb.noalias() += cv_.jb.transpose() * lambda;
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < 4; ++j)
        if (cv_.jcol(i, j) >= 0) rc[cv_.jcol(i, j)] += cv_.je(i, j) * lambda[i];
    c = cv_.phi / c_q;
  }
  // Driven coordinates: their acceleration is the motion's.
  if (!dyn_->driven().empty()) {
    dyn_->model().motion(t, motion_q_.data(), motion_v_.data(), motion_a_.data());
    for (std::size_t k = 0; k < dyn_->driven().size(); ++k) {
      const int d = dyn_->driven()[k];
      r[d] = a[d] - motion_a_[k];
    }
  }
}

void CoupledImplicitSystem::rigid_tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                           const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                           Eigen::MatrixXd& K_b, Eigen::MatrixXd& C_b, bool force_differences) {
  const int nb = dyn_->nb(), m = dyn_->m();
  qm_ = q;
  vm_ = v;
  dyn_->impose_motion(t, qm_, vm_);
  K_b.setZero(nb, nb);
  C_b.setZero(nb, nb);
  const ContactConstraints& cc = dyn_->constraints();
  const auto kernel = dyn_->model().dynamics_jacobians;
  if (kernel != nullptr && !force_differences) {
    // Closed form (row-major from the kernel), then d(J_b^T lambda)/dq_b below.
    kernel(qm_.data(), vm_.data(), a.data(), t, jac_k_.data(), jac_c_.data());
    K_b = Eigen::Map<const RowMajor>(jac_k_.data(), nb, nb);
    C_b = Eigen::Map<const RowMajor>(jac_c_.data(), nb, nb);
  }
  for (int j = 0; j < nb; ++j) {
    if (is_driven_[j]) {
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
  const int nb = dyn_->nb(), n = dyn_->n(), m = dyn_->m();
  rigid_tangents(t, q, v, a, lambda, kb_, cb_);
  // Mass matrix and contacts at the state (rigid_tangents left the motion imposed in qm_, vm_).
  evaluate_dynamics(dyn_->model(), qm_.data(), vm_.data(), t, mb_row_.data(), fb_.data(), qb_force_.data());
  triplets_.clear();
  auto add = [&](int i, int j, double value) {
    if (i < nb && is_driven_[i]) return;  // a driven row is a_d = motion''
    if (value != 0.0) triplets_.emplace_back(i, j, value);
  };
  for (int i = 0; i < nb; ++i) {
    if (is_driven_[i]) triplets_.emplace_back(i, i, 1.0);
    for (int j = 0; j < nb; ++j) add(i, j, mb_row_(i, j) + c_v * cb_(i, j) + c_q * kb_(i, j));
  }
  const std::vector<CoupledBeam>& beams = dyn_->beams();
  const ContactConstraints& cc = dyn_->constraints();
  for (std::size_t k = 0; k < beams.size(); ++k) {
    const CoupledBeam& b = beams[k];
    if (modal_blocks_ && b.low_rank) continue;  // its block: (1 + c_v c* + c_q k*) M with the low rank
    const int off = nb + cc.beam_offset(static_cast<int>(k));
    for (const auto* mat : {&b.M, &b.C, &b.K}) {
      const double scale = mat == &b.M ? 1.0 : (mat == &b.C ? c_v : c_q);
      for (int col = 0; col < mat->outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(*mat, col); it; ++it)
          add(off + static_cast<int>(it.row()), off + static_cast<int>(it.col()), scale * it.value());
    }
  }
  if (springs_.count() > 0) {
    springs_.apply(qm_.data(), qm_.data() + nb, vm_.data(), vm_.data() + nb, qb_force_, fc_);
    for (int k = 0; k < springs_.count(); ++k) {
      const SpringGradient& g = springs_.gradient(k);
      if (!g.pressing) continue;
      const double w = c_q * springs_.stiffness(k) + c_v * springs_.damping(k);
      // g over the rigid coordinates, then the 4 beam DOFs.
      std::vector<std::pair<int, double>> entries;
      for (int j = 0; j < nb; ++j)
        if (g.jb[j] != 0.0) entries.emplace_back(j, g.jb[j]);
      for (int j = 0; j < 4; ++j)
        if (g.cols[j] >= 0 && g.je[j] != 0.0) entries.emplace_back(nb + g.cols[j], g.je[j]);
      for (const auto& [i, gi] : entries)
        for (const auto& [j, gj] : entries) add(i, j, w * gi * gj);
    }
  }
  if (links_.count() > 0) {
    // Taut links: k g g^T and c g g^T on the beam DOFs they join. A link
    // inside a joined structure has its k g g^T in the structure: only its
    // damper while taut, minus its spring while slack.
    links_.apply(q.data() + nb, v.data() + nb, fc_);
    for (int k = 0; k < links_.count(); ++k) {
      const bool slack = links_.states()[k].slack;
      const double spring = c_q * links_.stiffness(k), damper = c_v * links_.damping(k);
      const double w = !links_.inside_structure(k) ? (slack ? 0.0 : spring + damper) : (slack ? -spring : damper);
      if (w == 0.0) continue;
      const BeamLinks::Gradient& g = links_.gradient(k);
      for (int i = 0; i < g.size; ++i)
        for (int j = 0; j < g.size; ++j) add(nb + g.cols[i], nb + g.cols[j], w * g.values[i] * g.values[j]);
    }
  }
  if (m > 0) {
    // The contacts' geometric stiffness d(G^T lambda)/dq that rigid_tangents
    // leaves out: the beam rows against q_b (the slider's position moves its
    // shape functions) and every row against the beam DOFs the contacts
    // touch, by central differences of the contact kernels.
    std::vector<int> columns;
    cc.evaluate(t, qm_.data(), qm_.data() + nb, nullptr, nullptr, cv_);
    for (int j = 0; j < nb; ++j)
      if (!is_driven_[j]) columns.push_back(j);
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
    for (std::size_t k = 0; k < beams.size(); ++k) {
      if (!beams[k].low_rank) continue;
      const BeamLowRank& lr = *beams[k].low_rank;
      ModalBlock blk;
      blk.row = nb + cc.beam_offset(static_cast<int>(k));
      blk.M = &beams[k].M;
      blk.mass_factor = block_mass_[k].get();
      blk.phi = &lr.phi_rows;
      blk.alpha = 1.0 + c_v * lr.c_star + c_q * lr.k_star;
      blk.d = c_v * lr.d_C + c_q * lr.d_K;
      blocks.push_back(std::move(blk));
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
  factorize_low_rank(t, c_q, c_v);
}

void CoupledImplicitSystem::factorize_low_rank(double t, double c_q, double c_v) {
  // The low-rank beams add W D W^T to the sparse matrix B, W = U on each
  // beam's rows, D = c_v d_C + c_q d_K. Woodbury, in the form that never
  // inverts D (an entry may be zero):
  //   (B + W D W^T)^-1 = B^-1 - Z (I + D W^T Z)^-1 D W^T B^-1,   Z = B^-1 W.
  const int nb = dyn_->nb(), n = dyn_->n(), m = dyn_->m();
  const std::vector<CoupledBeam>& beams = dyn_->beams();
  const ContactConstraints& cc = dyn_->constraints();
  low_rank_beams_.clear();
  int width = 0;
  for (std::size_t k = 0; k < beams.size(); ++k) {
    if (!beams[k].low_rank || beams[k].low_rank->U.cols() == 0) continue;
    low_rank_beams_.push_back({static_cast<int>(k), nb + cc.beam_offset(static_cast<int>(k)), width});
    width += static_cast<int>(beams[k].low_rank->U.cols());
  }
  // A joined structure's block of columns has rows on each of its beams.
  const int joined_col = width;
  for (const auto& js : dyn_->joined()) width += static_cast<int>(js->U.cols());
  if (width == 0) return;
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n + m, width);
  low_rank_d_.resize(width);
  for (const LowRankBlock& blk : low_rank_beams_) {
    const BeamLowRank& lr = *beams[blk.beam].low_rank;
    W.block(blk.row, blk.col, lr.U.rows(), lr.U.cols()) = lr.U;
    low_rank_d_.segment(blk.col, lr.U.cols()) = c_v * lr.d_C + c_q * lr.d_K;
  }
  int col = joined_col;
  for (const auto& js : dyn_->joined()) {
    const Eigen::Index mj = js->U.cols();
    Eigen::Index row = 0;
    for (int b : js->beams) {
      const int nk = beams[b].mesh.num_free;
      W.block(nb + cc.beam_offset(b), col, nk, mj) = js->U.middleRows(row, nk);
      row += nk;
    }
    low_rank_d_.segment(col, mj) = c_v * js->d_C + c_q * js->d_K;
    col += static_cast<int>(mj);
  }
  low_rank_z_ = lu_.solve(W);
  // W^T Z block by block: W is zero outside its beams' rows (a dense product
  // would spend most of its time on those zeros in a model of several beams).
  Eigen::MatrixXd capacity(width, width);
  for (const LowRankBlock& blk : low_rank_beams_) {
    const BeamLowRank& lr = *beams[blk.beam].low_rank;
    capacity.middleRows(blk.col, lr.U.cols()).noalias() =
        lr.U.transpose() * low_rank_z_.middleRows(blk.row, lr.U.rows());
  }
  col = joined_col;
  for (const auto& js : dyn_->joined()) {
    const Eigen::Index mj = js->U.cols();
    capacity.middleRows(col, mj).setZero();
    Eigen::Index row = 0;
    for (int b : js->beams) {
      const int nk = beams[b].mesh.num_free;
      capacity.middleRows(col, mj).noalias() +=
          js->U.middleRows(row, nk).transpose() * low_rank_z_.middleRows(nb + cc.beam_offset(b), nk);
      row += nk;
    }
    col += static_cast<int>(mj);
  }
  capacity = low_rank_d_.asDiagonal() * capacity;
  capacity.diagonal().array() += 1.0;
  capacity_lu_.compute(capacity);
  // Singular exactly when B + W D W^T is (B regular, factored above).
  const double rcond = capacity_lu_.rcond();
  if (!(rcond >= kSingularCapacityRcond)) {
    std::ostringstream os;
    os << "implicit step at t = " << t << " s: the Newton matrix is singular in its low-rank part (the adjusted "
       << "modes, by Woodbury: reciprocal condition number " << rcond << ")";
    throw std::runtime_error(os.str());
  }
  low_rank_w_ = std::move(W);
}

void CoupledImplicitSystem::solve(const Eigen::VectorXd& r, const Eigen::VectorXd& c, Eigen::VectorXd& da,
                                  Eigen::VectorXd& dlambda) {
  const int n = dyn_->n(), m = dyn_->m();
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
  if (low_rank_z_.cols() > 0) {
    low_rank_s_.noalias() = low_rank_w_.transpose() * sol_;
    low_rank_s_ = low_rank_d_.cwiseProduct(low_rank_s_);
    sol_.noalias() -= low_rank_z_ * capacity_lu_.solve(low_rank_s_);
  }
  da = sol_.head(n);
  dlambda = sol_.tail(m);
}

void CoupledImplicitSystem::stack_joined(const JoinedLowRank& js, const Eigen::VectorXd& y, Eigen::VectorXd& out) const {
  const int nb = dyn_->nb();
  out.resize(js.U.rows());
  Eigen::Index row = 0;
  for (int b : js.beams) {
    const int nk = dyn_->beams()[b].mesh.num_free;
    out.segment(row, nk) = y.segment(nb + dyn_->constraints().beam_offset(b), nk);
    row += nk;
  }
}

void CoupledImplicitSystem::accelerations(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                          Eigen::VectorXd& a, Eigen::VectorXd& lambda) {
  dyn_->evaluate(t, q, v);
  dyn_->solve_augmented(t, a, lambda);
}

}  // namespace mbfe::runtime
