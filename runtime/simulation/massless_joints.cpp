#include "runtime/simulation/massless_joints.h"

#include <algorithm>

#include "ir/coordinate_layout.h"
#include "ir/model_error.h"

namespace mbfe::runtime {

bool carries_no_mass(const ir::Model& model, std::size_t body) {
  const ir::Body& b = model.bodies[body];
  const bool zero3 = std::all_of(b.inertia3.begin(), b.inertia3.end(), [](double v) { return v == 0.0; });
  if (b.mass != 0.0 || b.inertia != 0.0 || !zero3) return false;
  for (std::size_t k = 0; k < model.bodies.size(); ++k)
    if (model.bodies[k].parent == static_cast<int>(body) && !carries_no_mass(model, k)) return false;
  return true;
}

std::string moves_no_mass(const ir::Model& model, const std::string& coordinate, std::size_t body) {
  return "'" + coordinate + "' moves no mass: body '" + model.bodies[body].name +
         "' and every body it carries have mass 0 and inertia 0, so its acceleration is not defined; give it a "
         "mass or inertia, or drive its joint";
}

void refuse_massless_joints(const ir::Model& model) {
  // A rigid chain's run meets the singular M(q) at its first step and names
  // the massless bodies there (exit 3, its rows kept); a coupled run has no
  // such check and would step on with NaN.
  if (model.beams.empty() || !model.constraints.empty()) return;
  for (const ir::Contact& c : model.contacts)
    if (c.is_constraint()) return;
  for (std::size_t k = 0; k < model.bodies.size(); ++k) {
    const ir::Body& b = model.bodies[k];
    if (b.joint.motion || !carries_no_mass(model, k)) continue;
    const std::string coordinate = ir::position_names(b.joint.type, b.name).front();  // "wheel", or "drone_x"
    throw ir::ModelError(model.source_path, b.loc,
                         "model '" + model.name + "': " + moves_no_mass(model, coordinate, k));
  }
}

}  // namespace mbfe::runtime
