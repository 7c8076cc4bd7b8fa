#include "generator/symbolic/loop_kinematics.h"

#include "generator/symbolic/spatial_composite_rigid_body.h"

namespace mbfe::gen {

using GiNaC::ex;

LoopKinematics planar_loop_kinematics(const ir::Model& model, const std::vector<BodyKinematics>& kin,
                                      const std::vector<GiNaC::symbol>& qd, CodeList& code) {
  const int n = static_cast<int>(model.bodies.size());
  LoopKinematics out;
  std::vector<Vec2x> velocity(n);
  for (int i = 0; i < n; ++i) {
    const ir::Body& body = model.bodies[i];
    const int p = body.parent;
    const BodyKinematics& k = kin[i];
    // v_i = v_p + w_p e_z x (o_i - o_p) [+ q_i' u_i for a slider].
    Vec2x v = p < 0 ? Vec2x{0, 0} : add(velocity[p], scale(kin[p].omega, perp(k.offset)));
    if (body.joint.type == ir::JointType::kPrismatic) v = add(v, scale(qd[i], k.axis));
    velocity[i] = define(code, v);
    LoopBody b;
    b.rotation = {{{{k.cos_angle, -k.sin_angle, 0}, {k.sin_angle, k.cos_angle, 0}, {0, 0, 1}}}};
    b.origin = {k.origin.x, k.origin.y, 0};
    b.omega = {0, 0, k.omega};
    b.velocity = {velocity[i].x, velocity[i].y, 0};
    b.alpha = zero3();  // the plane: no angular acceleration at q'' = 0
    b.bias_accel = {k.bias_accel.x, k.bias_accel.y, 0};
    out.bodies.push_back(b);
    // S_i at the ground origin: (e_z, o x e_z) for a revolute joint, (0, u) for a slider.
    if (body.joint.type == ir::JointType::kRevolute)
      out.columns.push_back({0, 0, 1, k.origin.y, -k.origin.x, 0});
    else
      out.columns.push_back({0, 0, 0, k.axis.x, k.axis.y, 0});
    out.velocity_parent.push_back(p);
    out.last_velocity.push_back(i);
  }
  return out;
}

LoopKinematics spatial_loop_kinematics(const ir::Model& model, const ir::CoordinateLayout& layout,
                                       const std::vector<SpatialBodyKinematics>& kin) {
  LoopKinematics out;
  out.velocity_parent = velocity_parents(model, layout);
  out.columns.resize(layout.num_velocities);
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const SpatialBodyKinematics& k = kin[i];
    out.bodies.push_back({k.rotation, k.origin, k.omega, k.velocity, k.alpha, k.bias_accel});
    for (std::size_t c = 0; c < k.columns.size(); ++c)
      out.columns[layout.first_velocity[i] + c] = at_ground_origin(k.columns[c], k.origin);
    out.last_velocity.push_back(layout.first_velocity[i] + static_cast<int>(k.columns.size()) - 1);
  }
  return out;
}

}  // namespace mbfe::gen
