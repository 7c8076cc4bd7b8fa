#include "runtime/coupled/split_beam_system.h"

#include <stdexcept>

namespace mbfe::runtime {

SplitBeamSystem::SplitBeamSystem(std::shared_ptr<CoupledDynamics> dyn) : CoupledSystem(std::move(dyn)) {
  if (!dyn_->split_low_rank_beams())
    throw std::invalid_argument("model '" + std::string(dyn_->kernels().model_name) +
                                "': split coordinates need a low-rank adjusted beam and no constraint contacts "
                                "or joined structures");
  for (int i = 0; i < dyn_->nb(); ++i) independent_.independent.push_back(i);
}

void SplitBeamSystem::unpack(const Eigen::VectorXd& y) {
  const int n = dyn_->n(), ne = dyn_->num_split_coordinates();
  if (y.size() != size())
    throw std::invalid_argument("SplitBeamSystem: y has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(size()) + " ([q_b; q_c; e; rates])");
  q_ = y.head(n);
  e_ = y.segment(n, ne);
  qd_ = y.segment(n + ne, n);
  ed_ = y.tail(ne);
}

void SplitBeamSystem::rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) {
  // The state a run has just reported is the next step's first stage: its
  // derivative is the report's, and the dynamics still describe it (an RK4
  // step and its report then cost four evaluations, not five). Loads set
  // from outside may have changed since the report: then it is evaluated
  // again.
  if (is_reported(t, y) && !dyn_->has_applied_loads()) {
    ydot = ydot_;
    return;
  }
  report_valid_ = false;  // the dynamics' springs and links now describe this y
  unpack(y);
  const SplitState split{e_, ed_};
  dyn_->evaluate(t, q_, qd_, nullptr, &split);
  dyn_->solve_partitioned(t, independent_, qdd_, lambda_);
  const int n = dyn_->n(), ne = dyn_->num_split_coordinates();
  ydot.resize(y.size());
  ydot.head(n + ne) = y.tail(n + ne);
  ydot.segment(n + ne, n) = qdd_;
  ydot.tail(ne) = dyn_->split_accelerations();
}

std::string SplitBeamSystem::name(int i) const {
  const int n = dyn_->n(), ne = dyn_->num_split_coordinates(), nz = n + ne;
  const int k = i % nz;
  std::string base;
  if (k < n) {
    base = dyn_->model().coordinate_names()[k];
  } else {
    // The split beam whose kept-mode coordinates hold entry k - n.
    const int j = k - n;
    std::size_t b = 0;
    while (b + 1 < dyn_->split_offsets().size() && dyn_->split_offsets()[b + 1] <= j) ++b;
    const LowRankStructure& st = *dyn_->model().structures()[dyn_->split_structures()[b]];
    const int m = st.rank();
    const int r = j - dyn_->split_offsets()[b];
    base = st.name() + (r < m ? "_eta" : "_zeta") + std::to_string(r % m + 1);
  }
  return i < nz ? base : base + "_dot";
}

Eigen::VectorXd SplitBeamSystem::initial_state(double, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  const int n = dyn_->n(), nb = dyn_->nb(), ne = dyn_->num_split_coordinates();
  if (q.size() != n || qd.size() != n)
    throw std::invalid_argument("initial state has " + std::to_string(q.size()) + " / " + std::to_string(qd.size()) +
                                " entries, expected " + std::to_string(n) + " ([q_b; q_c])");
  Eigen::VectorXd y(size());
  y.head(n) = q;
  y.segment(n + ne, n) = qd;
  dyn_->split_from_nodal(q.tail(n - nb), e_);
  y.segment(n, ne) = e_;
  dyn_->split_from_nodal(qd.tail(n - nb), ed_);
  y.tail(ne) = ed_;
  // A truncated beam has no uniform part: its q is Phi_L eta, the projection
  // eta = Phi_L^T M q of the nodal state on its kept modes.
  for (int k : dyn_->split_structures()) {
    const LowRankStructure& st = *dyn_->model().structures()[k];
    if (!st.truncated()) continue;
    const LowRankStructure::Range& r = st.ranges().front();
    y.segment(nb + r.offset, r.size).setZero();
    y.segment(n + ne + nb + r.offset, r.size).setZero();
  }
  return y;
}

void SplitBeamSystem::full_state(double, const Eigen::VectorXd& y, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  unpack(y);
  q = q_;
  qd = qd_;
  const int nb = dyn_->nb();
  for (std::size_t k = 0; k < dyn_->split_structures().size(); ++k) {
    const LowRankStructure::Range& r = dyn_->model().structures()[dyn_->split_structures()[k]]->ranges().front();
    const int off = nb + r.offset, nk = r.size;
    dyn_->split_to_nodal(static_cast<int>(k), q_.segment(off, nk), e_, q.segment(off, nk));
    dyn_->split_to_nodal(static_cast<int>(k), qd_.segment(off, nk), ed_, qd.segment(off, nk));
  }
}

void SplitBeamSystem::full_state_at(double, const Eigen::VectorXd& y, const std::vector<int>& beam_dofs,
                                    Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  unpack(y);
  q = q_;
  qd = qd_;
  const int nb = dyn_->nb();
  for (int c : beam_dofs) {
    for (std::size_t k = 0; k < dyn_->split_structures().size(); ++k) {
      const LowRankStructure::Range& r = dyn_->model().structures()[dyn_->split_structures()[k]]->ranges().front();
      const int off = r.offset;
      if (c < off || c >= off + r.size) continue;
      q[nb + c] = dyn_->split_to_nodal(static_cast<int>(k), c - off, q_[nb + c], e_);
      qd[nb + c] = dyn_->split_to_nodal(static_cast<int>(k), c - off, qd_[nb + c], ed_);
    }
  }
}

bool SplitBeamSystem::is_reported(double t, const Eigen::VectorXd& y) const {
  return report_valid_ && t == report_t_ && y.size() == report_y_.size() && y == report_y_;
}

const ContactReport& SplitBeamSystem::report(double t, const Eigen::VectorXd& y) {
  // A run reports each accepted state twice (its tallies, its row); the
  // second time, nothing has been evaluated since the first.
  if (is_reported(t, y)) return report_;
  rhs(t, y, ydot_);
  ContactReport& r = report_;
  r.lambda = lambda_;
  r.qdd = qdd_;  // a split beam's q_c'' slot holds s''
  r.phi = dyn_->values().phi;
  r.phi_max = dyn_->phi_max(dyn_->values());
  r.s = dyn_->values().s;
  report_y_ = y;
  report_t_ = t;
  report_valid_ = true;
  return r;
}

}  // namespace mbfe::runtime
