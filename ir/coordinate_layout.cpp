#include "ir/coordinate_layout.h"

namespace mbfe::ir {

std::vector<std::string> position_names(JointType type, const std::string& body) {
  switch (type) {
    case JointType::kSpherical:
      return {body + "_qw", body + "_qx", body + "_qy", body + "_qz"};
    case JointType::kFree:
      return {body + "_x", body + "_y", body + "_z", body + "_qw", body + "_qx", body + "_qy", body + "_qz"};
    default:
      return {body};
  }
}

std::vector<std::string> velocity_names(JointType type, const std::string& body) {
  switch (type) {
    case JointType::kSpherical:
      return {body + "_wx", body + "_wy", body + "_wz"};
    case JointType::kFree:
      return {body + "_vx", body + "_vy", body + "_vz", body + "_wx", body + "_wy", body + "_wz"};
    default:
      return {body};
  }
}

std::vector<Quantity> position_quantities(JointType type) {
  const Quantity entry = Quantity::kRatio, length = Quantity::kLength;
  switch (type) {
    case JointType::kSpherical:
      return {entry, entry, entry, entry};
    case JointType::kFree:
      return {length, length, length, entry, entry, entry, entry};
    default:
      return {joint_coordinate(type)};
  }
}

std::vector<Quantity> velocity_quantities(JointType type) {
  const Quantity angle = Quantity::kAngle, length = Quantity::kLength;
  switch (type) {
    case JointType::kSpherical:
      return {angle, angle, angle};
    case JointType::kFree:
      return {length, length, length, angle, angle, angle};
    default:
      return {joint_coordinate(type)};
  }
}

CoordinateLayout coordinate_layout(const Model& model) {
  CoordinateLayout layout;
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const Body& body = model.bodies[b];
    layout.first_position.push_back(layout.num_positions);
    layout.first_velocity.push_back(layout.num_velocities);
    layout.num_positions += position_count(body.joint.type);
    layout.num_velocities += velocity_count(body.joint.type);
    for (std::string& name : position_names(body.joint.type, body.name))
      layout.position_names.push_back(std::move(name));
    for (std::string& name : velocity_names(body.joint.type, body.name)) {
      layout.velocity_names.push_back(std::move(name));
      layout.velocity_body.push_back(static_cast<int>(b));
    }
    for (Quantity q : position_quantities(body.joint.type)) layout.position_quantity.push_back(q);
    for (Quantity q : velocity_quantities(body.joint.type)) layout.velocity_quantity.push_back(q);
  }
  return layout;
}

}  // namespace mbfe::ir
