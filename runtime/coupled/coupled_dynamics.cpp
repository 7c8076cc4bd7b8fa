#include "runtime/coupled/coupled_dynamics.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "runtime/errors/multibody_errors.h"
#include "runtime/fem/hermite_shape.h"
#include "runtime/linalg/inverse_norm.h"
#include "runtime/linalg/sparse_ldlt_solve.h"

namespace mbfe::runtime {

namespace {

// A matrix (saddle point, reduced system) is declared singular below this reciprocal condition number
// (double precision with a margin of ~1e3 ulps for the small dense solves).
constexpr double kSingularRcond = 1e-13;

// x = A^-1 b from A's full-pivoting factors, A = P^-1 L U Q^-1, through `tmp`:
// the arithmetic of FullPivLU::solve for a regular A, without its temporary.
void solve_with(const Eigen::FullPivLU<Eigen::MatrixXd>& lu, const Eigen::VectorXd& b, Eigen::VectorXd& tmp,
                Eigen::VectorXd& x) {
  tmp.noalias() = lu.permutationP() * b;
  lu.matrixLU().triangularView<Eigen::UnitLower>().solveInPlace(tmp);
  lu.matrixLU().triangularView<Eigen::Upper>().solveInPlace(tmp);
  x.noalias() = lu.permutationQ() * tmp;
}

// A lower bound of A's reciprocal 2-norm condition number, 1 / (||A||_F
// ||A^-1||_F), at least `floor`: A^-1 column by column from the factors
// (||Q y|| = ||y||), no allocation once `tmp` has A's size. False for a
// matrix near singular (or exactly: a zero pivot gives inf), which the
// caller then judges by Eigen's estimate.
bool clearly_regular(const Eigen::FullPivLU<Eigen::MatrixXd>& lu, double norm, double floor, Eigen::VectorXd& tmp) {
  if (lu.rows() == 0) return true;
  // A^-1 e_c = Q U^-1 L^-1 P e_c; Q permutes the column's entries, leaving its norm.
  const double inverse_norm = inverse_frobenius_norm(lu.rows(), tmp, [&lu](Eigen::Index c, Eigen::VectorXd& x) {
    x[lu.permutationP().indices()[c]] = 1.0;  // P e_c
    lu.matrixLU().triangularView<Eigen::UnitLower>().solveInPlace(x);
    lu.matrixLU().triangularView<Eigen::Upper>().solveInPlace(x);
  });
  return 1.0 / (norm * inverse_norm) >= floor;
}

}  // namespace

CoupledData::CoupledData(const CoupledModel& model) {
  const int nb = model.nb(), nc = model.nc(), m = model.m();
  const int nd = model.driven().count();
  motion = model.driven().make_motion();
  drive_m_rows.resize(nd, nb);
  drive_bias.resize(nd);
  for (const auto& f : model.forces()) forces.push_back(f->make_state());
  fc_extra.resize(nc);
  mb_row.resize(nb, nb);
  mb.resize(nb, nb);
  fb.resize(nb);
  qb_force.resize(nb);
  rb.resize(nb);
  rc.resize(nc);
  ac0.resize(nc);
  gc.resize(m);
  w.resize(nc, m);
  h.resize(m, m);
  for (const auto& s : model.structures()) structures.push_back(s->make_workspace());
  minv_col.assign(model.beams().size(), {});
}

CoupledDynamics::CoupledDynamics(std::shared_ptr<const CoupledModel> model)
    : model_(std::move(model)), data_(*model_) {}

const SpringContactState& CoupledDynamics::spring_state(int k) const {
  const int element = model_->slider_spring_elements()[static_cast<std::size_t>(k)];
  return static_cast<const SliderSpringForce::State&>(*data_.forces[static_cast<std::size_t>(element)]).contact;
}

const LinkState& CoupledDynamics::link_state(int k) const {
  const int element = model_->link_elements()[static_cast<std::size_t>(k)];
  return static_cast<const LinkForce::State&>(*data_.forces[static_cast<std::size_t>(element)]).link;
}

void CoupledDynamics::evaluate(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                               const ConstraintValues* at_q, const SplitState* split) {
  const CoupledModel& model = *model_;
  CoupledData& d = data_;
  const int nb = model.nb(), nc = model.nc(), n = nb + nc;
  if (q.size() != n || qd.size() != n) {
    std::ostringstream os;
    os << "coupled state has " << q.size() << " / " << qd.size() << " entries, expected " << n << " ([q_b; q_c])";
    throw std::invalid_argument(os.str());
  }
  if (split != nullptr && (split_structure_.empty() || split->e.size() != split_size_ || split->ed.size() != split_size_)) {
    std::ostringstream os;
    os << "split coordinates: " << split->e.size() << " / " << split->ed.size() << " kept-mode entries, expected "
       << split_size_ << (split_structure_.empty() ? " (no beam is split)" : "");
    throw std::invalid_argument(os.str());
  }
  const double* qb = q.data();
  const double* qbd = qd.data();
  const DrivenCoordinates& driven = model.driven();
  if (!driven.empty()) {
    d.q_motion = q;
    d.qd_motion = qd;
    driven.impose(t, d.q_motion.data(), d.qd_motion.data(), d.motion);
    qb = d.q_motion.data();
    qbd = d.qd_motion.data();
  }
  // The beam coordinates the forces read; with split beams the DOFs they
  // read are made nodal, and the other DOFs of split beams are left as they
  // are (nothing reads them: ForceElement::beam_dofs_read).
  const double* qc = q.data() + nb;
  const double* qcd = qd.data() + nb;
  if (split != nullptr) {
    split_read_dofs_nodal(qb, q, qd, *split);
    qc = d.split_qc.data();
    qcd = d.split_qcd.data();
  }
  evaluate_dynamics(model.kernels(), qb, qbd, t, d.mb_row.data(), d.fb.data(), d.qb_force.data());
  d.mb = d.mb_row;
  // The force elements load both sides: rigid forces join Q_b, beam forces f_c.
  d.fc_extra.setZero();
  const ForceArgs args{t, qb, qbd, qc, qcd};
  ForceSink sink{d.qb_force.data(), d.fc_extra.data()};
  const auto& forces = model.forces();
  for (std::size_t e = 0; e < forces.size(); ++e) forces[e]->add_force(args, *d.forces[e], sink);
  const bool applied = add_applied_loads(t, d.fc_extra.data());
  const bool extra = !forces.empty() || applied;
  d.rb = d.qb_force - d.fb;
  // Driven coordinates: q'' known. Their rows of M and F - Q are kept first,
  // for the drive reactions.
  const std::vector<int>& driven_indices = driven.indices();
  for (std::size_t k = 0; k < driven_indices.size(); ++k) {
    const int dk = driven_indices[k];
    d.drive_m_rows.row(static_cast<Eigen::Index>(k)) = d.mb.row(dk);
    d.drive_bias[static_cast<Eigen::Index>(k)] = d.fb[dk] - d.qb_force[dk];
  }
  eliminate_driven(d.mb, d.rb, driven_indices, d.motion.qdd);
  const ContactConstraints& cc = model.constraints();
  if (at_q != nullptr) {
    d.cv.phi = at_q->phi;  // same sizes every call: copies, no allocation
    d.cv.jb = at_q->jb;
    d.cv.je = at_q->je;
    d.cv.jcol = at_q->jcol;
    d.cv.s = at_q->s;
    d.cv.element = at_q->element;
    cc.evaluate_gamma(qb, qc, qbd, qcd, d.cv);
  } else {
    cc.evaluate(t, qb, qc, qbd, qcd, d.cv);
  }
  // Beam side: a_c0 = M_c^-1 (P + f_c - (C q' + K q)), per beam of its own
  // or per adjusted structure (structure/low_rank_structure.h).
  const auto& beams = model.beams();
  const auto& structures = model.structures();
  for (std::size_t k = 0; k < beams.size(); ++k) {
    const CoupledBeam& b = beams[k];
    const int off = b.offset, nk = b.mesh.num_free;
    if (b.structure >= 0) continue;
    Eigen::Ref<Eigen::VectorXd> rck = d.rc.segment(off, nk);
    rck.noalias() = b.C * qd.segment(nb + off, nk);
    rck.noalias() += b.K * q.segment(nb + off, nk);
    rck = b.P - rck;
    if (extra) rck += d.fc_extra.segment(off, nk);
    solve_ldlt(model.mass_factor(static_cast<int>(k)), rck, d.ac0.segment(off, nk), d.ldlt);
  }
  // Each structure writes its own range of a_c0 and its own workspace: on
  // the lanes when it pays (split_low_rank_beams).
  auto structure_acceleration = [&](int i) {
    const std::size_t s = static_cast<std::size_t>(i);
    const LowRankStructure& st = *structures[s];
    const int k = split != nullptr ? split_of_structure_[s] : -1;
    if (k >= 0) {
      const LowRankStructure::Range& r = st.ranges().front();
      split_accelerations(k, q.segment(nb + r.offset, r.size), qd.segment(nb + r.offset, r.size),
                          extra ? d.fc_extra.data() + r.offset : nullptr, *split, d.ac0.segment(r.offset, r.size));
      return;
    }
    st.free_acceleration(q.data() + nb, qd.data() + nb, extra ? d.fc_extra.data() : nullptr, d.ac0.data(),
                         d.structures[s]);
  };
  if (lanes_ != nullptr && split != nullptr) {
    lanes_->run(static_cast<int>(structures.size()), structure_acceleration);
  } else {
    for (std::size_t s = 0; s < structures.size(); ++s) structure_acceleration(static_cast<int>(s));
  }
  // W = M_c^-1 J_c^T column by column (each row of J_c lives on one beam, on
  // at most 4 of its DOFs): a combination of the cached columns M_c^-1 e_k.
  const int m = model.m();
  d.w.setZero();
  for (int r = 0; r < m; ++r) {
    const int beam = model.kernels().contacts[cc.contact_of_row(r)].beam;
    const int off = cc.beam_offset(beam);
    const int nk = beams[beam].mesh.num_free;
    for (int j = 0; j < 4; ++j) {
      const int c = d.cv.jcol(r, j);
      if (c < 0 || d.cv.je(r, j) == 0.0) continue;
      d.w.col(r).segment(off, nk) += d.cv.je(r, j) * inverse_mass_column(beam, c);
    }
  }
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      double v = 0.0;
      for (int k = 0; k < 4; ++k) {
        if (d.cv.jcol(i, k) >= 0) v += d.cv.je(i, k) * d.w(d.cv.jcol(i, k), j);
      }
      d.h(i, j) = v;
    }
  }
  d.cv.jc_times(d.ac0, d.gc);
}

