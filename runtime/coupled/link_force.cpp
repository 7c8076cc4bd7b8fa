#include "runtime/coupled/link_force.h"

namespace mbfe::runtime {

LinkForce::LinkForce(const ir::Link& link, double rest, const LinkGradient& g, bool inside, int nb)
    : name_(link.name), k_(link.stiffness), c_(link.damping), rest_(rest), slack_(link.slack), inside_(inside),
      g_(g), nb_(nb) {}

void LinkForce::add_force(const ForceArgs& x, ForceState& state, ForceSink& out) const {
  LinkState& st = static_cast<State&>(state).link;
  double ext = -rest_, rate = 0.0;
  for (int i = 0; i < g_.size; ++i) {
    ext += g_.values[i] * x.qc[g_.cols[i]];
    rate += g_.values[i] * x.vc[g_.cols[i]];
  }
  double t = k_ * ext + c_ * rate;
  st.extension = ext;
  st.rate = rate;
  st.slack = slack_ && t <= 0.0;
  if (st.slack) t = 0.0;
  st.tension = t;
  // Inside a joined structure, the force less the structure's part (see the header).
  const double f = inside_ ? t - k_ * (ext + rest_) : t;
  if (f == 0.0) return;
  for (int i = 0; i < g_.size; ++i) out.fc[g_.cols[i]] -= f * g_.values[i];
}

void LinkForce::add_tangent(const ForceArgs&, const ForceState& state, double c_q, double c_v,
                            TangentSink& out) const {
  const bool slack = static_cast<const State&>(state).link.slack;
  const double spring = c_q * k_, damper = c_v * c_;
  const double w = !inside_ ? (slack ? 0.0 : spring + damper) : (slack ? -spring : damper);
  if (w == 0.0) return;
  for (int i = 0; i < g_.size; ++i)
    for (int j = 0; j < g_.size; ++j) out.add(nb_ + g_.cols[i], nb_ + g_.cols[j], w * g_.values[i] * g_.values[j]);
}

void LinkForce::beam_dofs_read(const double*, std::vector<int>& out) const {
  out.insert(out.end(), g_.cols, g_.cols + g_.size);
}

}  // namespace mbfe::runtime
