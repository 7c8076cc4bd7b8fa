#include "generator/symbolic/rigid_dynamics.h"

#include <array>
#include <string>

namespace mbfe::gen {

namespace {

using GiNaC::ex;
using ir::JointType;

// 2D helpers; `cross` is the z component of the 3D cross product, `perp` is
// e_z x v (v rotated by +90 degrees).
ex dot(const Vec2x& a, const Vec2x& b) { return a.x * b.x + a.y * b.y; }
ex cross(const Vec2x& a, const Vec2x& b) { return a.x * b.y - a.y * b.x; }
Vec2x perp(const Vec2x& v) { return {-v.y, v.x}; }
Vec2x add(const Vec2x& a, const Vec2x& b) { return {a.x + b.x, a.y + b.y}; }
Vec2x sub(const Vec2x& a, const Vec2x& b) { return {a.x - b.x, a.y - b.y}; }
Vec2x scale(const ex& s, const Vec2x& v) { return {s * v.x, s * v.y}; }
Vec2x constant(const ir::Vec2& v) { return {exact(v[0]), exact(v[1])}; }
Vec2x rotate(const ex& c, const ex& s, const Vec2x& v) { return {c * v.x - s * v.y, s * v.x + c * v.y}; }
Vec2x define(CodeList& code, const Vec2x& v) { return {code.define(v.x), code.define(v.y)}; }

// What the forward pass knows of one body.
struct BodyKinematics {
  Vec2x origin;          // joint origin o_i, ground frame
  Vec2x offset;          // o_i - o_parent, ground frame
  ex offset_squared;     // |o_i - o_parent|^2 (a constant for a revolute joint)
  ex cos_angle, sin_angle;
  Vec2x axis;            // prismatic: joint axis u_i in the ground frame
  Vec2x com_offset;      // p_i - o_i, ground frame
  ex omega;              // angular velocity
  Vec2x bias_accel;      // origin acceleration with q'' = 0
};

}  // namespace

Vec2x body_point(RigidDerivation& d, const ir::Model& model, int b, const ir::Vec2& local) {
  (void)model;
  return define(d.code, add(d.origin[b], rotate(d.cos_angle[b], d.sin_angle[b], constant(local))));
}

void derive_rigid_dynamics(const ir::Model& model, RigidDerivation& d) {
  const int n = static_cast<int>(model.bodies.size());
  CodeList& code = d.code;
  for (int i = 0; i < n; ++i) {
    d.q.emplace_back("q" + std::to_string(i));
    d.qd.emplace_back("qd" + std::to_string(i));
  }

  // ---- Forward pass: positions, angles, velocities, bias accelerations. ----
  std::vector<BodyKinematics> kin(n);
  std::vector<ex> angle(n);
  for (int i = 0; i < n; ++i) {
    const ir::Body& body = model.bodies[i];
    const int p = body.parent;
    const Vec2x parent_origin = p < 0 ? Vec2x{0, 0} : kin[p].origin;
    const ex parent_angle = p < 0 ? ex(0) : angle[p];
    const ex pc = p < 0 ? ex(1) : kin[p].cos_angle;
    const ex ps = p < 0 ? ex(0) : kin[p].sin_angle;
    const ex parent_omega = p < 0 ? ex(0) : kin[p].omega;
    const Vec2x parent_accel = p < 0 ? Vec2x{0, 0} : kin[p].bias_accel;
    BodyKinematics& k = kin[i];

    Vec2x offset = rotate(pc, ps, constant(body.joint.at));  // o_i - o_p
    if (body.joint.type == JointType::kRevolute) {
      angle[i] = code.define(parent_angle + d.q[i]);
      k.cos_angle = code.define(GiNaC::cos(angle[i]));  // each sin/cos once
      k.sin_angle = code.define(GiNaC::sin(angle[i]));
      k.omega = code.define(parent_omega + d.qd[i]);
      k.axis = {0, 0};
    } else {
      angle[i] = parent_angle;
      k.cos_angle = pc;
      k.sin_angle = ps;
      k.omega = parent_omega;
      k.axis = define(code, rotate(pc, ps, constant(body.joint.axis)));
      offset = define(code, add(offset, scale(d.q[i], k.axis)));
    }
    k.offset = offset;
    // A rotation keeps lengths: |R at|^2 = |at|^2 is a constant for a revolute joint.
    k.offset_squared = body.joint.type == JointType::kRevolute
                           ? ex(exact(body.joint.at[0]) * exact(body.joint.at[0]) +
                                exact(body.joint.at[1]) * exact(body.joint.at[1]))
                           : code.define(dot(offset, offset));
    k.origin = define(code, add(parent_origin, offset));
    k.com_offset = define(code, rotate(k.cos_angle, k.sin_angle, constant(body.com)));

    // a_i = a_p - w_p^2 (o_i - o_p) [+ 2 w_p qd_i e_z x u_i for a slider]; the
    // parent's angular acceleration is zero when q'' = 0.
    Vec2x accel = sub(parent_accel, scale(parent_omega * parent_omega, offset));
    if (body.joint.type == JointType::kPrismatic)
      accel = add(accel, scale(2 * parent_omega * d.qd[i], perp(k.axis)));
    k.bias_accel = define(code, accel);
  }
  for (int i = 0; i < n; ++i) {
    d.origin.push_back(kin[i].origin);
    d.cos_angle.push_back(kin[i].cos_angle);
    d.sin_angle.push_back(kin[i].sin_angle);
  }

  std::vector<std::vector<int>> children(n);
  for (int i = 0; i < n; ++i)
    if (model.bodies[i].parent >= 0) children[model.bodies[i].parent].push_back(i);

  // ---- Backward pass (eq (5)): bias forces F and applied forces Q. ----
  // f: net force the subtree needs (inertial) or receives (applied);
  // m: its moment about the body's joint origin.
  std::vector<Vec2x> inertial_force(n), applied_force(n);
  std::vector<ex> inertial_moment(n), applied_moment(n);
  std::vector<ex> torque_load(n, 0);
  std::vector<Vec2x> point_force(n, Vec2x{0, 0});
  std::vector<ex> point_moment(n, 0);
  std::vector<ex> spring(n, 0);
  for (const ir::Load& load : model.loads) {
    const int b = load.body;
    switch (load.type) {
      case ir::LoadType::kForce: {
        const ir::Vec2 local = load.point >= 0 ? model.bodies[b].points[load.point].position
                                                  : ir::Vec2{0.0, 0.0};
        const Vec2x arm = rotate(kin[b].cos_angle, kin[b].sin_angle, constant(local));
        const Vec2x force = constant(load.force);
        point_force[b] = add(point_force[b], force);
        point_moment[b] = point_moment[b] + cross(arm, force);
        break;
      }
      case ir::LoadType::kTorque:
        torque_load[b] = torque_load[b] + exact(load.torque);
        break;
      case ir::LoadType::kSpringDamper:
        spring[b] = spring[b] - exact(load.stiffness) * (d.q[b] - exact(load.rest)) -
                    exact(load.damping) * d.qd[b];
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

  // ---- Composite bodies for M: mass, first moment h_k about o_k, and the
  // second moment J_k = sum (I_i + m_i |p_i - o_k|^2) about o_k. (The
  // momenta U_k below are taken at the ground origin: an entry then loses
  // ~eps |o| |h| to cancellation, 1e-13 of J for a body 1 km away.) ----
  std::vector<ex> composite_mass(n);
  std::vector<Vec2x> first_moment(n);
  std::vector<ex> second_moment(n);  // about o_k
  for (int i = n - 1; i >= 0; --i) {
    const ir::Body& body = model.bodies[i];
    const ex mass = exact(body.mass);
    ex total_mass = mass;
    Vec2x h = scale(mass, kin[i].com_offset);
    // m |com|^2 is frame-independent: a constant.
    ex j = exact(body.inertia) + mass * (exact(body.com[0]) * exact(body.com[0]) +
                                         exact(body.com[1]) * exact(body.com[1]));
    for (int c : children[i]) {
      const Vec2x& lever = kin[c].offset;
      total_mass = total_mass + composite_mass[c];
      h = add(h, add(first_moment[c], scale(composite_mass[c], lever)));
      j = j + second_moment[c] + 2 * dot(lever, first_moment[c]) + composite_mass[c] * kin[c].offset_squared;
    }
    composite_mass[i] = total_mass;  // a constant
    first_moment[i] = define(code, h);
    second_moment[i] = code.define(j);
  }

  // ---- Kernels. ----
  d.mass_matrix = {"mass_matrix", "const double* q, double* M",
                   "Mass matrix M(q), row-major nq x nq, symmetric.", {}, {}};
  d.inertial_forces = {"inertial_forces", "const double* q, const double* qd, double* F",
                       "Velocity-dependent inertial terms F(q, q').", {}, {}};
  d.generalized_forces = {"generalized_forces", "const double* q, const double* qd, double t, double* Q",
                          "Generalized forces Q(q, q', t): gravity, loads, spring-dampers.", {}, {}};

  // M by the composite-rigid-body algorithm (CRBA). Planar spatial vectors
  // at the ground origin: (angular, linear x, linear y). The motion subspace of
  // joint j is S_j = (1, o_jy, -o_jx) (revolute: the velocity at the origin of
  // a unit rotation about o_j) or (0, u_jx, u_jy) (prismatic). The composite
  // momentum of subtree k moving with a unit rate of joint k, U_k = I_k^c S_k
  // (angular momentum about the origin, then linear momentum), is
  //   revolute:  (A_k, -h_ky, h_kx),                 A_k = J_k + o_k . h_k
  //   prismatic: ((C_k o_k + h_k) x u_k, C_k u_kx, C_k u_ky)
  // and M_jk = S_j . U_k for every j on the path from k to the ground. Written
  // out, M_jk is A_k - o_j . h_k (revolute j, k; J_k on the diagonal),
  // u_j . (e_z x h_k), (e_z x (h_k + C_k (o_k - o_j))) . u_k, or C_k u_j . u_k.
  // S and U are O(N) straight-line code; the pairs are summed by a loop in the
  // emitted code (Kernel::assembly), so the code stays O(N) while a chain's M
  // has N(N+1)/2 entries.
  constexpr int kSpatial = 3;
  AncestorPairAssembly assembly;
  assembly.target = "M";
  assembly.left = "motion_subspace";
  assembly.left_doc = "S_j: joint j's unit motion, planar spatial vector at the ground origin";
  assembly.right = "composite_momentum";
  assembly.right_doc = "U_k: momentum of subtree k (about the origin, then linear) for a unit rate of joint k";
  assembly.width = kSpatial;
  std::vector<std::array<ex, kSpatial>> motion_of(n);
  for (int k = 0; k < n; ++k) {
    const ir::Body& body = model.bodies[k];
    const Vec2x& o = kin[k].origin;
    const Vec2x& h = first_moment[k];
    std::array<ex, kSpatial>& motion = motion_of[k];
    std::array<ex, kSpatial> momentum;
    if (body.joint.type == JointType::kRevolute) {
      motion = {1, o.y, -o.x};
      momentum = {second_moment[k] + dot(o, h), -h.y, h.x};
    } else {
      const Vec2x& u = kin[k].axis;
      motion = {0, u.x, u.y};
      momentum = {cross(add(scale(composite_mass[k], o), h), u), composite_mass[k] * u.x,
                  composite_mass[k] * u.y};
    }
    // A component that is a named intermediate up to its sign is written as
    // is (a unary minus is free); anything else becomes one.
    auto output = [&](const std::string& array, int c, const ex& value) {
      const ex v = is_atomic(value) || is_atomic(-value) ? value : code.define(value);
      d.mass_matrix.outputs.push_back({array + "[" + std::to_string(k) + "][" + std::to_string(c) + "]", v});
    };
    // U_k[c] only ever multiplies S_j[c] of k and its ancestors; where all of
    // those are zero (a root joint at the ground origin: S = (1, 0, 0)) it
    // cannot count, and 0 saves computing it.
    for (int c = 0; c < kSpatial; ++c) {
      bool counts = false;
      for (int j = k; j >= 0 && !counts; j = model.bodies[j].parent) counts = !motion_of[j][c].is_zero();
      if (!counts) momentum[c] = 0;
    }
    for (int c = 0; c < kSpatial; ++c) output(assembly.left, c, motion[c]);
    for (int c = 0; c < kSpatial; ++c) output(assembly.right, c, momentum[c]);
    assembly.parent.push_back(body.parent);
  }
  d.mass_matrix.assembly = assembly;
  for (int i = 0; i < n; ++i) {
    const bool rev = model.bodies[i].joint.type == JointType::kRevolute;
    const ex f = rev ? inertial_moment[i] : dot(kin[i].axis, inertial_force[i]);
    const ex q = (rev ? applied_moment[i] : dot(kin[i].axis, applied_force[i])) + spring[i];
    d.inertial_forces.outputs.push_back({"F[" + std::to_string(i) + "]", code.define(f)});
    d.generalized_forces.outputs.push_back({"Q[" + std::to_string(i) + "]", code.define(q)});
  }
  for (int b = 0; b < n; ++b) {
    for (int p = 0; p < static_cast<int>(model.bodies[b].points.size()); ++p) {
      const Vec2x xy = body_point(d, model, b, model.bodies[b].points[p].position);
      Kernel k{"point_position_" + std::to_string(b) + "_" + std::to_string(p),
               "const double* q, double* xy",
               "Ground-frame position of point '" + model.bodies[b].points[p].name + "' of body '" +
                   model.bodies[b].name + "'.",
               {}, {{"xy[0]", xy.x}, {"xy[1]", xy.y}}};
      d.points.push_back({b, p, std::move(k)});
    }
  }
  d.dynamics = {"dynamics",
                "const double* q, const double* qd, double t, double* M, double* F, double* Q",
                "M, F and Q at once, sharing the kinematics.", {}, {}};
  for (const Kernel* k : {&d.mass_matrix, &d.inertial_forces, &d.generalized_forces})
    d.dynamics.outputs.insert(d.dynamics.outputs.end(), k->outputs.begin(), k->outputs.end());
  d.dynamics.assembly = d.mass_matrix.assembly;
  for (Kernel* k : {&d.mass_matrix, &d.inertial_forces, &d.generalized_forces, &d.dynamics})
    k->statements = code.closure(k->outputs);
  for (auto& pk : d.points) pk.kernel.statements = code.closure(pk.kernel.outputs);
}

}  // namespace mbfe::gen
