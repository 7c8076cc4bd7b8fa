#include "runtime/simulation/static_start_hints.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace mbfe::runtime {

bool held_against_rigid_motion(const ir::Beam& beam) {
  std::vector<double> places;
  for (const ir::Support& s : beam.supports) {
    if (s.type == ir::SupportType::kClamped) return true;
    if (std::find(places.begin(), places.end(), s.at) == places.end()) places.push_back(s.at);
  }
  return places.size() >= 2;
}

std::string supports_in_words(const ir::Beam& beam) {
  if (beam.supports.empty()) return "no support";
  std::ostringstream os;
  os << beam.supports.size() << " support" << (beam.supports.size() == 1 ? "" : "s") << " at s =";
  for (std::size_t k = 0; k < beam.supports.size(); ++k) os << (k == 0 ? " " : ", ") << beam.supports[k].at;
  os << " m";
  return os.str();
}

std::vector<std::string> static_start_hints(const ir::Model& model, CoupledDynamics& dyn, const Eigen::VectorXd& q,
                                            const Eigen::VectorXd& qd) {
  std::vector<std::string> out;
  try {
    dyn.evaluate(0.0, q, qd);
  } catch (const std::runtime_error&) {
    return out;  // no state to judge there (a slider_pin off its beam): Newton says why
  }
  // Bodies over no beam: every compression-only contact of theirs off its beam.
  std::vector<std::string> off(model.bodies.size());
  std::vector<bool> any(model.bodies.size(), false), on(model.bodies.size(), false);
  int k = -1;
  for (const ir::Contact& c : model.contacts) {
    if (c.type != ir::ContactType::kSliderSpring) continue;
    ++k;
    if (!c.unilateral && c.law != ir::ContactLaw::kHertz) continue;
    const auto body = static_cast<std::size_t>(c.body);
    const SpringContactState& st = dyn.spring_state(k);
    any[body] = true;
    if (st.on_beam) {
      on[body] = true;
      continue;
    }
    const ir::Beam& beam = model.beams[static_cast<std::size_t>(c.beam)];
    std::ostringstream os;
    os << (off[body].empty() ? "" : ", ") << "'" << c.name << "' (s = " << st.s << " m; beam '" << beam.name
       << "' spans 0 to " << beam.length << " m)";
    off[body] += os.str();
  }
  for (std::size_t b = 0; b < model.bodies.size(); ++b)
    if (any[b] && !on[b])
      out.push_back("body '" + model.bodies[b].name + "' is over no beam at t = 0: its contact" +
                    (off[b].find("), '") == std::string::npos ? " " : "s ") + off[b] +
                    " hold nothing up (start it over a beam: its position or the carriage's, or a train's front)");
  // Beams free to move as rigid bodies, with nothing but contacts to hold them.
  for (std::size_t b = 0; b < model.beams.size(); ++b) {
    const ir::Beam& beam = model.beams[b];
    if (held_against_rigid_motion(beam)) continue;
    const bool linked = std::any_of(model.links.begin(), model.links.end(), [&](const ir::Link& l) {
      return l.a.beam == static_cast<int>(b) || l.b.beam == static_cast<int>(b);
    });
    const bool pinned = std::any_of(model.contacts.begin(), model.contacts.end(), [&](const ir::Contact& c) {
      return c.is_constraint() && c.beam == static_cast<int>(b);
    });
    if (linked || pinned) continue;
    out.push_back("beam '" + beam.name + "' has " + supports_in_words(beam) +
                  ", which leaves it free to turn or move as a rigid body; only the contacts on it hold it (give it "
                  "supports that hold it: two pinned, or one clamped)");
  }
  return out;
}

}  // namespace mbfe::runtime
