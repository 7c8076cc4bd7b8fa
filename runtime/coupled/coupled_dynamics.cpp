#include "runtime/coupled/coupled_dynamics.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "runtime/multibody/driven_coordinates.h"
#include "runtime/errors/multibody_errors.h"

namespace mbfe::runtime {

namespace {

// A matrix (saddle point, reduced system) is declared singular below this reciprocal condition number
// (double precision with a margin of ~1e3 ulps for the small dense solves).
constexpr double kSingularRcond = 1e-13;

std::vector<BeamMesh> meshes_of(const std::vector<CoupledBeam>& beams) {
  std::vector<BeamMesh> out;
  for (const CoupledBeam& b : beams) out.push_back(b.mesh);
  return out;
}

}  // namespace

CoupledDynamics::CoupledDynamics(const mbfe_model_v1& model, std::vector<CoupledBeam> beams,
                                 std::vector<BodyInertia> bodies, const std::vector<ir::Link>& links,
                                 std::vector<std::shared_ptr<const JoinedLowRank>> joined)
    : model_(model),
      beams_(std::move(beams)),
      bodies_(std::move(bodies)),
      cc_(model, meshes_of(beams_)),
      springs_(model, cc_),
      links_(links, cc_.beams(), cc_.beam_offsets()),
      joined_(std::move(joined)),
      nb_(model.num_coordinates),
      nc_(cc_.num_beam_dofs()) {
  if (model.abi_version != MBFE_MODEL_ABI_VERSION) {
    throw std::invalid_argument("model '" + std::string(model.model_name) +
                                "' has another ABI version; regenerate it");
  }
  for (const CoupledBeam& b : beams_) {
    const int n = b.mesh.num_free;
    if (b.M.rows() != n || b.M.cols() != n || b.P.size() != n || !b.force) {
      std::ostringstream os;
      os << "beam '" << b.mesh.name << "': M is " << b.M.rows() << " x " << b.M.cols()
         << " and P has " << b.P.size() << " entries, expected " << n
         << " (its free DOFs), and a force callback";
      throw std::invalid_argument(os.str());
    }
    auto f = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(b.M);
    if (f->info() != Eigen::Success || (n > 0 && !(f->vectorD().minCoeff() > 0.0))) {
      throw std::runtime_error("beam '" + b.mesh.name +
                               "': mass matrix is not positive definite (a lumped mass "
                               "matrix without rotary inertia cannot carry a contact)");
    }
    mc_factor_.push_back(std::move(f));
  }
  for (const auto& s : joined_) {
    Eigen::Index rows = 0;
    for (int b : s->beams) {
      if (b < 0 || b >= static_cast<int>(beams_.size()))
        throw std::invalid_argument("joined structure: beam index " + std::to_string(b) + " out of range");
      rows += beams_[b].mesh.num_free;
    }
    const Eigen::Index m = s->U.cols();
    if (s->U.rows() != rows || s->phi.rows() != rows || s->phi.cols() != m || s->d_C.size() != m ||
        s->d_K.size() != m) {
      std::ostringstream os;
      os << "joined structure: U is " << s->U.rows() << " x " << m << ", phi " << s->phi.rows() << " x "
         << s->phi.cols() << ", d_C and d_K " << s->d_C.size() << " and " << s->d_K.size() << "; its beams have "
         << rows << " free DOFs";
      throw std::invalid_argument(os.str());
    }
    for (int l : s->links) {
      if (l < 0 || l >= links_.count())
        throw std::invalid_argument("joined structure: link index " + std::to_string(l) + " out of range");
      links_.set_inside_structure(l, true);
    }
  }
  for (int i = 0; i < model.num_driven; ++i) driven_.push_back(model.driven_coordinates[i]);
  if (!driven_.empty() && cc_.num_rows() > 0) {
    throw std::invalid_argument("model '" + std::string(model.model_name) +
                                "': driven joints with pin or slider_pin contacts are not supported; "
                                "use slider_spring contacts with driven joints");
  }
  const int nd = static_cast<int>(driven_.size());
  drive_q_.resize(nd);
  drive_qd_.resize(nd);
  drive_qdd_.resize(nd);
  drive_m_rows_.resize(nd, nb_);
  drive_bias_.resize(nd);
  fc_extra_.resize(nc_);
  const int m = cc_.num_rows();
  mb_row_.resize(nb_, nb_);
  mb_.resize(nb_, nb_);
  fb_.resize(nb_);
  qb_force_.resize(nb_);
  rb_.resize(nb_);
  rc_.resize(nc_);
  ac0_.resize(nc_);
  gc_.resize(m);
  w_.resize(nc_, m);
  h_.resize(m, m);
}

bool CoupledDynamics::split_low_rank_beams() {
  if (!split_beam_.empty()) return true;
  if (cc_.num_rows() > 0 || !joined_.empty()) return false;
  std::vector<int> index(beams_.size(), -1);
  int size = 0;
  for (std::size_t k = 0; k < beams_.size(); ++k) {
    const BeamLowRank* lr = beams_[k].low_rank.get();
    if (lr == nullptr || lr->phi_rows.rows() != beams_[k].mesh.num_free || lr->phi_rows.cols() != lr->U.cols() ||
        lr->d_C.size() != lr->U.cols() || lr->d_K.size() != lr->U.cols())
      continue;
    index[k] = static_cast<int>(split_beam_.size());
    split_beam_.push_back(static_cast<int>(k));
    split_offset_.push_back(size);
    size += 2 * static_cast<int>(lr->U.cols());
    split_minv_p_.push_back(mc_factor_[k]->solve(beams_[k].P));
    split_phi_p_.push_back(lr->phi_rows.transpose() * beams_[k].P);
  }
  if (split_beam_.empty()) return false;
  split_index_ = std::move(index);
  split_size_ = size;
  split_acc_.setZero(size);
  return true;
}

void CoupledDynamics::split_to_nodal(int k, const Eigen::Ref<const Eigen::VectorXd>& s, const Eigen::VectorXd& e,
                                     Eigen::Ref<Eigen::VectorXd> q) const {
  const BeamLowRank& lr = *beams_[split_beam_[k]].low_rank;
  const Eigen::Index m = lr.U.cols();
  const int o = split_offset_[k];
  q = s;
  q.noalias() += lr.phi_rows * (e.segment(o, m) - e.segment(o + m, m));
}

double CoupledDynamics::split_to_nodal(int k, int dof, double s, const Eigen::VectorXd& e) const {
  const BeamLowRank& lr = *beams_[split_beam_[k]].low_rank;
  const Eigen::Index m = lr.U.cols();
  const int o = split_offset_[k];
  return s + lr.phi_rows.row(dof).dot(e.segment(o, m) - e.segment(o + m, m));
}

void CoupledDynamics::split_from_nodal(const Eigen::Ref<const Eigen::VectorXd>& qc, Eigen::VectorXd& e) const {
  e.resize(split_size_);
  for (std::size_t k = 0; k < split_beam_.size(); ++k) {
    const int b = split_beam_[k];
    const BeamLowRank& lr = *beams_[b].low_rank;
    const Eigen::Index m = lr.U.cols();
    const int o = split_offset_[k];
    e.segment(o, m).noalias() = lr.U.transpose() * qc.segment(cc_.beam_offset(b), beams_[b].mesh.num_free);
    e.segment(o + m, m) = e.segment(o, m);
  }
}

void CoupledDynamics::evaluate(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                               const ConstraintValues* at_q, const SplitState* split) {
  const int n = nb_ + nc_;
  if (q.size() != n || qd.size() != n) {
    std::ostringstream os;
    os << "coupled state has " << q.size() << " / " << qd.size() << " entries, expected " << n
       << " ([q_b; q_c])";
    throw std::invalid_argument(os.str());
  }
  if (split != nullptr && (split_beam_.empty() || split->e.size() != split_size_ || split->ed.size() != split_size_)) {
    std::ostringstream os;
    os << "split coordinates: " << split->e.size() << " / " << split->ed.size() << " kept-mode entries, expected "
       << split_size_ << (split_beam_.empty() ? " (no beam is split)" : "");
    throw std::invalid_argument(os.str());
  }
  const double* qb = q.data();
  const double* qbd = qd.data();
  if (!driven_.empty()) {
    q_motion_ = q;
    qd_motion_ = qd;
    impose_motion(t, q_motion_, qd_motion_);
    qb = q_motion_.data();
    qbd = qd_motion_.data();
  }
  // The beam coordinates the forces read; with split beams the DOFs they
  // read are made nodal (the rest keep the uniform part, and nothing reads them).
  const double* qc = q.data() + nb_;
  const double* qcd = qd.data() + nb_;
  if (split != nullptr) {
    split_qc_ = q.tail(nc_);
    split_qcd_ = qd.tail(nc_);
    split_read_.clear();
    springs_.columns_read(qb, split_read_);
    for (int k = 0; k < links_.count(); ++k) {
      const BeamLinks::Gradient& g = links_.gradient(k);
      split_read_.insert(split_read_.end(), g.cols, g.cols + g.size);
    }
    // eta - zeta and its rate once per beam; then one row of Phi_L per DOF read.
    split_delta_.resize(split_size_ / 2);
    split_delta_rate_.resize(split_size_ / 2);
    for (std::size_t k = 0; k < split_beam_.size(); ++k) {
      const Eigen::Index m = beams_[split_beam_[k]].low_rank->U.cols();
      const int o = split_offset_[k];
      split_delta_.segment(o / 2, m) = split->e.segment(o, m) - split->e.segment(o + m, m);
      split_delta_rate_.segment(o / 2, m) = split->ed.segment(o, m) - split->ed.segment(o + m, m);
    }
    for (int c : split_read_) {
      for (std::size_t k = 0; k < split_beam_.size(); ++k) {
        const int off = cc_.beam_offset(split_beam_[k]);
        if (c < off || c >= off + beams_[split_beam_[k]].mesh.num_free) continue;
        const BeamLowRank& lr = *beams_[split_beam_[k]].low_rank;
        const Eigen::Index m = lr.U.cols();
        const int o = split_offset_[k] / 2;
        split_qc_[c] = q[nb_ + c] + lr.phi_rows.row(c - off).dot(split_delta_.segment(o, m));
        split_qcd_[c] = qd[nb_ + c] + lr.phi_rows.row(c - off).dot(split_delta_rate_.segment(o, m));
      }
    }
    qc = split_qc_.data();
    qcd = split_qcd_.data();
  }
  evaluate_dynamics(model_, qb, qbd, t, mb_row_.data(), fb_.data(), qb_force_.data());
  mb_ = mb_row_;
  // Spring contacts load both sides; their beam part joins the time loads below.
  fc_extra_.setZero();
  bool extra = false;
  if (springs_.count() > 0) {
    springs_.apply(qb, qc, qbd, qcd, qb_force_, fc_extra_);
    extra = true;
  }
  if (links_.count() > 0) {
    links_.apply(qc, qcd, fc_extra_);
    extra = true;
  }
  rb_ = qb_force_ - fb_;
  // Driven coordinates: q'' known (driven_coordinates.h). Their rows of M and
  // F - Q are kept first, for the drive reactions.
  for (std::size_t k = 0; k < driven_.size(); ++k) {
    const int d = driven_[k];
    drive_m_rows_.row(k) = mb_.row(d);
    drive_bias_[k] = fb_[d] - qb_force_[d];
  }
  eliminate_driven(mb_, rb_, driven_, drive_qdd_);
  if (at_q != nullptr) {
    cv_.phi = at_q->phi;  // same sizes every call: copies, no allocation
    cv_.jb = at_q->jb;
    cv_.je = at_q->je;
    cv_.jcol = at_q->jcol;
    cv_.s = at_q->s;
    cv_.element = at_q->element;
    cc_.evaluate_gamma(qb, qc, qbd, qcd, cv_);
  } else {
    cc_.evaluate(t, qb, qc, qbd, qcd, cv_);
  }
  for (const CoupledBeam& b : beams_) extra = extra || static_cast<bool>(b.time_loads);
  // Loads that change with time and spring and link forces, per beam.
  if (extra) {
    for (std::size_t k = 0; k < beams_.size(); ++k) {
      if (!beams_[k].time_loads) continue;
      const int off = cc_.beam_offset(static_cast<int>(k));
      beams_[k].time_loads(t, nodal_);
      for (const NodalForce& f : nodal_) fc_extra_[off + f.index] += f.value;
    }
  }
  // Beam side: a_c0 = M_c^-1 (P - (C qd + K q) + f_extra), one solve with M_c
  // per beam; a beam that gives its free acceleration without a solve needs
  // one for f_extra alone, when it has any.
  for (std::size_t k = 0; k < beams_.size(); ++k) {
    const int off = nb_ + cc_.beam_offset(static_cast<int>(k));
    const int nk = beams_[k].mesh.num_free;
    const auto fk = fc_extra_.segment(off - nb_, nk);
    if (split != nullptr && split_index_[k] >= 0) {
      split_accelerations(static_cast<int>(k), q.segment(off, nk), qd.segment(off, nk), extra ? fk.data() : nullptr,
                          *split, ac0_.segment(off - nb_, nk));
      continue;
    }
    if (beams_[k].acceleration) {
      beams_[k].acceleration(q.segment(off, nk), qd.segment(off, nk), ac0_.segment(off - nb_, nk));
      if (extra && !fk.isZero(0.0)) {
        tmp_ = fk;
        ac0_.segment(off - nb_, nk) += mc_factor_[k]->solve(tmp_);
      }
      continue;
    }
    Eigen::Ref<Eigen::VectorXd> rck = rc_.segment(off - nb_, nk);
    beams_[k].force(q.segment(off, nk), qd.segment(off, nk), rck);
    rck = beams_[k].P - rck;
    if (extra) rck += fk;
    ac0_.segment(off - nb_, nk) = mc_factor_[k]->solve(rck);
  }
  // Joined structures: M_s^-1 U = Phi_L, so their low-rank part enters the
  // accelerations without a solve.
  for (const auto& s : joined_) {
    const Eigen::Index ns = s->U.rows();
    joined_x_.resize(ns);
    joined_v_.resize(ns);
    Eigen::Index row = 0;
    for (int b : s->beams) {
      const int off = nb_ + cc_.beam_offset(b);
      const int nk = beams_[b].mesh.num_free;
      joined_x_.segment(row, nk) = q.segment(off, nk);
      joined_v_.segment(row, nk) = qd.segment(off, nk);
      row += nk;
    }
    joined_r_.noalias() = s->U.transpose() * joined_v_;
    joined_rk_.noalias() = s->U.transpose() * joined_x_;
    joined_r_ = s->d_C.cwiseProduct(joined_r_) + s->d_K.cwiseProduct(joined_rk_);
    row = 0;
    for (int b : s->beams) {
      const int off = cc_.beam_offset(b);
      const int nk = beams_[b].mesh.num_free;
      ac0_.segment(off, nk).noalias() -= s->phi.middleRows(row, nk) * joined_r_;
      row += nk;
    }
  }
  // W = M_c^-1 J_c^T column by column (each row of J_c lives on one beam, on
  // at most 4 of its DOFs): a combination of the cached columns M_c^-1 e_k.
  const int m = cc_.num_rows();
  w_.setZero();
  if (minv_col_.size() != beams_.size()) minv_col_.assign(beams_.size(), {});
  for (int r = 0; r < m; ++r) {
    const int beam = model_.contacts[cc_.contact_of_row(r)].beam;
    const int off = cc_.beam_offset(beam);
    const int nk = beams_[beam].mesh.num_free;
    auto& cols = minv_col_[beam];
    if (static_cast<int>(cols.size()) != nk) cols.assign(nk, Eigen::VectorXd());
    for (int j = 0; j < 4; ++j) {
      const int c = cv_.jcol(r, j);
      if (c < 0 || cv_.je(r, j) == 0.0) continue;
      Eigen::VectorXd& col = cols[c - off];
      if (col.size() == 0) {
        tmp_.setZero(nk);
        tmp_(c - off) = 1.0;
        col = mc_factor_[beam]->solve(tmp_);
      }
      w_.col(r).segment(off, nk) += cv_.je(r, j) * col;
    }
  }
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      double v = 0.0;
      for (int k = 0; k < 4; ++k) {
        if (cv_.jcol(i, k) >= 0) v += cv_.je(i, k) * w_(cv_.jcol(i, k), j);
      }
      h_(i, j) = v;
    }
  }
  cv_.jc_times(ac0_, gc_);
}

