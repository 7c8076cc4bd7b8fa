// The forward pass of the derivation (eqs (2)-(4) of the paper): for every
// body, ground outwards, its absolute angle (cosine and sine, each computed
// once), joint origin, slider axis, centre-of-mass offset, angular velocity
// and the acceleration of its origin with q'' = 0. Every quantity is a named
// intermediate of the code list.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "generator/symbolic/code_list.h"
#include "generator/symbolic/planar_vectors.h"
#include "ir/model.h"

namespace mbfe::gen {

// What the forward pass knows of one body.
struct BodyKinematics {
  Vec2x origin;          // joint origin o_i, ground frame
  Vec2x offset;          // o_i - o_parent, ground frame
  GiNaC::ex offset_squared;     // |o_i - o_parent|^2 (a constant for a revolute joint)
  GiNaC::ex cos_angle, sin_angle;
  Vec2x axis;            // prismatic: joint axis u_i in the ground frame
  Vec2x com_offset;      // p_i - o_i, ground frame
  GiNaC::ex omega;              // angular velocity
  Vec2x bias_accel;      // origin acceleration with q'' = 0
};

/// The kinematics of every body of `model` in terms of q and qd (one symbol
/// per body, model order).
std::vector<BodyKinematics> forward_kinematics(const ir::Model& model, const std::vector<GiNaC::symbol>& q,
                                               const std::vector<GiNaC::symbol>& qd, CodeList& code);

/// The children of every body (index lists, in model order).
std::vector<std::vector<int>> children_of(const ir::Model& model);

}  // namespace mbfe::gen
