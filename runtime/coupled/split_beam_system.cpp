#include "runtime/coupled/split_beam_system.h"

#include <algorithm>
#include <stdexcept>

namespace mbfe::runtime {

SplitBeamSystem::SplitBeamSystem(std::shared_ptr<CoupledDynamics> dyn) : CoupledSystem(std::move(dyn)) {
  if (!dyn_->split_low_rank_beams())
    throw std::invalid_argument("model '" + std::string(dyn_->kernels().model_name) +
                                "': split coordinates need a low-rank adjusted beam and no constraint contacts "
                                "or joined structures");
  for (int i = 0; i < dyn_->nb(); ++i) independent_.independent.push_back(i);
  // The entries of [q; e] a truncated beam leaves at 0: its q_c range and its zeta.
  const int n = dyn_->n(), nb = dyn_->nb(), ne = dyn_->num_split_coordinates();
  std::vector<char> left_out(static_cast<std::size_t>(n + ne), 0);
  const auto& structures = dyn_->model().structures();
  for (std::size_t k = 0; k < dyn_->split_structures().size(); ++k) {
    const LowRankStructure& st = *structures[static_cast<std::size_t>(dyn_->split_structures()[k])];
    if (!st.truncated()) continue;
    const LowRankStructure::Range& r = st.ranges().front();
    std::fill_n(left_out.begin() + nb + r.offset, r.size, 1);
    std::fill_n(left_out.begin() + n + dyn_->split_offsets()[k] + st.rank(), st.rank(), 1);
  }
  for (int i = 0; i < n + ne; ++i) {
    if (left_out[static_cast<std::size_t>(i)]) continue;
    // A run never spans q and e: they unpack into different vectors.
    if (runs_.empty() || runs_.back().full + runs_.back().size != i || i == n) runs_.push_back({i, 0});
    ++runs_.back().size;
    ++half_;
  }
  q_.setZero(n);
  qd_.setZero(n);
  e_.setZero(ne);
  ed_.setZero(ne);
}

void SplitBeamSystem::unpack(const Eigen::VectorXd& y) {
  if (y.size() != size())
    throw std::invalid_argument("SplitBeamSystem: y has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(size()) + " ([q_b; q_c; e; rates], without truncated beams' zeros)");
  const int n = dyn_->n();
  int at = 0;
  for (const Run& r : runs_) {
    if (r.full < n) {
      q_.segment(r.full, r.size) = y.segment(at, r.size);
      qd_.segment(r.full, r.size) = y.segment(half_ + at, r.size);
    } else {
      e_.segment(r.full - n, r.size) = y.segment(at, r.size);
      ed_.segment(r.full - n, r.size) = y.segment(half_ + at, r.size);
    }
    at += r.size;
  }
}

void SplitBeamSystem::pack(const Eigen::VectorXd& q, const Eigen::VectorXd& e, double* half) const {
  const int n = dyn_->n();
  for (const Run& r : runs_) {
    const double* from = r.full < n ? q.data() + r.full : e.data() + (r.full - n);
    std::copy(from, from + r.size, half);
    half += r.size;
  }
}

int SplitBeamSystem::full_index(int i) const {
  for (const Run& r : runs_) {
    if (i < r.size) return r.full + i;
    i -= r.size;
  }
  return -1;
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
  ydot.resize(y.size());
  ydot.head(half_) = y.tail(half_);
  pack(qdd_, dyn_->split_accelerations(), ydot.data() + half_);
}

std::string SplitBeamSystem::name(int i) const {
  const int n = dyn_->n(), nz = half_;
  const int k = full_index(i % nz);
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
  // A truncated beam has no uniform part: its q is Phi_L eta, the projection
  // eta = Phi_L^T M q of the nodal state on its kept modes; pack leaves its
  // q_c range (and its zeta, 0) out.
  Eigen::VectorXd y(size());
  Eigen::VectorXd e(ne), ed(ne);
  dyn_->split_from_nodal(q.tail(n - nb), e);
  dyn_->split_from_nodal(qd.tail(n - nb), ed);
  pack(q, e, y.data());
  pack(qd, ed, y.data() + half_);
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
