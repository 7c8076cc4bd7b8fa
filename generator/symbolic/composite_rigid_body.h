// The mass matrix by the composite-rigid-body algorithm (CRBA): the mass, first
// and second moments of every subtree (a backward pass), each joint's motion
// subspace S_j and its subtree's composite momentum U_k as straight-line code,
// and the loop over (ancestor, descendant) pairs that sums M_jk = S_j . U_k in
// the emitted code (AncestorPairAssembly), so the code stays O(N) although a
// chain's M has N(N+1)/2 entries.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "generator/symbolic/code_list.h"
#include "generator/symbolic/planar_vectors.h"
#include "generator/symbolic/rigid_kinematics.h"
#include "ir/model.h"

namespace mbfe::gen {

/// Per body: mass, first moment h_k and second moment J_k of its subtree about
/// its joint origin o_k.
struct CompositeBodies {
  std::vector<GiNaC::ex> mass;           // a constant
  std::vector<Vec2x> first_moment;       // h_k
  std::vector<GiNaC::ex> second_moment;  // J_k = sum (I_i + m_i |p_i - o_k|^2)
};

CompositeBodies composite_bodies(const ir::Model& model, const std::vector<BodyKinematics>& kin,
                                 const std::vector<std::vector<int>>& children, CodeList& code);

/// Fills the outputs (S_j, U_k) and the assembly loop of the mass-matrix kernel.
void mass_matrix_outputs(const ir::Model& model, const std::vector<BodyKinematics>& kin,
                         const CompositeBodies& composite, CodeList& code, Kernel& mass_matrix);

}  // namespace mbfe::gen
