// Closed-form equations of motion of a planar tree of rigid bodies,
//   M(q) q'' + F(q, q') = Q(q, q', t)          (eq (6) of the paper)
// as straight-line kernels.
//
// Kinematics are built recursively from the ground outwards (eqs (2)-(4)):
// absolute angle, joint origin, velocities and the velocity-product
// accelerations of every body, each a named intermediate. F and Q come from
// the Newton-Euler equations (5) with the successors' joint forces eliminated
// by a backward pass (the recursive Newton-Euler algorithm with q'' = 0), so
// they cost O(N). M comes from the composite-rigid-body algorithm: the mass,
// first and second moments of each subtree (also a backward pass) give each
// joint's motion subspace and its subtree's composite momentum, O(N)
// straight-line code; the kernels then sum one dot product per (ancestor,
// descendant) pair in a loop (Kernel::assembly), so the emitted code stays
// O(N) although a chain's M has N(N+1)/2 entries. Nothing is ever inverted
// symbolically: the runtime factors M numerically.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "ir/model.h"
#include "generator/symbolic/code_list.h"
#include "generator/symbolic/planar_vectors.h"
#include "generator/symbolic/rigid_kinematics.h"

namespace mbfe::gen {

/// Symbols and kernels of a model's rigid part.
struct RigidDerivation {
  std::vector<GiNaC::symbol> q, qd;  // one per body, model order
  GiNaC::symbol t{"t"};
  CodeList code;
  /// Per body: frame origin, absolute angle's cosine and sine (ground frame).
  std::vector<Vec2x> origin;
  std::vector<GiNaC::ex> cos_angle, sin_angle;
  /// Everything the forward pass knows (for the loop kernels).
  std::vector<BodyKinematics> kinematics;
  Kernel mass_matrix, inertial_forces, generalized_forces;
  Kernel dynamics;  // all three at once, kinematics shared
  /// One kernel per named point: body b, point p -> ground-frame position.
  struct PointKernel {
    int body, point;
    Kernel kernel;
  };
  std::vector<PointKernel> points;
};

/// Derives the kernels of `model` (bodies and rigid loads).
void derive_rigid_dynamics(const ir::Model& model, RigidDerivation& out);

/// Ground-frame position of a body-frame point of body `b` (an expression in q).
Vec2x body_point(RigidDerivation& d, const ir::Model& model, int b, const ir::Vec2& local);

}  // namespace mbfe::gen