void CoupledDynamics::split_accelerations(int beam, const Eigen::Ref<const Eigen::VectorXd>& s,
                                          const Eigen::Ref<const Eigen::VectorXd>& sd,
                                          const double* f, const SplitState& split,
                                          Eigen::Ref<Eigen::VectorXd> a) {
  const int k = split_index_[beam];
  const BeamLowRank& lr = *beams_[beam].low_rank;
  const Eigen::Index m = lr.U.cols();
  const int o = split_offset_[k];
  // s'' = M^-1 (P + f) - c* s' - k* s, and the kept modes' load g = Phi_L^T (P + f)
  // from the rows of Phi_L where f is not zero (contacts, links, point loads).
  a = split_minv_p_[k] - lr.c_star * sd - lr.k_star * s;
  split_g_ = split_phi_p_[k];
  const Eigen::Map<const Eigen::VectorXd> loads(f, f != nullptr ? s.size() : 0);
  if (f != nullptr && !loads.isZero(0.0)) {
    tmp_ = loads;
    a += mc_factor_[beam]->solve(tmp_);
    for (Eigen::Index i = 0; i < loads.size(); ++i)
      if (loads[i] != 0.0) split_g_.noalias() += loads[i] * lr.phi_rows.row(i).transpose();
  }
  const auto eta = split.e.segment(o, m), zeta = split.e.segment(o + m, m);
  const auto etad = split.ed.segment(o, m), zetad = split.ed.segment(o + m, m);
  split_acc_.segment(o, m) = split_g_ - (lr.c_star + lr.d_C.array()).matrix().cwiseProduct(etad) -
                             (lr.k_star + lr.d_K.array()).matrix().cwiseProduct(eta);
  split_acc_.segment(o + m, m) = split_g_ - lr.c_star * zetad - lr.k_star * zeta;
}

