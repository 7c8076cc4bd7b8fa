#include "generator/symbolic/spatial_kinematics.h"

namespace mbfe::gen {

using GiNaC::ex;
using ir::JointType;

namespace {

bool is_identity(const ir::Vec3& rpy) { return rpy[0] == 0.0 && rpy[1] == 0.0 && rpy[2] == 0.0; }

Vec3x unit_vector(int c) { return {c == 0 ? 1 : 0, c == 1 ? 1 : 0, c == 2 ? 1 : 0}; }

}  // namespace

std::vector<SpatialBodyKinematics> spatial_forward_kinematics(const ir::Model& model,
                                                              const ir::CoordinateLayout& layout,
                                                              const std::vector<GiNaC::symbol>& q,
                                                              const std::vector<GiNaC::symbol>& v, CodeList& code) {
  const int n = static_cast<int>(model.bodies.size());
  std::vector<SpatialBodyKinematics> kin(n);
  for (int i = 0; i < n; ++i) {
    const ir::Body& body = model.bodies[i];
    const ir::Joint& joint = body.joint;
    const int p = body.parent;
    const Mat3x parent_rotation = p < 0 ? identity3() : kin[p].rotation;
    const Vec3x parent_origin = p < 0 ? zero3() : kin[p].origin;
    const Vec3x parent_omega = p < 0 ? zero3() : kin[p].omega;
    const Vec3x parent_velocity = p < 0 ? zero3() : kin[p].velocity;
    const Vec3x parent_alpha = p < 0 ? zero3() : kin[p].alpha;
    const Vec3x parent_accel = p < 0 ? zero3() : kin[p].bias_accel;
    const Vec3x parent_local_omega = p < 0 ? zero3() : kin[p].local_omega;
    const Vec3x parent_local_alpha = p < 0 ? zero3() : kin[p].local_alpha;
    const Vec3x parent_local_accel = p < 0 ? zero3() : kin[p].local_accel;
    const Mat3x fixed = rotation_rpy(joint.rotation);  // C, exact constants
    const int iq = layout.first_position[i];
    const int iv = layout.first_velocity[i];
    SpatialBodyKinematics& k = kin[i];

    // The joint frame: R_J = R_p C; a joint without `rotation` has C = I.
    k.joint_rotation = is_identity(joint.rotation)
                           ? parent_rotation
                           : define(code, mul(parent_rotation, rotation_rpy(joint.rotation)));
    Vec3x offset = define(code, mul(parent_rotation, constant(joint.at3)));  // R_p at
    // A rotation keeps lengths: |R_p at|^2 = |at|^2.
    k.offset_squared = exact(joint.at3[0]) * exact(joint.at3[0]) + exact(joint.at3[1]) * exact(joint.at3[1]) +
                       exact(joint.at3[2]) * exact(joint.at3[2]);
    // The joint's own velocity terms: angular (ground frame) and the velocity
    // of o_i relative to the joint frame moving with the parent; and the same
    // in the body frame (angular) and the parent frame (linear).
    Vec3x joint_angular = zero3(), joint_linear = zero3();
    Vec3x local_angular = zero3(), parent_linear = zero3();
    k.local_offset = constant(joint.at3);
    switch (joint.type) {
      case JointType::kRevolute: {
        const ex c = code.define(GiNaC::cos(q[iq]));  // each sin/cos once
        const ex s = code.define(GiNaC::sin(q[iq]));
        const Mat3x turn = axis_rotation(joint.axis3, c, s);
        k.rotation = define(code, mul(k.joint_rotation, turn));
        k.relative = define(code, mul(fixed, turn));
        k.axis = define(code, mul(k.joint_rotation, constant(joint.axis3)));
        k.columns.push_back({k.axis, zero3()});
        // The axis is fixed in the joint frame and in the body frame alike.
        k.local_columns.push_back({constant(joint.axis3), zero3()});
        joint_angular = scale(v[iv], k.axis);
        local_angular = scale(v[iv], constant(joint.axis3));
        break;
      }
      case JointType::kPrismatic: {
        k.rotation = k.joint_rotation;
        k.relative = fixed;
        k.axis = define(code, mul(parent_rotation, constant(joint.axis3)));
        offset = define(code, add(offset, scale(q[iq], k.axis)));
        k.offset_squared = code.define(dot(offset, offset));
        k.columns.push_back({zero3(), k.axis});
        k.local_columns.push_back({zero3(), mul_transposed(fixed, constant(joint.axis3))});  // C^T axis, constants
        k.local_offset = add(k.local_offset, scale(q[iq], constant(joint.axis3)));
        joint_linear = scale(v[iv], k.axis);
        parent_linear = scale(v[iv], constant(joint.axis3));
        break;
      }
      case JointType::kSpherical:
      case JointType::kFree: {
        const bool free = joint.type == JointType::kFree;
        const int quaternion = iq + (free ? 3 : 0);
        const int angular = iv + (free ? 3 : 0);
        const Mat3x relative =
            define(code, quaternion_rotation(q[quaternion], q[quaternion + 1], q[quaternion + 2], q[quaternion + 3]));
        if (free) {
          // Translation by (x, y, z) of the joint frame, then the rotation.
          const Vec3x translation{q[iq], q[iq + 1], q[iq + 2]};
          offset = define(code, add(offset, mul(k.joint_rotation, translation)));
          k.offset_squared = code.define(dot(offset, offset));
          for (int c = 0; c < 3; ++c) k.columns.push_back({zero3(), k.joint_rotation.column(c)});
          // In the body frame a joint-frame axis e_c is row c of the quaternion's rotation.
          for (int c = 0; c < 3; ++c)
            k.local_columns.push_back({zero3(), {relative.m[c][0], relative.m[c][1], relative.m[c][2]}});
          const Vec3x rates{v[iv], v[iv + 1], v[iv + 2]};
          joint_linear = define(code, mul(k.joint_rotation, rates));
          parent_linear = define(code, mul(fixed, rates));
          k.local_offset = define(code, add(k.local_offset, mul(fixed, translation)));
        }
        k.rotation = define(code, mul(k.joint_rotation, relative));
        k.relative = define(code, mul(fixed, relative));
        k.axis = zero3();
        for (int c = 0; c < 3; ++c) k.columns.push_back({k.rotation.column(c), zero3()});
        for (int c = 0; c < 3; ++c) k.local_columns.push_back({unit_vector(c), zero3()});
        local_angular = Vec3x{v[angular], v[angular + 1], v[angular + 2]};
        joint_angular = define(code, mul(k.rotation, local_angular));
        break;
      }
    }
    k.offset = offset;
    k.origin = define(code, add(parent_origin, offset));
    k.com_offset = define(code, mul(k.rotation, constant(body.com3)));

    // Velocities, and accelerations with v' = 0. The joint's terms are fixed
    // in the parent (an axis) or the body (a quaternion joint's angular
    // velocity), so they turn with the parent's angular velocity:
    //   w_i = w_p + s,   a(w)_i = a(w)_p + w_p x s,
    //   v_i = v_p + w_p x d + l,   a_i = a_p + a(w)_p x d + w_p x (w_p x d) + 2 w_p x l,
    // with d = o_i - o_p, s the joint's angular and l its linear velocity term.
    k.omega = define(code, add(parent_omega, joint_angular));
    k.velocity = define(code, add(add(parent_velocity, cross(parent_omega, offset)), joint_linear));
    k.alpha = define(code, add(parent_alpha, cross(parent_omega, joint_angular)));
    Vec3x accel = add(parent_accel, cross(parent_alpha, offset));
    accel = add(accel, cross(parent_omega, cross(parent_omega, offset)));
    accel = add(accel, scale(2, cross(parent_omega, joint_linear)));
    k.bias_accel = define(code, accel);

    // The same in the body frame: the parent's terms turned by E^T, the
    // offset d and the joint's terms constant in their own frames:
    //   w = E^T w_p + s,   a(w) = E^T a(w)_p + w x s,
    //   a = E^T (a_p + a(w)_p x d + w_p x (w_p x d) + 2 w_p x l),
    // d and l in the parent frame, s in the body frame.
    const Vec3x& d = k.local_offset;
    k.local_omega = define(code, add(mul_transposed(k.relative, parent_local_omega), local_angular));
    k.local_alpha =
        define(code, add(mul_transposed(k.relative, parent_local_alpha), cross(k.local_omega, local_angular)));
    Vec3x local = add(parent_local_accel, cross(parent_local_alpha, d));
    local = add(local, cross(parent_local_omega, cross(parent_local_omega, d)));
    local = add(local, scale(2, cross(parent_local_omega, parent_linear)));
    k.local_accel = define(code, mul_transposed(k.relative, define(code, local)));
  }
  return kin;
}

}  // namespace mbfe::gen
