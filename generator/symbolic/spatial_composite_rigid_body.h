// The mass matrix of a spatial tree by the composite-rigid-body algorithm,
// the counterpart of composite_rigid_body.h: the mass, first moment and
// rotational inertia of every subtree about its joint origin in the body's
// own frame (a backward pass, each child's turned by its sparse joint
// rotation); for each velocity coordinate j its unit motion
// S_j and for each k the momentum U_k of k's subtree moving with a unit rate
// of k, both spatial vectors (angular, linear) at the ground origin; and the
// loop over (ancestor, descendant) pairs of velocity coordinates that sums
// M_jk = S_j . U_k in the emitted code (AncestorPairAssembly, width 6).
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "generator/symbolic/code_list.h"
#include "generator/symbolic/spatial_kinematics.h"
#include "generator/symbolic/spatial_vectors.h"
#include "ir/coordinate_layout.h"
#include "ir/model.h"

namespace mbfe::gen {

/// Per body: mass, first moment h_k and rotational inertia J_k of its
/// subtree about its joint origin o_k, in the body's own frame.
struct SpatialCompositeBodies {
  std::vector<GiNaC::ex> mass;    // a constant
  std::vector<Vec3x> first_moment;
  std::vector<Sym3x> inertia;
};

SpatialCompositeBodies spatial_composite_bodies(const ir::Model& model, const std::vector<SpatialBodyKinematics>& kin,
                                                const std::vector<std::vector<int>>& children, CodeList& code);

/// The parent of each velocity coordinate in the tree of coordinates: the
/// previous coordinate of the same joint, else the last one of the parent
/// body's joint, else -1 (Featherstone's expanded parent array).
std::vector<int> velocity_parents(const ir::Model& model, const ir::CoordinateLayout& layout);

/// Fills the outputs (S_j, U_k) and the assembly loop of the mass-matrix kernel.
void spatial_mass_matrix_outputs(const ir::Model& model, const ir::CoordinateLayout& layout,
                                 const std::vector<SpatialBodyKinematics>& kin,
                                 const SpatialCompositeBodies& composite, CodeList& code, Kernel& mass_matrix);

/// A column (motion of o_k) as a spatial vector at the ground origin:
/// (angular, linear + o_k x angular).
std::array<GiNaC::ex, 6> at_ground_origin(const SpatialColumn& column, const Vec3x& origin);

}  // namespace mbfe::gen
