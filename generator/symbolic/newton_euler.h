// The backward pass of the derivation (eq (5) of the paper, the recursive
// Newton-Euler algorithm with q'' = 0): for every body, leaves to ground, the
// net force and moment its subtree needs (inertial) and receives (applied:
// gravity, point forces, torques), and the spring-damper terms of its joint.
// Projected on the joint axes they are F and Q of M q'' + F = Q.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "generator/symbolic/code_list.h"
#include "generator/symbolic/planar_vectors.h"
#include "generator/symbolic/rigid_kinematics.h"
#include "ir/model.h"

namespace mbfe::gen {

/// Per body: subtree forces (ground frame) and moments about the body's joint
/// origin, and the spring-damper generalized force on its own coordinate.
struct SubtreeForces {
  std::vector<Vec2x> inertial_force, applied_force;
  std::vector<GiNaC::ex> inertial_moment, applied_moment;
  std::vector<GiNaC::ex> spring;
};

SubtreeForces newton_euler_pass(const ir::Model& model, const std::vector<BodyKinematics>& kin,
                                const std::vector<std::vector<int>>& children, const std::vector<GiNaC::symbol>& q,
                                const std::vector<GiNaC::symbol>& qd, const GiNaC::symbol& t,
                                CodeList& code);

}  // namespace mbfe::gen
