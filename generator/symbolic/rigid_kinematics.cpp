#include "generator/symbolic/rigid_kinematics.h"

namespace mbfe::gen {

using GiNaC::ex;
using ir::JointType;

std::vector<BodyKinematics> forward_kinematics(const ir::Model& model, const std::vector<GiNaC::symbol>& q,
                                               const std::vector<GiNaC::symbol>& qd, CodeList& code) {
  const int n = static_cast<int>(model.bodies.size());
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
      angle[i] = code.define(parent_angle + q[i]);
      k.cos_angle = code.define(GiNaC::cos(angle[i]));  // each sin/cos once
      k.sin_angle = code.define(GiNaC::sin(angle[i]));
      k.omega = code.define(parent_omega + qd[i]);
      k.axis = {0, 0};
    } else {
      angle[i] = parent_angle;
      k.cos_angle = pc;
      k.sin_angle = ps;
      k.omega = parent_omega;
      k.axis = define(code, rotate(pc, ps, constant(body.joint.axis)));
      offset = define(code, add(offset, scale(q[i], k.axis)));
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
      accel = add(accel, scale(2 * parent_omega * qd[i], perp(k.axis)));
    k.bias_accel = define(code, accel);
  }
  return kin;
}

std::vector<std::vector<int>> children_of(const ir::Model& model) {
  const int n = static_cast<int>(model.bodies.size());
  std::vector<std::vector<int>> children(n);
  for (int i = 0; i < n; ++i)
    if (model.bodies[i].parent >= 0) children[model.bodies[i].parent].push_back(i);
  return children;
}

}  // namespace mbfe::gen