const Eigen::VectorXd& CoupledDynamics::inverse_mass_column(int beam, int c) {
  std::vector<Eigen::VectorXd>& cols = data_.minv_col[static_cast<std::size_t>(beam)];
  const CoupledBeam& b = model_->beams()[static_cast<std::size_t>(beam)];
  const int nk = b.mesh.num_free;
  if (static_cast<int>(cols.size()) != nk) cols.assign(nk, Eigen::VectorXd());
  Eigen::VectorXd& col = cols[static_cast<std::size_t>(c - b.offset)];
  if (col.size() == 0) {
    data_.tmp.setZero(nk);
    data_.tmp(c - b.offset) = 1.0;
    // The beam's inertia: its M, or an adjusted structure's M_adj when that
    // is not M (the policy mass; such a structure is one beam's: the model
    // refuses constraint contacts on joined ones with another mass).
    const LowRankStructure* st = b.structure >= 0 ? model_->structures()[b.structure].get() : nullptr;
    if (st != nullptr && (st->base() != LowRankStructure::Base::kMass || !(st->mass().d.array() == 0.0).all())) {
      st->solve_mass(data_.tmp, col, data_.structures[static_cast<std::size_t>(b.structure)]);
    } else {
      col.resize(nk);
      solve_ldlt(model_->mass_factor(beam), data_.tmp, col, data_.ldlt);
    }
  }
  return col;
}

