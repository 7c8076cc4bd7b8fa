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
    const Vec3x& c = k.com_offset;
    // Centre-of-mass acceleration with v' = 0: a_i + a(w)_i x c + w_i x (w_i x c).
    const Vec3x com_accel = add(add(k.bias_accel, cross(k.alpha, c)), cross(k.omega, cross(k.omega, c)));
    const Vec3x momentum_rate = define(code, scale(mass, com_accel));
    // Euler's equation in the body frame, where the inertia is a constant:
    // I a(w)_b + w_b x I w_b with w_b = R^T w, a(w)_b = R^T a(w).
    const Sym3x inertia = constant(body.inertia3);
    Vec3x euler = zero3();
    if (!(inertia.xx.is_zero() && inertia.yy.is_zero() && inertia.zz.is_zero())) {
      const Vec3x omega_body = define(code, mul_transposed(k.rotation, k.omega));
      const Vec3x alpha_body = define(code, mul_transposed(k.rotation, k.alpha));
      // Not a temporary: w_b x I w_b then cancels where I has equal moments.
      const Vec3x spin = mul(inertia, omega_body);
      euler = define(code, mul(k.rotation, define(code, add(mul(inertia, alpha_body), cross(omega_body, spin)))));
    }
    Vec3x f_in = momentum_rate;
    Vec3x n_in = add(cross(c, momentum_rate), euler);
    const Vec3x weight = scale(mass, gravity);
    Vec3x f_ap = add(weight, load_force[i]);
    Vec3x n_ap = add(cross(c, weight), load_moment[i]);
    for (int child : children[i]) {
      const Vec3x& lever = kin[child].offset;
      f_in = add(f_in, out.inertial_force[child]);
      n_in = add(add(n_in, out.inertial_moment[child]), cross(lever, out.inertial_force[child]));
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
