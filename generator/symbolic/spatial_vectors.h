// Vectors and rotation matrices of GiNaC expressions for spatial models, and
// the few operations the derivation needs: the spatial counterpart of
// planar_vectors.h. Every matrix is a rotation or an inertia in the ground
// frame; none is ever inverted.
#pragma once

#include <ginac/ginac.h>

#include <array>

#include "generator/symbolic/code_list.h"
#include "ir/model.h"

namespace mbfe::gen {

/// A 3-vector of expressions.
struct Vec3x {
  GiNaC::ex x, y, z;
  const GiNaC::ex& operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
};

/// A 3x3 matrix of expressions, row-major: m[row][column].
struct Mat3x {
  std::array<std::array<GiNaC::ex, 3>, 3> m;
  Vec3x column(int c) const { return {m[0][c], m[1][c], m[2][c]}; }
};

/// A symmetric 3x3 matrix by its entries xx, yy, zz, xy, xz, yz (the order
/// of ir::InertiaTensor).
struct Sym3x {
  GiNaC::ex xx, yy, zz, xy, xz, yz;
};

inline Vec3x zero3() { return {0, 0, 0}; }
inline GiNaC::ex dot(const Vec3x& a, const Vec3x& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3x cross(const Vec3x& a, const Vec3x& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3x add(const Vec3x& a, const Vec3x& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3x sub(const Vec3x& a, const Vec3x& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3x scale(const GiNaC::ex& s, const Vec3x& v) { return {s * v.x, s * v.y, s * v.z}; }
inline Vec3x negate(const Vec3x& v) { return {-v.x, -v.y, -v.z}; }

/// A vector of the model file, as exact decimal rationals.
inline Vec3x constant(const ir::Vec3& v) { return {exact(v[0]), exact(v[1]), exact(v[2])}; }

/// A v.
inline Vec3x mul(const Mat3x& a, const Vec3x& v) {
  Vec3x r;
  GiNaC::ex* out[3] = {&r.x, &r.y, &r.z};
  for (int i = 0; i < 3; ++i) *out[i] = a.m[i][0] * v.x + a.m[i][1] * v.y + a.m[i][2] * v.z;
  return r;
}
/// A^T v.
inline Vec3x mul_transposed(const Mat3x& a, const Vec3x& v) {
  Vec3x r;
  GiNaC::ex* out[3] = {&r.x, &r.y, &r.z};
  for (int i = 0; i < 3; ++i) *out[i] = a.m[0][i] * v.x + a.m[1][i] * v.y + a.m[2][i] * v.z;
  return r;
}
/// A B.
inline Mat3x mul(const Mat3x& a, const Mat3x& b) {
  Mat3x r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
  return r;
}
/// S v for a symmetric S.
inline Vec3x mul(const Sym3x& s, const Vec3x& v) {
  return {s.xx * v.x + s.xy * v.y + s.xz * v.z, s.xy * v.x + s.yy * v.y + s.yz * v.z,
          s.xz * v.x + s.yz * v.y + s.zz * v.z};
}
inline Sym3x add(const Sym3x& a, const Sym3x& b) {
  return {a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.xz + b.xz, a.yz + b.yz};
}

inline Mat3x identity3() { return {{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}}; }

/// The rotation of roll, pitch, yaw (rad) as URDF's rpy: Rz(yaw) Ry(pitch)
/// Rx(roll), each entry an exact decimal of its double, and exactly 0, 1 or
/// -1 where the angles are whole quarter turns to double precision (0, and
/// the doubles nearest to pi/2, pi, ...), so a joint without `rotation` costs
/// nothing and a URDF-style quarter turn only permutes axes.
Mat3x rotation_rpy(const ir::Vec3& rpy);

/// The rotation by an angle with cosine c and sine s about the unit `axis`
/// (Rodrigues: c I + s [axis]x + (1 - c) axis axis^T).
Mat3x axis_rotation(const ir::Vec3& axis, const GiNaC::ex& c, const GiNaC::ex& s);

/// The rotation of the unit quaternion (w, x, y, z), Hamilton's convention:
/// R v = q v q*. Written for |q| = 1 (1 - 2 (y^2 + z^2) on the diagonal):
/// for another q the matrix is not a rotation.
Mat3x quaternion_rotation(const GiNaC::ex& w, const GiNaC::ex& x, const GiNaC::ex& y, const GiNaC::ex& z);

/// The inertia tensor of the model file as a symmetric matrix of exact decimals.
Sym3x constant(const ir::InertiaTensor& inertia);

/// R I R^T: a body-frame inertia in the ground frame.
Sym3x rotate(const Mat3x& r, const Sym3x& inertia);

/// Every component as a named intermediate of `code`.
Vec3x define(CodeList& code, const Vec3x& v);
Mat3x define(CodeList& code, const Mat3x& m);
Sym3x define(CodeList& code, const Sym3x& s);

}  // namespace mbfe::gen