void CoupledDynamics::solve_augmented(double t, Eigen::VectorXd& qdd, Eigen::VectorXd& lambda) {
  // Beam accelerations eliminated with the constant, factored M_c:
  //   q_c'' = a_c0 - W lambda, so the saddle-point system shrinks to
  //   [[M_b, J_b^T], [J_b, -H]] [q_b''; lambda] = [r_b; gamma - J_c a_c0].
  const int m = cc_.num_rows();
  Eigen::MatrixXd a(nb_ + m, nb_ + m);
  a.topLeftCorner(nb_, nb_) = mb_;
  a.topRightCorner(nb_, m) = cv_.jb.transpose();
  a.bottomLeftCorner(m, nb_) = cv_.jb;
  a.bottomRightCorner(m, m) = -h_;
  Eigen::VectorXd b(nb_ + m);
  b.head(nb_) = rb_;
  b.tail(m) = cv_.gamma - gc_;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
  const double rc = lu.rcond();
  if (!(rc >= kSingularRcond)) {
    if (m > 0 && sigma_min(cv_.jb * cv_.jb.transpose()) <
                     kSingularRcond * std::pow(constraint_scale(cv_), 2)) {
      throw_singular_constraints(cc_, cv_.jb, t, rc, "saddle-point matrix");
    }
    throw_singular_mass_matrix(model_, bodies_, mb_, t);
  }
  const Eigen::VectorXd x = lu.solve(b);
  qdd.resize(nb_ + nc_);
  qdd.head(nb_) = x.head(nb_);
  lambda = x.tail(m);
  qdd.tail(nc_) = ac0_ - w_ * lambda;
}

