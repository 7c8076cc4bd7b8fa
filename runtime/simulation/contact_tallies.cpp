#include "runtime/simulation/contact_tallies.h"

#include <cmath>

namespace mbfe::runtime {

ContactTallies::ContactTallies(const CoupledModel& model, const ir::Model& ir) {
  for (const SliderSpringForce* s : model.slider_springs()) {
    springs_.emplace_back();
    springs_.back().name = s->name();
    const ir::Contact& c = ir.contacts[static_cast<std::size_t>(s->contact())];
    spring_point_.push_back({c.body, c.point});
  }
  for (std::size_t k = 0; k < model.links().size(); ++k) {
    const LinkForce& l = *model.links()[k];
    if (!l.can_go_slack()) continue;
    links_.push_back({l.name(), 0, 0.0, false, false});
    link_index_.push_back(static_cast<int>(k));
  }
}

void ContactTallies::count(double t, const CoupledDynamics& dynamics) {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    LinkSlackTally& c = links_[i];
    const bool slack = dynamics.link_state(link_index_[i]).slack;
    if (slack) c.time_slack += t - t_prev_;
    if (slack && !c.slack && c.seen) ++c.slackenings;
    c.slack = slack;
    c.seen = true;
  }
  for (std::size_t k = 0; k < springs_.size(); ++k) {
    const SpringContactState& st = dynamics.spring_state(static_cast<int>(k));
    SpringContactTally& c = springs_[k];
    const bool touching = st.delta > 0.0;  // in contact, pressing or not
    if (st.on_beam && !touching) c.time_off += t - t_prev_;
    if (c.seen && c.in_contact && !touching && st.on_beam) ++c.lift_offs;
    c.in_contact = touching;
    c.touched = c.touched || (touching && st.on_beam);
    c.seen = c.seen || st.on_beam;
  }
  t_prev_ = t;
}

void ContactTallies::place(const CoupledDynamics& dynamics, const Eigen::VectorXd& q) {
  const mbfe_model_v1& kernels = dynamics.kernels();
  if (kernels.point_position == nullptr) return;
  for (std::size_t k = 0; k < springs_.size(); ++k) {
    SpringContactTally& c = springs_[k];
    kernels.point_position(q.data(), spring_point_[k][0], spring_point_[k][1], c.end.data());
    if (std::isnan(c.start[0])) c.start = c.end;
  }
}

}  // namespace mbfe::runtime
