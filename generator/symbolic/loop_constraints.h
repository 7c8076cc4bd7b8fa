// Closed kinematic loops (`constraints:`), planar and spatial: the constraint
// values Phi(q), the Jacobian J with Phi' = J v, and gamma = -(dJ/dt) v, in
// closed form from the kinematics the dynamics already derives (positions,
// rotations, velocities, the accelerations with v' = 0, each velocity
// coordinate's unit motion), not by differentiating long expressions.
//
// Every row is one of three kinds, with p_a, p_b the two points, R_a, R_b
// the two body frames and d = p_b - p_a (docs/generator.md, "Closed loops"):
//   point:       Phi = e_k . (p_a - p_b)              (e_k a ground axis)
//   slide:       Phi = (R_a n) . d                    (n perpendicular to the axis, in a's frame)
//   orientation: Phi = (R_a u) . (R_b e)              (u fixed in a, e fixed in b, u . e = 0)
// Each row's rate is linear in the two bodies' angular velocities and point
// velocities, Phi' = c_wa . w_a + c_pa . p_a' + c_wb . w_b + c_pb . p_b', so
// J's entry for velocity coordinate j, whose unit motion is the spatial
// vector S_j = (w_j, l_j) at the ground origin, is S_j . (c_w + p x c_p, c_p)
// summed over the ends that j moves; gamma is minus Phi'' at v' = 0, the
// rates of the coefficients dotted with the velocities plus the
// coefficients dotted with the accelerations at v' = 0.
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <string>
#include <vector>

#include "generator/symbolic/code_list.h"
#include "generator/symbolic/spatial_vectors.h"
#include "ir/model.h"

namespace mbfe::gen {

/// What a loop needs of one body, ground frame (a planar model's in the
/// plane z = 0, turning about z).
struct LoopBody {
  Mat3x rotation;
  Vec3x origin, omega, velocity;  // velocity: of the origin
  Vec3x alpha, bias_accel;        // angular and origin accelerations with v' = 0
};

/// The kinematics of a tree as the loop kernels read it.
struct LoopKinematics {
  std::vector<LoopBody> bodies;
  /// Per velocity coordinate: its unit motion (angular, linear) at the ground origin.
  std::vector<std::array<GiNaC::ex, 6>> columns;
  /// Per velocity coordinate: the one before it on the way to the ground, -1 at the root.
  std::vector<int> velocity_parent;
  /// Per body: its last velocity coordinate, where the walk to the ground starts.
  std::vector<int> last_velocity;
};

struct LoopKernels {
  Kernel constraints, jacobian, gamma;  // loop_constraints(q, Phi), loop_jacobian(q, J), loop_gamma(q, v, gamma)
  struct Entry {
    std::string name;
    int type = 0, first_row = 0, rows = 0;
  };
  std::vector<Entry> entries;  // per constraint, model order
  int rows = 0;                // nc
};

/// The kernels of every constraint of `model` (which has some); `v_name` is
/// the name of the velocity argument ("v" or "qd"). Intermediates go into `code`.
LoopKernels derive_loop_constraints(const ir::Model& model, const LoopKinematics& kin, const std::string& v_name,
                                    CodeList& code);

/// Two unit vectors that make a right-handed orthonormal frame (n1, n2, axis)
/// with the unit `axis`: n1 is axis x e normalised, e the coordinate axis least
/// aligned with it (the first of equals).
std::array<ir::Vec3, 2> perpendicular_pair(const ir::Vec3& axis);

}  // namespace mbfe::gen
