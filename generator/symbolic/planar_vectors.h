// Planar vectors of GiNaC expressions and the few operations the derivation
// needs. `cross` is the z component of the 3D cross product, `perp` is
// e_z x v (v rotated by +90 degrees).
#pragma once

#include <ginac/ginac.h>

#include "generator/symbolic/code_list.h"
#include "ir/model.h"

namespace mbfe::gen {

/// A planar vector of expressions.
struct Vec2x {
  GiNaC::ex x, y;
};

inline GiNaC::ex dot(const Vec2x& a, const Vec2x& b) { return a.x * b.x + a.y * b.y; }
inline GiNaC::ex cross(const Vec2x& a, const Vec2x& b) { return a.x * b.y - a.y * b.x; }
inline Vec2x perp(const Vec2x& v) { return {-v.y, v.x}; }
inline Vec2x add(const Vec2x& a, const Vec2x& b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2x sub(const Vec2x& a, const Vec2x& b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2x scale(const GiNaC::ex& s, const Vec2x& v) { return {s * v.x, s * v.y}; }
/// A vector of the model file, as exact decimal rationals.
inline Vec2x constant(const ir::Vec2& v) { return {exact(v[0]), exact(v[1])}; }
/// v rotated counter-clockwise by the angle whose cosine and sine are c, s.
inline Vec2x rotate(const GiNaC::ex& c, const GiNaC::ex& s, const Vec2x& v) {
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}
/// Both components as named intermediates of `code`.
inline Vec2x define(CodeList& code, const Vec2x& v) { return {code.define(v.x), code.define(v.y)}; }

}  // namespace mbfe::gen