void CoupledDynamics::solve_partitioned(double t, const Partition& p, Eigen::VectorXd& qdd,
                                        Eigen::VectorXd& lambda) {
  // Unknowns x = [u''; mu] with mu = -lambda (docs/partitioning.md):
  //   v''    = X (gamma - g_c - J_u u'' - H mu),       X = J_v^-1
  //   q_c''  = a_c0 + W mu
  //   M_b q_b'' - J_b^T mu = r_b                       (16a) and (16b)
  // Every matrix below is a member sized once: no allocation per evaluation.
  const int m = cc_.num_rows();
  const int nu = static_cast<int>(p.independent.size());
  p_jv_.resize(m, m);
  p_ju_.resize(m, nu);
  for (int i = 0; i < m; ++i) p_jv_.col(i) = cv_.jb.col(p.dependent[i]);
  for (int i = 0; i < nu; ++i) p_ju_.col(i) = cv_.jb.col(p.independent[i]);
  p_d_.resize(m);
  p_xju_.resize(m, nu);
  p_xh_.resize(m, m);
  if (m > 0) {
    p_jv_lu_.compute(p_jv_);
    if (!clearly_regular(p_jv_lu_, cv_)) {
      const double rel = sigma_min(p_jv_) / constraint_scale(cv_);
      if (!(rel >= kSingularConstraint)) {
        throw_singular_constraints(cc_, cv_.jb, t, rel, "J_v of the partition");
      }
    }
    p_rhs_ = cv_.gamma - gc_;
    p_jv_lu_.solve(p_rhs_, p_d_);
    // nu == 0 (every coordinate dependent): p_xju_ stays m x 0. Eigen's
    // triangular solve of an empty right-hand side binds a reference to its
    // null data, which UndefinedBehaviorSanitizer reports.
    if (nu > 0) p_jv_lu_.solve(p_ju_, p_xju_);
    p_jv_lu_.solve(h_, p_xh_);
  }
  // Directions of q_b'' per unknown, then A = M_b * dir (- J_b^T for mu).
  p_dir_.setZero(nb_, nb_);
  for (int j = 0; j < nu; ++j) {
    p_dir_(p.independent[j], j) = 1.0;
    for (int i = 0; i < m; ++i) p_dir_(p.dependent[i], j) = -p_xju_(i, j);
  }
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) p_dir_(p.dependent[i], nu + j) = -p_xh_(i, j);
  }
  p_base_.setZero(nb_);
  for (int i = 0; i < m; ++i) p_base_(p.dependent[i]) = p_d_(i);
  p_a_.resize(nb_, nb_);
  p_a_.noalias() = mb_ * p_dir_;
  p_a_.rightCols(m) -= cv_.jb.transpose();
  p_b_ = rb_;
  p_b_.noalias() -= mb_ * p_base_;
  p_a_lu_.compute(p_a_);
  if (!(p_a_lu_.rcond_lower_cheap() >= kSingularRcond || p_a_lu_.rcond_lower() >= kSingularRcond)) {
    // The lower bounds are the cheap screen; when both fail, Eigen's
    // full-pivoting LU and its 1-norm condition estimate decide (the solve
    // below still uses the partial-pivoting factors).
    Eigen::FullPivLU<Eigen::MatrixXd> full(p_a_);
    if (!(full.rcond() >= kSingularRcond)) throw_singular_mass_matrix(model_, bodies_, mb_, t);
  }
  p_a_lu_.solve(p_b_, p_x_);
  qdd.resize(nb_ + nc_);
  qdd.head(nb_) = p_base_;
  qdd.head(nb_).noalias() += p_dir_ * p_x_;
  p_mu_ = p_x_.tail(m);
  qdd.tail(nc_) = ac0_;
  qdd.tail(nc_).noalias() += w_ * p_mu_;
  lambda = -p_mu_;
}

