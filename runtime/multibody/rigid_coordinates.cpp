#include "runtime/multibody/rigid_coordinates.h"

#include <cmath>

#include "ir/coordinate_layout.h"

namespace mbfe::runtime {

RigidCoordinates rigid_coordinates(const ir::Model& model) {
  const ir::CoordinateLayout layout = ir::coordinate_layout(model);
  RigidCoordinates c;
  c.nq = layout.num_positions;
  c.nv = layout.num_velocities;
  c.position_columns = layout.position_names;
  c.velocity_body = layout.velocity_body;
  c.position_quantity = layout.position_quantity;
  c.velocity_quantity = layout.velocity_quantity;
  c.rate_of.assign(c.nv, -1);
  c.rotation_of.assign(c.nv, -1);
  c.rotation_axis.assign(c.nv, -1);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const ir::Body& body = model.bodies[b];
    const int q0 = layout.first_position[b], v0 = layout.first_velocity[b];
    switch (body.joint.type) {
      case ir::JointType::kRevolute:
      case ir::JointType::kPrismatic:
        c.rate_of[v0] = q0;
        c.velocity_columns.push_back(layout.velocity_names[v0] + "_dot");
        break;
      case ir::JointType::kFree:
      case ir::JointType::kSpherical: {
        const bool free = body.joint.type == ir::JointType::kFree;
        const int translations = free ? 3 : 0;
        for (int k = 0; k < translations; ++k) c.rate_of[v0 + k] = q0 + k;
        const int quat = q0 + translations;
        c.quaternions.push_back(quat);
        for (int k = 0; k < 3; ++k) {
          c.rotation_of[v0 + translations + k] = quat;
          c.rotation_axis[v0 + translations + k] = k;
        }
        for (int k = 0; k < translations + 3; ++k) c.velocity_columns.push_back(layout.velocity_names[v0 + k]);
        break;
      }
    }
  }
  return c;
}

void displace(const RigidCoordinates& c, double* q, const Eigen::VectorXd& dv) {
  for (int i = 0; i < c.nv; ++i)
    if (c.rate_of[i] >= 0) q[c.rate_of[i]] += dv[i];
  for (int w : c.quaternions) {
    double r[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < c.nv; ++i)
      if (c.rotation_of[i] == w) r[c.rotation_axis[i]] = dv[i];
    const double angle = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    if (angle == 0.0) continue;
    // quat * (cos(angle / 2), sin(angle / 2) r / angle), Hamilton's product.
    const double s = std::sin(0.5 * angle) / angle, e0 = std::cos(0.5 * angle);
    const double e1 = s * r[0], e2 = s * r[1], e3 = s * r[2];
    const double a0 = q[w], a1 = q[w + 1], a2 = q[w + 2], a3 = q[w + 3];
    q[w] = a0 * e0 - a1 * e1 - a2 * e2 - a3 * e3;
    q[w + 1] = a0 * e1 + a1 * e0 + a2 * e3 - a3 * e2;
    q[w + 2] = a0 * e2 - a1 * e3 + a2 * e0 + a3 * e1;
    q[w + 3] = a0 * e3 + a1 * e2 - a2 * e1 + a3 * e0;
  }
}

void normalize_quaternions(const RigidCoordinates& c, double* q) {
  for (int w : c.quaternions) {
    const double norm = std::sqrt(q[w] * q[w] + q[w + 1] * q[w + 1] + q[w + 2] * q[w + 2] + q[w + 3] * q[w + 3]);
    if (!(norm > 0.0)) continue;  // a zero quaternion is left for the kernels to fail on
    for (int k = 0; k < 4; ++k) q[w + k] /= norm;
  }
}

double quaternion_norm_error(const RigidCoordinates& c, const double* q) {
  double worst = 0.0;
  for (int w : c.quaternions) {
    const double norm = std::sqrt(q[w] * q[w] + q[w + 1] * q[w + 1] + q[w + 2] * q[w + 2] + q[w + 3] * q[w + 3]);
    worst = std::max(worst, std::abs(norm - 1.0));
  }
  return worst;
}

}  // namespace mbfe::runtime
