#include "runtime/coupled/discrete_damping_force.h"

namespace mbfe::runtime {

DiscreteDampingForce::DiscreteDampingForce(const std::string& beam_name,
                                           std::vector<std::pair<int, double>> remainder, int offset, int nb)
    : remainder_(std::move(remainder)), nb_(nb), name_("damping of the discrete parts of '" + beam_name + "'") {
  for (auto& [dof, value] : remainder_) dof += offset;
}

void DiscreteDampingForce::add_force(const ForceArgs& x, ForceState&, ForceSink& out) const {
  for (const auto& [dof, r] : remainder_) out.fc[dof] -= r * x.vc[dof];
}

void DiscreteDampingForce::add_tangent(const ForceArgs&, const ForceState&, double, double c_v,
                                       TangentSink& out) const {
  for (const auto& [dof, r] : remainder_) out.add(nb_ + dof, nb_ + dof, c_v * r);
}

void DiscreteDampingForce::beam_dofs_read(const double*, std::vector<int>& out) const {
  for (const auto& [dof, r] : remainder_) out.push_back(dof);
}

}  // namespace mbfe::runtime