double CoupledDynamics::phi_max(const ConstraintValues& cv, int* row) const {
  if (cv.phi.size() == 0) {
    if (row) *row = 0;
    return 0.0;
  }
  int r = 0;
  const double v = cv.phi.cwiseAbs().maxCoeff(&r);
  if (row) *row = r;
  return v;
}

void CoupledDynamics::impose_motion(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd) const {
  if (driven_.empty()) return;
  model_.motion(t, drive_q_.data(), drive_qd_.data(), drive_qdd_.data());
  for (std::size_t k = 0; k < driven_.size(); ++k) {
    q[driven_[k]] = drive_q_[k];
    qd[driven_[k]] = drive_qd_[k];
  }
}

void CoupledDynamics::drive_reactions(const Eigen::VectorXd& qdd, Eigen::VectorXd& out) const {
  out = drive_m_rows_ * qdd.head(nb_) + drive_bias_;
}

std::vector<std::string> coupled_coordinate_names(const CoupledDynamics& dyn) {
  std::vector<std::string> out;
  const mbfe_model_v1& model = dyn.model();
  for (int i = 0; i < model.num_coordinates; ++i) {
    out.push_back(model.coordinate_names && model.coordinate_names[i]
                      ? model.coordinate_names[i]
                      : "q" + std::to_string(i));
  }
  for (const CoupledBeam& b : dyn.beams()) {
    std::vector<std::string> names(b.mesh.num_free);
    for (std::size_t full = 0; full < b.mesh.full_to_free.size(); ++full) {
      const int f = b.mesh.full_to_free[full];
      if (f < 0) continue;
      names[f] = b.mesh.name + (full % 2 == 0 ? "_w" : "_dw") + std::to_string(full / 2);
    }
    out.insert(out.end(), names.begin(), names.end());
  }
  return out;
}

}  // namespace mbfe::runtime
