// The rigid part of a model, derived: the three passes (rigid_kinematics,
// newton_euler, composite_rigid_body) in order, then the kernels.
#include "generator/symbolic/rigid_dynamics.h"

#include <string>

#include "generator/symbolic/composite_rigid_body.h"
#include "generator/symbolic/newton_euler.h"
#include "generator/symbolic/rigid_kinematics.h"

namespace mbfe::gen {

using GiNaC::ex;
using ir::JointType;

Vec2x body_point(RigidDerivation& d, const ir::Model& /*model*/, int b, const ir::Vec2& local) {
  return define(d.code, add(d.origin[b], rotate(d.cos_angle[b], d.sin_angle[b], constant(local))));
}

void derive_rigid_dynamics(const ir::Model& model, RigidDerivation& d) {
  const int n = static_cast<int>(model.bodies.size());
  CodeList& code = d.code;
  for (int i = 0; i < n; ++i) {
    d.q.emplace_back("q" + std::to_string(i));
    d.qd.emplace_back("qd" + std::to_string(i));
  }

  // Forward pass (eqs (2)-(4)), the backward Newton-Euler pass (eq (5)) and
  // the composite bodies, in this order: the order intermediates are defined
  // in is the order of the emitted temporaries.
  d.kinematics = forward_kinematics(model, d.q, d.qd, code);
  const std::vector<BodyKinematics>& kin = d.kinematics;
  for (int i = 0; i < n; ++i) {
    d.origin.push_back(kin[i].origin);
    d.cos_angle.push_back(kin[i].cos_angle);
    d.sin_angle.push_back(kin[i].sin_angle);
  }
  const std::vector<std::vector<int>> children = children_of(model);
  const SubtreeForces forces = newton_euler_pass(model, kin, children, d.q, d.qd, d.t, code);
  const CompositeBodies composite = composite_bodies(model, kin, children, code);

  // The kernels.
  d.mass_matrix = {"mass_matrix", "const double* q, double* M",
                   "Mass matrix M(q), row-major nq x nq, symmetric.", {}, {}};
  d.inertial_forces = {"inertial_forces", "const double* q, const double* qd, double* F",
                       "Velocity-dependent inertial terms F(q, q').", {}, {}};
  d.generalized_forces = {"generalized_forces", "const double* q, const double* qd, double t, double* Q",
                          "Generalized forces Q(q, q', t): gravity, loads, spring-dampers.", {}, {}};

  mass_matrix_outputs(model, kin, composite, code, d.mass_matrix);
  for (int i = 0; i < n; ++i) {
    const bool rev = model.bodies[i].joint.type == JointType::kRevolute;
    const ex f = rev ? forces.inertial_moment[i] : dot(kin[i].axis, forces.inertial_force[i]);
    const ex q = (rev ? forces.applied_moment[i] : dot(kin[i].axis, forces.applied_force[i])) + forces.spring[i];
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