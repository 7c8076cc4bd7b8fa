#include "generator/symbolic/spatial_vectors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace mbfe::gen {

using GiNaC::ex;

namespace {

/// k when `angle` is k quarter turns to double precision (the double nearest
/// to k pi/2, give or take a few units in the last place), else none. A file
/// can only write pi/2 as 1.5707963267948966, whose cosine is 6.1e-17, not 0.
std::optional<long> quarter_turns(double angle) {
  constexpr double kQuarter = 1.5707963267948966;  // pi/2 rounded to a double
  constexpr double kUlps = 4;  // k * kQuarter and the file's digits each round once
  const double k = std::nearbyint(angle / kQuarter);
  const double tolerance = kUlps * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(angle));
  if (std::fabs(angle - k * kQuarter) > tolerance) return std::nullopt;
  return static_cast<long>(k);
}

}  // namespace

Mat3x rotation_rpy(const ir::Vec3& rpy) {
  // Exact 1, 0 and -1 for a whole number of quarter turns (no rotation,
  // URDF's rpy of 1.5707963267948966 or 3.141592653589793); otherwise the
  // decimal of the double's cosine and sine.
  static constexpr int kCosine[4] = {1, 0, -1, 0};
  auto cosine = [](double a) {
    const std::optional<long> k = quarter_turns(a);
    return k ? ex(kCosine[((*k % 4) + 4) % 4]) : ex(exact(std::cos(a)));
  };
  auto sine = [](double a) {
    const std::optional<long> k = quarter_turns(a);
    return k ? ex(kCosine[((*k % 4) + 7) % 4]) : ex(exact(std::sin(a)));  // sin(a) = cos(a - pi/2)
  };
  const ex cr = cosine(rpy[0]), sr = sine(rpy[0]);
  const ex cp = cosine(rpy[1]), sp = sine(rpy[1]);
  const ex cy = cosine(rpy[2]), sy = sine(rpy[2]);
  const Mat3x rx{{{{1, 0, 0}, {0, cr, -sr}, {0, sr, cr}}}};
  const Mat3x ry{{{{cp, 0, sp}, {0, 1, 0}, {-sp, 0, cp}}}};
  const Mat3x rz{{{{cy, -sy, 0}, {sy, cy, 0}, {0, 0, 1}}}};
  return mul(rz, mul(ry, rx));
}

Mat3x axis_rotation(const ir::Vec3& axis, const ex& c, const ex& s) {
  const ex x = exact(axis[0]), y = exact(axis[1]), z = exact(axis[2]);
  const ex k = 1 - c;
  // A coordinate axis gives exact 0 and 1 entries ((1 - c) + c is 1).
  return {{{{c + k * x * x, k * x * y - s * z, k * x * z + s * y},
            {k * x * y + s * z, c + k * y * y, k * y * z - s * x},
            {k * x * z - s * y, k * y * z + s * x, c + k * z * z}}}};
}

Mat3x quaternion_rotation(const ex& w, const ex& x, const ex& y, const ex& z) {
  return {{{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
            {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
            {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}}};
}

Sym3x constant(const ir::InertiaTensor& i) {
  return {exact(i[0]), exact(i[1]), exact(i[2]), exact(i[3]), exact(i[4]), exact(i[5])};
}

Sym3x rotate(const Mat3x& r, const Sym3x& inertia) {
  // (R I) R^T, only the six distinct entries of the symmetric result.
  const Vec3x rows[3] = {mul(inertia, Vec3x{r.m[0][0], r.m[0][1], r.m[0][2]}),
                         mul(inertia, Vec3x{r.m[1][0], r.m[1][1], r.m[1][2]}),
                         mul(inertia, Vec3x{r.m[2][0], r.m[2][1], r.m[2][2]})};  // I r_i (I symmetric)
  auto entry = [&](int i, int j) { return dot(rows[i], Vec3x{r.m[j][0], r.m[j][1], r.m[j][2]}); };
  return {entry(0, 0), entry(1, 1), entry(2, 2), entry(0, 1), entry(0, 2), entry(1, 2)};
}

namespace {

// A component that is a number or a named intermediate up to its sign stays
// as it is (a unary minus is free); anything else becomes a temporary.
ex define_component(CodeList& code, const ex& value) {
  return is_atomic(value) || is_atomic(-value) ? value : code.define(value);
}

}  // namespace

Vec3x define(CodeList& code, const Vec3x& v) {
  return {define_component(code, v.x), define_component(code, v.y), define_component(code, v.z)};
}

Mat3x define(CodeList& code, const Mat3x& m) {
  Mat3x r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.m[i][j] = define_component(code, m.m[i][j]);
  return r;
}

Sym3x define(CodeList& code, const Sym3x& s) {
  return {define_component(code, s.xx), define_component(code, s.yy), define_component(code, s.zz),
          define_component(code, s.xy), define_component(code, s.xz), define_component(code, s.yz)};
}

}  // namespace mbfe::gen
