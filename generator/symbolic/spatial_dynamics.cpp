// A spatial model, derived: the three passes (spatial_kinematics,
// spatial_newton_euler, spatial_composite_rigid_body) in order, then the
// kernels.
#include "generator/symbolic/spatial_dynamics.h"

#include <string>

#include "generator/symbolic/rigid_kinematics.h"
#include "generator/symbolic/spatial_composite_rigid_body.h"
#include "generator/symbolic/spatial_newton_euler.h"

namespace mbfe::gen {

using GiNaC::ex;
using ir::JointType;

namespace {

std::string index(const std::string& array, int i) { return array + "[" + std::to_string(i) + "]"; }

/// q' = G(q) v, one output per position coordinate.
void position_derivative_outputs(const ir::Model& model, SpatialDerivation& d, Kernel& kernel) {
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const JointType type = model.bodies[b].joint.type;
    const int iq = d.layout.first_position[b], iv = d.layout.first_velocity[b];
    int quaternion = iq, angular = iv;
    if (type == JointType::kRevolute || type == JointType::kPrismatic) {
      kernel.outputs.push_back({index("qdot", iq), d.v[iv]});
      continue;
    }
    if (type == JointType::kFree) {
      for (int c = 0; c < 3; ++c) kernel.outputs.push_back({index("qdot", iq + c), d.v[iv + c]});
      quaternion += 3;
      angular += 3;
    }
    // (w, x, y, z)' = 1/2 (w, x, y, z) (0, wx, wy, wz), Hamilton's product:
    // the rotation R(t) with R' = R [w]x, w in the body frame.
    const ex w = d.q[quaternion], x = d.q[quaternion + 1], y = d.q[quaternion + 2], z = d.q[quaternion + 3];
    const ex wx = d.v[angular], wy = d.v[angular + 1], wz = d.v[angular + 2];
    const ex half = GiNaC::numeric(1, 2);
    const ex rates[4] = {-half * (x * wx + y * wy + z * wz), half * (w * wx + y * wz - z * wy),
                         half * (w * wy + z * wx - x * wz), half * (w * wz + x * wy - y * wx)};
    for (int c = 0; c < 4; ++c) kernel.outputs.push_back({index("qdot", quaternion + c), d.code.define(rates[c])});
  }
}

}  // namespace

void derive_spatial_dynamics(const ir::Model& model, SpatialDerivation& d) {
  CodeList& code = d.code;
  d.layout = ir::coordinate_layout(model);
  for (int i = 0; i < d.layout.num_positions; ++i) d.q.emplace_back("q" + std::to_string(i));
  for (int i = 0; i < d.layout.num_velocities; ++i) d.v.emplace_back("v" + std::to_string(i));

  // Forward pass, backward Newton-Euler pass and composite bodies, in this
  // order: the order intermediates are defined in is the order of the
  // emitted temporaries.
  d.kinematics = spatial_forward_kinematics(model, d.layout, d.q, d.v, code);
  const std::vector<SpatialBodyKinematics>& kin = d.kinematics;
  const std::vector<std::vector<int>> children = children_of(model);
  const SpatialSubtreeForces forces =
      spatial_newton_euler_pass(model, d.layout, kin, children, d.q, d.v, d.t, code);
  const SpatialCompositeBodies composite = spatial_composite_bodies(model, kin, children, code);

  d.mass_matrix = {"mass_matrix", "const double* q, double* M",
                   "Mass matrix M(q), row-major nv x nv, symmetric.", {}, {}};
  d.inertial_forces = {"inertial_forces", "const double* q, const double* v, double* F",
                       "Velocity terms F(q, v), nv entries.", {}, {}};
  d.generalized_forces = {"generalized_forces", "const double* q, const double* v, double t, double* Q",
                          "Generalized forces Q(q, v, t), nv entries: gravity, loads, spring-dampers.", {}, {}};
  spatial_mass_matrix_outputs(model, d.layout, kin, composite, code, d.mass_matrix);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    for (std::size_t c = 0; c < kin[b].columns.size(); ++c) {
      const int j = d.layout.first_velocity[b] + static_cast<int>(c);
      const SpatialColumn& column = kin[b].columns[c];
      const ex f = project(kin[b].local_columns[c], forces.inertial_force[b], forces.inertial_moment[b]);
      const ex q = project(column, forces.applied_force[b], forces.applied_moment[b]) + forces.spring[j];
      d.inertial_forces.outputs.push_back({index("F", j), code.define(f)});
      d.generalized_forces.outputs.push_back({index("Q", j), code.define(q)});
    }
  }
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    for (std::size_t p = 0; p < model.bodies[b].points.size(); ++p) {
      const Vec3x xyz = define(code, add(kin[b].origin, mul(kin[b].rotation, constant(model.bodies[b].points[p].position3))));
      Kernel k{"point_position_" + std::to_string(b) + "_" + std::to_string(p), "const double* q, double* xyz",
               "Ground-frame position of point '" + model.bodies[b].points[p].name + "' of body '" +
                   model.bodies[b].name + "'.",
               {}, {{"xyz[0]", xyz.x}, {"xyz[1]", xyz.y}, {"xyz[2]", xyz.z}}};
      d.points.push_back({static_cast<int>(b), static_cast<int>(p), std::move(k)});
    }
  }
  d.dynamics = {"dynamics", "const double* q, const double* v, double t, double* M, double* F, double* Q",
                "M, F and Q at once, sharing the kinematics.", {}, {}};
  for (const Kernel* k : {&d.mass_matrix, &d.inertial_forces, &d.generalized_forces})
    d.dynamics.outputs.insert(d.dynamics.outputs.end(), k->outputs.begin(), k->outputs.end());
  d.dynamics.assembly = d.mass_matrix.assembly;
  d.position_derivative = {"position_derivative", "const double* q, const double* v, double* qdot",
                           "Position rates q' = G(q) v, nq entries (a quaternion read as unit).", {}, {}};
  position_derivative_outputs(model, d, d.position_derivative);
  for (Kernel* k : {&d.mass_matrix, &d.inertial_forces, &d.generalized_forces, &d.dynamics, &d.position_derivative})
    k->statements = code.closure(k->outputs);
  for (auto& pk : d.points) pk.kernel.statements = code.closure(pk.kernel.outputs);
}

}  // namespace mbfe::gen
