#include "generator/symbolic/spatial_composite_rigid_body.h"

#include <string>

namespace mbfe::gen {

using GiNaC::ex;

namespace {

/// m (|r|^2 I - r r^T) with |r|^2 given: the inertia of a point mass m at r.
Sym3x point_inertia(const ex& mass, const Vec3x& r, const ex& r_squared) {
  return {mass * (r_squared - r.x * r.x), mass * (r_squared - r.y * r.y), mass * (r_squared - r.z * r.z),
          -mass * r.x * r.y, -mass * r.x * r.z, -mass * r.y * r.z};
}

}  // namespace

std::array<ex, 6> at_ground_origin(const SpatialColumn& column, const Vec3x& origin) {
  const Vec3x linear = add(column.linear, cross(origin, column.angular));
  return {column.angular.x, column.angular.y, column.angular.z, linear.x, linear.y, linear.z};
}

SpatialCompositeBodies spatial_composite_bodies(const ir::Model& model, const std::vector<SpatialBodyKinematics>& kin,
                                                const std::vector<std::vector<int>>& children, CodeList& code) {
  const int n = static_cast<int>(model.bodies.size());
  SpatialCompositeBodies out;
  out.mass.resize(n);
  out.first_moment.resize(n);
  out.inertia.resize(n);
  for (int i = n - 1; i >= 0; --i) {
    const ir::Body& body = model.bodies[i];
    const ex mass = exact(body.mass);
    // In the body's own frame the body's inertia about o_i is a constant:
    // I + m (|com|^2 1 - com com^T).
    const Vec3x com = constant(body.com3);
    Sym3x inertia = add(constant(body.inertia3), point_inertia(mass, com, dot(com, com)));
    ex total = mass;
    Vec3x h = scale(mass, com);
    for (int child : children[i]) {
      // A subtree (mass C, first moment h_c and inertia J_c about o_c in the
      // child's frame) turned into this frame by the child's joint rotation E
      // and moved to o_i, with d = o_c - o_i in this frame:
      //   h = E h_c,   J = E J_c E^T + (2 h . d + C |d|^2) 1 - (h d^T + d h^T + C d d^T).
      const Vec3x& d = kin[child].local_offset;
      const ex& cm = out.mass[child];
      const Vec3x hc = define(code, mul(kin[child].relative, out.first_moment[child]));
      const Sym3x jc = rotate(kin[child].relative, out.inertia[child]);
      const ex trace_part = 2 * dot(hc, d) + cm * kin[child].offset_squared;
      const Sym3x shifted{jc.xx + trace_part - 2 * hc.x * d.x - cm * d.x * d.x,
                          jc.yy + trace_part - 2 * hc.y * d.y - cm * d.y * d.y,
                          jc.zz + trace_part - 2 * hc.z * d.z - cm * d.z * d.z,
                          jc.xy - hc.x * d.y - d.x * hc.y - cm * d.x * d.y,
                          jc.xz - hc.x * d.z - d.x * hc.z - cm * d.x * d.z,
                          jc.yz - hc.y * d.z - d.y * hc.z - cm * d.y * d.z};
      inertia = add(inertia, shifted);
      total = total + cm;
      h = add(h, add(hc, scale(cm, d)));
    }
    out.mass[i] = total;  // a constant
    out.first_moment[i] = define(code, h);
    out.inertia[i] = define(code, inertia);
  }
  return out;
}

std::vector<int> velocity_parents(const ir::Model& model, const ir::CoordinateLayout& layout) {
  std::vector<int> parent(layout.num_velocities, -1);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const int first = layout.first_velocity[b];
    const int count = ir::velocity_count(model.bodies[b].joint.type);
    const int p = model.bodies[b].parent;
    parent[first] = p < 0 ? -1 : layout.first_velocity[p] + ir::velocity_count(model.bodies[p].joint.type) - 1;
    for (int c = 1; c < count; ++c) parent[first + c] = first + c - 1;
  }
  return parent;
}

void spatial_mass_matrix_outputs(const ir::Model& model, const ir::CoordinateLayout& layout,
                                 const std::vector<SpatialBodyKinematics>& kin,
                                 const SpatialCompositeBodies& composite, CodeList& code, Kernel& mass_matrix) {
  // Spatial vectors at the ground origin, (angular, linear). A unit rate of
  // coordinate k moves its body's subtree with angular velocity w and its
  // origin o_k with velocity l (the column). The subtree's momentum is then,
  // in the body frame (where the composite body of
  // spatial_composite_bodies() is) and turned to the ground by R_k,
  //   p = C l + w x h,   L(o_k) = J w + h x l,   L(0) = R_k L(o_k) + o_k x R_k p,
  // U_k = (L(0), R_k p); S_j = (w_j, l_j + o_j x w_j) in the ground frame;
  // and M_jk = S_j . U_k for every coordinate j on the path from k to the
  // ground (in the tree of velocity coordinates, velocity_parents()). S and U
  // are O(N) straight-line code; the pairs are summed by a loop in the
  // emitted code.
  constexpr int kSpatial = 6;
  AncestorPairAssembly assembly;
  assembly.target = "M";
  assembly.size_name = "kNumVelocities";
  assembly.left = "motion_subspace";
  assembly.left_doc = "S_j: velocity coordinate j's unit motion, (angular, linear) at the ground origin";
  assembly.right = "composite_momentum";
  assembly.right_doc = "U_k: momentum of k's subtree (about the origin, then linear) for a unit rate of k";
  assembly.width = kSpatial;
  assembly.parent = velocity_parents(model, layout);
  std::vector<std::array<ex, kSpatial>> motion_of(layout.num_velocities);
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const SpatialBodyKinematics& k = kin[b];
    const ex& mass = composite.mass[b];
    const Vec3x& h = composite.first_moment[b];
    const Sym3x& inertia = composite.inertia[b];
    for (std::size_t c = 0; c < k.columns.size(); ++c) {
      const int j = layout.first_velocity[b] + static_cast<int>(c);
      const SpatialColumn& column = k.columns[c];
      const SpatialColumn& local = k.local_columns[c];
      const Vec3x linear_momentum =
          define(code, mul(k.rotation, define(code, add(scale(mass, local.linear), cross(local.angular, h)))));
      const Vec3x angular_momentum =
          add(mul(k.rotation, define(code, add(mul(inertia, local.angular), cross(h, local.linear)))),
              cross(k.origin, linear_momentum));
      std::array<ex, kSpatial> momentum{angular_momentum.x, angular_momentum.y, angular_momentum.z,
                                        linear_momentum.x,  linear_momentum.y,  linear_momentum.z};
      motion_of[j] = at_ground_origin(column, k.origin);
      // U_k[c] only ever multiplies S_j[c] of k and its ancestors; where all of
      // those are zero it cannot count, and 0 saves computing it.
      for (int e = 0; e < kSpatial; ++e) {
        bool counts = false;
        for (int a = j; a >= 0 && !counts; a = assembly.parent[a]) counts = !motion_of[a][e].is_zero();
        if (!counts) momentum[e] = 0;
      }
      auto output = [&](const std::string& array, int e, const ex& value) {
        const ex v = is_atomic(value) || is_atomic(-value) ? value : code.define(value);
        mass_matrix.outputs.push_back({array + "[" + std::to_string(j) + "][" + std::to_string(e) + "]", v});
      };
      for (int e = 0; e < kSpatial; ++e) output(assembly.left, e, motion_of[j][e]);
      for (int e = 0; e < kSpatial; ++e) output(assembly.right, e, momentum[e]);
    }
  }
  mass_matrix.assembly = assembly;
}

}  // namespace mbfe::gen
