#include "generator/symbolic/newton_euler.h"

#include "generator/symbolic/time_functions.h"

namespace mbfe::gen {

using GiNaC::ex;

SubtreeForces newton_euler_pass(const ir::Model& model, const std::vector<BodyKinematics>& kin,
                                const std::vector<std::vector<int>>& children, const std::vector<GiNaC::symbol>& q,
                                const std::vector<GiNaC::symbol>& qd, const GiNaC::symbol& t,
                                CodeList& code) {
  const int n = static_cast<int>(model.bodies.size());
  // ---- Backward pass (eq (5)): bias forces F and applied forces Q. ----
  // f: net force the subtree needs (inertial) or receives (applied);
  // m: its moment about the body's joint origin.
  SubtreeForces out;
  std::vector<Vec2x>& inertial_force = out.inertial_force;
  std::vector<Vec2x>& applied_force = out.applied_force;
  std::vector<ex>& inertial_moment = out.inertial_moment;
  std::vector<ex>& applied_moment = out.applied_moment;
  inertial_force.resize(n);
  applied_force.resize(n);
  inertial_moment.resize(n);
  applied_moment.resize(n);
  std::vector<ex> torque_load(n, 0);
  std::vector<Vec2x> point_force(n, Vec2x{0, 0});
  std::vector<ex> point_moment(n, 0);
  std::vector<ex>& spring = out.spring;
  spring.assign(n, 0);
  for (const ir::Load& load : model.loads) {
    const int b = load.body;
    switch (load.type) {
      case ir::LoadType::kForce: {
        const ir::Vec2 local = load.point >= 0 ? model.bodies[b].points[load.point].position
                                                  : ir::Vec2{0.0, 0.0};
        const Vec2x arm = rotate(kin[b].cos_angle, kin[b].sin_angle, constant(local));
        const ex on = window_factor(load.window, t);
        const Vec2x force{on * to_ginac(load.force[0], t), on * to_ginac(load.force[1], t)};
        point_force[b] = add(point_force[b], force);
        point_moment[b] = point_moment[b] + cross(arm, force);
        break;
      }
      case ir::LoadType::kTorque:
        torque_load[b] = torque_load[b] + window_factor(load.window, t) * to_ginac(load.torque, t);
        break;
      case ir::LoadType::kSpringDamper:
        spring[b] = spring[b] - window_factor(load.window, t) * (exact(load.stiffness) * (q[b] - exact(load.rest)) +
                                                                 exact(load.damping) * qd[b]);
        break;
    }
  }
  const Vec2x gravity = constant(model.gravity);
  for (int i = n - 1; i >= 0; --i) {
    const ir::Body& body = model.bodies[i];
    const BodyKinematics& k = kin[i];
    const ex mass = exact(body.mass);
    // Centre-of-mass bias acceleration: a_i - w_i^2 (p_i - o_i).
    const Vec2x com_accel = sub(k.bias_accel, scale(k.omega * k.omega, k.com_offset));
    Vec2x f_in = scale(mass, com_accel);
    ex m_in = cross(k.com_offset, f_in);
    const Vec2x weight = scale(mass, gravity);
    Vec2x f_ap = add(weight, point_force[i]);
    ex m_ap = cross(k.com_offset, weight) + point_moment[i] + torque_load[i];
    for (int c : children[i]) {
      const Vec2x& lever = kin[c].offset;
      f_in = add(f_in, inertial_force[c]);
      m_in = m_in + inertial_moment[c] + cross(lever, inertial_force[c]);
      f_ap = add(f_ap, applied_force[c]);
      m_ap = m_ap + applied_moment[c] + cross(lever, applied_force[c]);
    }
    inertial_force[i] = define(code, f_in);
    inertial_moment[i] = code.define(m_in);
    applied_force[i] = define(code, f_ap);
    applied_moment[i] = code.define(m_ap);
  }
  return out;
}

}  // namespace mbfe::gen
