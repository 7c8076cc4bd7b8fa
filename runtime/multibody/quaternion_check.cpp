#include "runtime/multibody/quaternion_check.h"

#include <cmath>
#include <sstream>

#include "ir/coordinate_layout.h"

namespace mbfe::runtime {

std::string non_unit_quaternion(const ir::Model& model, const double* q) {
  const ir::CoordinateLayout layout = ir::coordinate_layout(model);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const ir::JointType type = model.bodies[b].joint.type;
    if (type != ir::JointType::kSpherical && type != ir::JointType::kFree) continue;
    const int w = layout.first_position[b] + (type == ir::JointType::kFree ? 3 : 0);
    const double norm = std::sqrt(q[w] * q[w] + q[w + 1] * q[w + 1] + q[w + 2] * q[w + 2] + q[w + 3] * q[w + 3]);
    if (std::abs(norm - 1.0) <= kUnitQuaternionTol) continue;  // NaN falls through
    std::ostringstream os;
    os.precision(10);  // a norm just past the tolerance shows as such
    os << "the quaternion of body '" << model.bodies[b].name << "' (" << layout.position_names[w] << " .. "
       << layout.position_names[w + 3] << ") has norm " << norm << ", expected 1 (within " << kUnitQuaternionTol
       << "): the kernels read it as a rotation, which it is only when unit; divide it by its norm";
    return os.str();
  }
  return "";
}

}  // namespace mbfe::runtime
