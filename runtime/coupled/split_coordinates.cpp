// CoupledDynamics in split coordinates (docs/damping-adjustment.md, "Split
// coordinates"): which low-rank beams are split, the maps between their
// nodal and split coordinates, the DOFs the forces read made nodal, and the
// kept modes' accelerations.
#include "runtime/coupled/coupled_dynamics.h"

#include "runtime/linalg/row_products.h"
#include "runtime/platform/thread_budget.h"

namespace mbfe::runtime {

namespace {

// Split structures of at least this many DOFs share an evaluation's work
// between two threads (docs/performance.md, "Both cores in a step").
constexpr int kLaneDofs = 2000;

}  // namespace

bool CoupledDynamics::split_low_rank_beams() {
  if (!split_structure_.empty()) return true;
  if (!model_->splittable()) return false;
  const auto& structures = model_->structures();
  split_of_structure_.assign(structures.size(), -1);
  int size = 0;
  for (std::size_t s = 0; s < structures.size(); ++s) {
    const LowRankStructure& st = *structures[s];
    if (st.ranges().size() != 1 || st.every_mode()) continue;
    split_of_structure_[s] = static_cast<int>(split_structure_.size());
    split_structure_.push_back(static_cast<int>(s));
    split_offset_.push_back(size);
    size += 2 * st.rank();
  }
  split_size_ = size;
  data_.split_acc.setZero(size);
  for (const CoupledBeam& b : model_->beams())
    if (b.structure < 0 || split_of_structure_[static_cast<std::size_t>(b.structure)] < 0)
      unsplit_ranges_.emplace_back(b.offset, b.mesh.num_free);
  // Two lanes pay when each split structure's share of an evaluation (a row
  // of Phi_L per DOF the forces read, a sparse solve) outweighs handing it
  // to another thread, tens of microseconds on a busy host.
  std::size_t large = 0;
  for (int s : split_structure_)
    if (structures[static_cast<std::size_t>(s)]->ranges().front().size >= kLaneDofs) ++large;
  lanes_ = std::make_unique<StructureLanes>(large >= 2 && thread_budget() >= 2);
  return true;
}

void CoupledDynamics::split_read_dofs_nodal(const double* qb, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                            const SplitState& split) {
  const CoupledModel& model = *model_;
  CoupledData& d = data_;
  const int nb = model.nb(), nc = model.nc();
  if (d.split_qc.size() != nc) {
    d.split_qc = q.tail(nc);
    d.split_qcd = qd.tail(nc);
  }
  for (const auto& [offset, size] : unsplit_ranges_) {
    d.split_qc.segment(offset, size) = q.segment(nb + offset, size);
    d.split_qcd.segment(offset, size) = qd.segment(nb + offset, size);
  }
  d.split_read.clear();
  for (const auto& f : model.forces()) f->beam_dofs_read(qb, d.split_read);
  // eta - zeta and its rate once per structure; then one row of Phi_L per DOF read.
  d.split_delta.resize(split_size_ / 2);
  d.split_delta_rate.resize(split_size_ / 2);
  for (std::size_t k = 0; k < split_structure_.size(); ++k) {
    const Eigen::Index m = model.structures()[split_structure_[k]]->rank();
    const int o = split_offset_[k];
    d.split_delta.segment(o / 2, m) = split.e.segment(o, m) - split.e.segment(o + m, m);
    d.split_delta_rate.segment(o / 2, m) = split.ed.segment(o, m) - split.ed.segment(o + m, m);
  }
  auto nodal = [&](int k) {
    const std::size_t s = static_cast<std::size_t>(split_structure_[static_cast<std::size_t>(k)]);
    const LowRankStructure& st = *model.structures()[s];
    const LowRankStructure::Range& r = st.ranges().front();
    const Eigen::Index m = st.rank();
    const int o = split_offset_[static_cast<std::size_t>(k)] / 2;
    LowRankStructure::Workspace& ws = d.structures[s];
    ws.rows.clear();
    for (int c : d.split_read) {
      if (c < r.offset || c >= r.offset + r.size) continue;
      char& listed = ws.row_listed[static_cast<std::size_t>(c - r.offset)];
      if (!listed) ws.rows.push_back(c - r.offset);  // two forces at one DOF read it once
      listed = 1;
    }
    for (int row : ws.rows) ws.row_listed[static_cast<std::size_t>(row)] = 0;
    const int n = static_cast<int>(ws.rows.size());
    ws.row_x.resize(ws.rows.size());
    ws.row_v.resize(ws.rows.size());
    dot_rows(st.phi().data(), m, ws.rows.data(), n, d.split_delta.data() + o, d.split_delta_rate.data() + o,
             ws.row_x.data(), ws.row_v.data());
    for (int i = 0; i < n; ++i) {
      const int c = r.offset + ws.rows[static_cast<std::size_t>(i)];
      d.split_qc[c] = q[nb + c] + ws.row_x[static_cast<std::size_t>(i)];
      d.split_qcd[c] = qd[nb + c] + ws.row_v[static_cast<std::size_t>(i)];
    }
  };
  lanes_->run(static_cast<int>(split_structure_.size()), nodal);
}

void CoupledDynamics::split_to_nodal(int k, const Eigen::Ref<const Eigen::VectorXd>& s, const Eigen::VectorXd& e,
                                     Eigen::Ref<Eigen::VectorXd> q) const {
  const LowRankStructure& st = *model_->structures()[split_structure_[k]];
  const Eigen::Index m = st.rank();
  const int o = split_offset_[k];
  q = s;
  q.noalias() += st.phi() * (e.segment(o, m) - e.segment(o + m, m));
}

double CoupledDynamics::split_to_nodal(int k, int dof, double s, const Eigen::VectorXd& e) const {
  const LowRankStructure& st = *model_->structures()[split_structure_[k]];
  const Eigen::Index m = st.rank();
  const int o = split_offset_[k];
  return s + st.phi().row(dof).dot(e.segment(o, m) - e.segment(o + m, m));
}

void CoupledDynamics::split_from_nodal(const Eigen::Ref<const Eigen::VectorXd>& qc, Eigen::VectorXd& e) const {
  e.resize(split_size_);
  for (std::size_t k = 0; k < split_structure_.size(); ++k) {
    const LowRankStructure& st = *model_->structures()[split_structure_[k]];
    const Eigen::Index m = st.rank();
    const int o = split_offset_[k];
    const LowRankStructure::Range& r = st.ranges().front();
    e.segment(o, m).noalias() = st.phi().transpose() * (st.M() * qc.segment(r.offset, r.size));
    // A truncated beam is Phi_L eta alone: s = 0 and zeta = 0 (SplitBeamSystem).
    if (st.truncated())
      e.segment(o + m, m).setZero();
    else
      e.segment(o + m, m) = e.segment(o, m);
  }
}

void CoupledDynamics::split_accelerations(int k, const Eigen::Ref<const Eigen::VectorXd>& s,
                                          const Eigen::Ref<const Eigen::VectorXd>& sd, const double* f,
                                          const SplitState& split, Eigen::Ref<Eigen::VectorXd> a) {
  const LowRankStructure& st = *model_->structures()[split_structure_[k]];
  CoupledData& d = data_;
  const Eigen::Index m = st.rank();
  const int o = split_offset_[k];
  const double mu_m = st.mass().mu, mu_c = st.damping().mu, mu_k = st.stiffness().mu;
  // s'' = B^-1 (P + f) / mu_M - (mu_C s' + mu_K s) / mu_M, and the kept
  // modes' load g = Phi_L^T (P + f) from the rows of Phi_L where f is not
  // zero (contacts, links, point loads). A truncated beam has no s (it stays
  // 0) and no zeta: no sparse solve, only the kept modes.
  const bool truncated = st.truncated();
  if (truncated)
    a.setZero();
  else
    a = st.base_load_response() - (mu_c / mu_m) * sd - (mu_k / mu_m) * s;
  // Each structure's own scratch: the two wires of a catenary differ in size.
  LowRankStructure::Workspace& ws = d.structures[static_cast<std::size_t>(split_structure_[k])];
  Eigen::VectorXd& g = ws.modal_g;
  g = st.modal_loads();
  const Eigen::Map<const Eigen::VectorXd> loads(f, f != nullptr ? s.size() : 0);
  if (f != nullptr && !loads.isZero(0.0)) {
    if (!truncated) {
      ws.r = loads;
      st.solve_base(ws.r, ws.base_solve, ws);
      a += ws.base_solve / mu_m;
    }
    ws.rows.clear();
    ws.row_x.clear();
    for (Eigen::Index i = 0; i < loads.size(); ++i)
      if (loads[i] != 0.0) {
        ws.rows.push_back(static_cast<int>(i));
        ws.row_x.push_back(loads[i]);
      }
    add_rows(st.phi().data(), m, ws.rows.data(), ws.row_x.data(), static_cast<int>(ws.rows.size()), g.data());
  }
  const auto eta = split.e.segment(o, m), zeta = split.e.segment(o + m, m);
  const auto etad = split.ed.segment(o, m), zetad = split.ed.segment(o + m, m);
  const auto b = st.base_modal().array();
  d.split_acc.segment(o, m) = ((g.array() - (mu_c * b + st.damping().d.array()) * etad.array() -
                                (mu_k * b + st.stiffness().d.array()) * eta.array()) /
                               (mu_m * b + st.mass().d.array()))
                                  .matrix();
  if (truncated)
    d.split_acc.segment(o + m, m).setZero();
  else
    d.split_acc.segment(o + m, m) =
        (g.array() / (mu_m * b) - (mu_c / mu_m) * zetad.array() - (mu_k / mu_m) * zeta.array()).matrix();
}

}  // namespace mbfe::runtime