void CoupledDynamics::solve_augmented(double t, Eigen::VectorXd& qdd, Eigen::VectorXd& lambda) {
  // Beam accelerations eliminated with the constant, factored M_c:
  //   q_c'' = a_c0 - W lambda, so the saddle-point system shrinks to
  //   [[M_b, J_b^T], [J_b, -H]] [q_b''; lambda] = [r_b; gamma - J_c a_c0].
  // The matrix, its factors and the vectors live in the data, sized once.
  CoupledData& d = data_;
  const int nb = model_->nb(), nc = model_->nc(), m = model_->m();
  d.a_matrix.resize(nb + m, nb + m);
  d.a_matrix.topLeftCorner(nb, nb) = d.mb;
  d.a_matrix.topRightCorner(nb, m) = d.cv.jb.transpose();
  d.a_matrix.bottomLeftCorner(m, nb) = d.cv.jb;
  d.a_matrix.bottomRightCorner(m, m) = -d.h;
  d.a_rhs.resize(nb + m);
  d.a_rhs.head(nb) = d.rb;
  d.a_rhs.tail(m) = d.cv.gamma - d.gc;
  d.a_lu.compute(d.a_matrix);
  if (!clearly_regular(d.a_lu, d.a_matrix.norm(), kSingularRcond, d.a_tmp)) {
    // Near singular by the lower bound: Eigen's 1-norm estimate decides.
    const double rc = d.a_lu.rcond();
    if (!(rc >= kSingularRcond)) {
      if (m > 0 && sigma_min(d.cv.jb * d.cv.jb.transpose()) < kSingularRcond * std::pow(constraint_scale(d.cv), 2)) {
        throw_singular_constraints(model_->constraints(), d.cv.jb, t, rc, "saddle-point matrix");
      }
      throw_singular_mass_matrix(model_->kernels(), model_->bodies(), d.mb, t);
    }
  }
  solve_with(d.a_lu, d.a_rhs, d.a_tmp, d.a_x);
  qdd.resize(nb + nc);
  qdd.head(nb) = d.a_x.head(nb);
  lambda = d.a_x.tail(m);
  qdd.tail(nc) = d.ac0;
  qdd.tail(nc).noalias() -= d.w * lambda;
}

