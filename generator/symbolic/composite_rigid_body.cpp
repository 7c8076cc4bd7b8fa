#include "generator/symbolic/composite_rigid_body.h"

#include <array>
#include <string>

namespace mbfe::gen {

using GiNaC::ex;
using ir::JointType;

CompositeBodies composite_bodies(const ir::Model& model, const std::vector<BodyKinematics>& kin,
                                 const std::vector<std::vector<int>>& children, CodeList& code) {
  const int n = static_cast<int>(model.bodies.size());
  // ---- Composite bodies for M: mass, first moment h_k about o_k, and the
  // second moment J_k = sum (I_i + m_i |p_i - o_k|^2) about o_k. (The
  // momenta U_k below are taken at the ground origin: an entry then loses
  // ~eps |o| |h| to cancellation, 1e-13 of J for a body 1 km away.) ----
  CompositeBodies out;
  std::vector<ex>& composite_mass = out.mass;
  std::vector<Vec2x>& first_moment = out.first_moment;
  std::vector<ex>& second_moment = out.second_moment;  // about o_k
  composite_mass.resize(n);
  first_moment.resize(n);
  second_moment.resize(n);
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
  return out;
}

void mass_matrix_outputs(const ir::Model& model, const std::vector<BodyKinematics>& kin,
                         const CompositeBodies& composite, CodeList& code, Kernel& mass_matrix) {
  const int n = static_cast<int>(model.bodies.size());
  const std::vector<ex>& composite_mass = composite.mass;
  const std::vector<Vec2x>& first_moment = composite.first_moment;
  const std::vector<ex>& second_moment = composite.second_moment;
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
      mass_matrix.outputs.push_back({array + "[" + std::to_string(k) + "][" + std::to_string(c) + "]", v});
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
  mass_matrix.assembly = assembly;
}

}  // namespace mbfe::gen
