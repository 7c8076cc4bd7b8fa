#include "generator/symbolic/spatial_newton_euler.h"

#include "generator/symbolic/time_functions.h"

namespace mbfe::gen {

using GiNaC::ex;

ex project(const SpatialColumn& column, const Vec3x& force, const Vec3x& moment) {
  return dot(column.angular, moment) + dot(column.linear, force);
}

SpatialSubtreeForces spatial_newton_euler_pass(const ir::Model& model, const ir::CoordinateLayout& layout,
                                               const std::vector<SpatialBodyKinematics>& kin,
                                               const std::vector<std::vector<int>>& children,
                                               const std::vector<GiNaC::symbol>& q,
                                               const std::vector<GiNaC::symbol>& v, const GiNaC::symbol& t,
                                               CodeList& code) {
  const int n = static_cast<int>(model.bodies.size());
  SpatialSubtreeForces out;
  out.inertial_force.resize(n);
  out.applied_force.resize(n);
  out.inertial_moment.resize(n);
  out.applied_moment.resize(n);
  out.spring.assign(layout.num_velocities, 0);
  // Point forces and torques gathered per body: the force and its moment
  // about the body's origin.
  std::vector<Vec3x> load_force(n, zero3()), load_moment(n, zero3());
  for (const ir::Load& load : model.loads) {
    const int b = load.body;
    const ex on = window_factor(load.window, t);
    switch (load.type) {
      case ir::LoadType::kForce: {
        const ir::Vec3 local = load.point >= 0 ? model.bodies[b].points[load.point].position3 : ir::Vec3{0, 0, 0};
        const Vec3x arm = mul(kin[b].rotation, constant(local));
        const Vec3x force = scale(on, Vec3x{to_ginac(load.force3[0], t), to_ginac(load.force3[1], t),
                                             to_ginac(load.force3[2], t)});
        load_force[b] = add(load_force[b], force);
        load_moment[b] = add(load_moment[b], cross(arm, force));
        break;
      }
      case ir::LoadType::kTorque:
        load_moment[b] = add(load_moment[b], scale(on, Vec3x{to_ginac(load.torque3[0], t), to_ginac(load.torque3[1], t),
                                                             to_ginac(load.torque3[2], t)}));
        break;
      case ir::LoadType::kSpringDamper: {
        const int iq = layout.first_position[b], iv = layout.first_velocity[b];
        out.spring[iv] = out.spring[iv] - on * (exact(load.stiffness) * (q[iq] - exact(load.rest)) +
                                                exact(load.damping) * v[iv]);
        break;
      }
    }
  }
  const Vec3x gravity = constant(model.gravity3);
  for (int i = n - 1; i >= 0; --i) {
    const ir::Body& body = model.bodies[i];
    const SpatialBodyKinematics& k = kin[i];
    const ex mass = exact(body.mass);
    // Inertial: in the body frame, where the centre of mass and the inertia
    // are constants. Centre-of-mass acceleration with v' = 0:
    // a_i + a(w)_i x com + w_i x (w_i x com), and Euler's equation
    // I a(w) + w x I w (not through temporaries: w x I w then cancels where
    // I has equal moments).
    const Vec3x com = constant(body.com3);
    const Vec3x com_accel =
        add(add(k.local_accel, cross(k.local_alpha, com)), cross(k.local_omega, cross(k.local_omega, com)));
    const Vec3x momentum_rate = define(code, scale(mass, com_accel));
    const Sym3x inertia = constant(body.inertia3);
    const Vec3x euler = add(mul(inertia, k.local_alpha), cross(k.local_omega, mul(inertia, k.local_omega)));
    Vec3x f_in = momentum_rate;
    Vec3x n_in = add(cross(com, momentum_rate), euler);
    // Applied: in the ground frame (gravity is a constant there).
    const Vec3x& c = k.com_offset;
    const Vec3x weight = scale(mass, gravity);
    Vec3x f_ap = add(weight, load_force[i]);
    Vec3x n_ap = add(cross(c, weight), load_moment[i]);
    for (int child : children[i]) {
      // A child's force and moment turned into this body's frame: E_c f_c.
      const Vec3x child_force = define(code, mul(kin[child].relative, out.inertial_force[child]));
      f_in = add(f_in, child_force);
      n_in = add(add(n_in, mul(kin[child].relative, out.inertial_moment[child])),
                 cross(kin[child].local_offset, child_force));
      const Vec3x& lever = kin[child].offset;
      f_ap = add(f_ap, out.applied_force[child]);
      n_ap = add(add(n_ap, out.applied_moment[child]), cross(lever, out.applied_force[child]));
    }
    out.inertial_force[i] = define(code, f_in);
    out.inertial_moment[i] = define(code, n_in);
    out.applied_force[i] = define(code, f_ap);
    out.applied_moment[i] = define(code, n_ap);
  }
  return out;
}

}  // namespace mbfe::gen