void CoupledDynamics::solve_partitioned(double t, const Partition& p, Eigen::VectorXd& qdd,
                                        Eigen::VectorXd& lambda) {
  // Unknowns x = [u''; mu] with mu = -lambda (docs/partitioning.md):
  //   v''    = X (gamma - g_c - J_u u'' - H mu),       X = J_v^-1
  //   q_c''  = a_c0 + W mu
  //   M_b q_b'' - J_b^T mu = r_b                       (16a) and (16b)
  // Every matrix below lives in the data, sized once: no allocation per evaluation.
  CoupledData& d = data_;
  const int nb = model_->nb(), nc = model_->nc(), m = model_->m();
  const int nu = static_cast<int>(p.independent.size());
  d.p_jv.resize(m, m);
  d.p_ju.resize(m, nu);
  for (int i = 0; i < m; ++i) d.p_jv.col(i) = d.cv.jb.col(p.dependent[i]);
  for (int i = 0; i < nu; ++i) d.p_ju.col(i) = d.cv.jb.col(p.independent[i]);
  d.p_d.resize(m);
  d.p_xju.resize(m, nu);
  d.p_xh.resize(m, m);
  if (m > 0) {
    d.p_jv_lu.compute(d.p_jv);
    if (!clearly_regular(d.p_jv_lu, d.cv)) {
      const double rel = sigma_min(d.p_jv) / constraint_scale(d.cv);
      if (!(rel >= kSingularConstraint)) {
        throw_singular_constraints(model_->constraints(), d.cv.jb, t, rel, "J_v of the partition");
      }
    }
    d.p_rhs = d.cv.gamma - d.gc;
    d.p_jv_lu.solve(d.p_rhs, d.p_d);
    // nu == 0 (every coordinate dependent): p_xju stays m x 0. Eigen's
    // triangular solve of an empty right-hand side binds a reference to its
    // null data, which UndefinedBehaviorSanitizer reports.
    if (nu > 0) d.p_jv_lu.solve(d.p_ju, d.p_xju);
    d.p_jv_lu.solve(d.h, d.p_xh);
  }
  // Directions of q_b'' per unknown, then A = M_b * dir (- J_b^T for mu).
  d.p_dir.setZero(nb, nb);
  for (int j = 0; j < nu; ++j) {
    d.p_dir(p.independent[j], j) = 1.0;
    for (int i = 0; i < m; ++i) d.p_dir(p.dependent[i], j) = -d.p_xju(i, j);
  }
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) d.p_dir(p.dependent[i], nu + j) = -d.p_xh(i, j);
  }
  d.p_base.setZero(nb);
  for (int i = 0; i < m; ++i) d.p_base(p.dependent[i]) = d.p_d(i);
  d.p_a.resize(nb, nb);
  d.p_a.noalias() = d.mb * d.p_dir;
  d.p_a.rightCols(m) -= d.cv.jb.transpose();
  d.p_b = d.rb;
  d.p_b.noalias() -= d.mb * d.p_base;
  d.p_a_lu.compute(d.p_a);
  if (!(d.p_a_lu.rcond_lower_cheap() >= kSingularRcond || d.p_a_lu.rcond_lower() >= kSingularRcond)) {
    // The lower bounds are the cheap screen; when both fail, Eigen's
    // full-pivoting LU and its 1-norm condition estimate decide (the solve
    // below still uses the partial-pivoting factors).
    Eigen::FullPivLU<Eigen::MatrixXd> full(d.p_a);
    if (!(full.rcond() >= kSingularRcond)) throw_singular_mass_matrix(model_->kernels(), model_->bodies(), d.mb, t);
  }
  d.p_a_lu.solve(d.p_b, d.p_x);
  qdd.resize(nb + nc);
  qdd.head(nb) = d.p_base;
  qdd.head(nb).noalias() += d.p_dir * d.p_x;
  d.p_mu = d.p_x.tail(m);
  qdd.tail(nc) = d.ac0;
  qdd.tail(nc).noalias() += d.w * d.p_mu;
  lambda = -d.p_mu;
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

void CoupledDynamics::set_applied_load(int beam, double s, std::function<double(double)> value) {
  const auto& beams = model_->beams();
  if (beam < 0 || beam >= static_cast<int>(beams.size()))
    throw std::invalid_argument("beam index " + std::to_string(beam) + " outside the model's " +
                                std::to_string(beams.size()) + " beams");
  const BeamMesh& mesh = beams[static_cast<std::size_t>(beam)].mesh;
  if (!(s >= 0.0 && s <= mesh.length()))
    throw std::invalid_argument("beam '" + mesh.name + "': s = " + std::to_string(s) + " m is off the beam [0, " +
                                std::to_string(mesh.length()) + "] m");
  CoupledData::AppliedLoad load;
  load.beam = beam;
  load.s = s;
  load.value = std::move(value);
  const int element = std::min(static_cast<int>(std::floor(s / mesh.element_length)), mesh.num_elements - 1);
  const double xi = (s - element * mesh.element_length) / mesh.element_length;
  const hermite::Row4 n = hermite::N(xi, mesh.element_length);
  for (int j = 0; j < 4; ++j) {
    const int f = mesh.full_to_free[2 * element + j];
    load.cols[j] = f >= 0 ? beams[static_cast<std::size_t>(beam)].offset + f : -1;
    load.weights[j] = n[j];
  }
  auto& applied = data_.applied;
  applied.erase(std::remove_if(applied.begin(), applied.end(),
                               [&](const CoupledData::AppliedLoad& a) { return a.beam == beam && a.s == s; }),
                applied.end());
  applied.push_back(std::move(load));
}

bool CoupledDynamics::add_applied_loads(double t, double* fc) const {
  for (const CoupledData::AppliedLoad& a : data_.applied) {
    const double v = a.value(t);
    for (int j = 0; j < 4; ++j)
      if (a.cols[j] >= 0 && a.weights[j] != 0.0) fc[a.cols[j]] += v * a.weights[j];
  }
  return !data_.applied.empty();
}

void CoupledDynamics::impose_motion(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  model_->driven().impose(t, q.data(), qd.data(), data_.motion);
}

void CoupledDynamics::drive_reactions(const Eigen::VectorXd& qdd, Eigen::VectorXd& out) const {
  out = data_.drive_m_rows * qdd.head(model_->nb()) + data_.drive_bias;
}

}  // namespace mbfe::runtime
