#include "generator/symbolic/loop_constraints.h"

#include <cmath>

namespace mbfe::gen {

using GiNaC::ex;

namespace {

/// One end of a loop, its point and that point's motion.
struct EndMotion {
  int body = -1;
  Vec3x point, velocity, accel;  // ground frame; accel with v' = 0
  Vec3x omega, alpha;
  Mat3x rotation;
};

/// One constraint row: Phi' = c_wa . w_a + c_pa . p_a' + c_wb . w_b + c_pb . p_b',
/// and Phi'' at v' = 0 (gamma is its negative).
struct Row {
  ex value;
  Vec3x c_wa, c_pa, c_wb, c_pb;
  ex second_rate;
};

EndMotion end_motion(const ir::LoopEnd& end, const LoopKinematics& kin, CodeList& code) {
  EndMotion m;
  m.body = end.body;
  if (end.body < 0) {  // the ground
    m.point = constant(end.at);
    m.velocity = m.accel = m.omega = m.alpha = zero3();
    m.rotation = identity3();
    return m;
  }
  const LoopBody& b = kin.bodies[end.body];
  const Vec3x arm = define(code, mul(b.rotation, constant(end.at)));  // p - o
  m.point = define(code, add(b.origin, arm));
  m.velocity = define(code, add(b.velocity, cross(b.omega, arm)));
  m.accel = define(code, add(add(b.bias_accel, cross(b.alpha, arm)), cross(b.omega, cross(b.omega, arm))));
  m.omega = b.omega;
  m.alpha = b.alpha;
  m.rotation = b.rotation;
  return m;
}

Vec3x unit(int k) { return {k == 0 ? 1 : 0, k == 1 ? 1 : 0, k == 2 ? 1 : 0}; }

Row point_row(const EndMotion& a, const EndMotion& b, int k) {
  const Vec3x e = unit(k);
  return {a.point[k] - b.point[k], zero3(), e, zero3(), negate(e), a.accel[k] - b.accel[k]};
}

/// (R_a n) . (p_b - p_a), n in a's frame.
Row slide_row(const EndMotion& a, const EndMotion& b, const ir::Vec3& n_local, CodeList& code) {
  const Vec3x n = define(code, mul(a.rotation, constant(n_local)));
  const Vec3x d = define(code, sub(b.point, a.point));
  const Vec3x d_rate = sub(b.velocity, a.velocity);
  const Vec3x n_rate = cross(a.omega, n);
  const Vec3x n_cross_d = define(code, cross(n, d));
  // Phi' = w_a . (n x d) + n . d', so
  // Phi'' = a(w)_a . (n x d) + w_a . (n' x d + n x d') + n' . d' + n . d''.
  const ex second = dot(a.alpha, n_cross_d) + dot(a.omega, add(cross(n_rate, d), cross(n, d_rate))) +
                    dot(n_rate, d_rate) + dot(n, sub(b.accel, a.accel));
  return {dot(n, d), n_cross_d, negate(n), zero3(), n, second};
}

/// (R_a u) . (R_b e), u in a's frame and e in b's.
Row orientation_row(const EndMotion& a, const EndMotion& b, const ir::Vec3& u_local, const ir::Vec3& e_local,
                    CodeList& code) {
  const Vec3x u = define(code, mul(a.rotation, constant(u_local)));
  const Vec3x e = define(code, mul(b.rotation, constant(e_local)));
  const Vec3x u_cross_e = define(code, cross(u, e));
  // Phi' = (u x e) . (w_a - w_b); (u x e)' = (w_a x u) x e + u x (w_b x e).
  const Vec3x rate = add(cross(cross(a.omega, u), e), cross(u, cross(b.omega, e)));
  const ex second = dot(rate, sub(a.omega, b.omega)) + dot(u_cross_e, sub(a.alpha, b.alpha));
  return {dot(u, e), u_cross_e, zero3(), negate(u_cross_e), zero3(), second};
}

std::vector<Row> rows_of(const ir::LoopConstraint& loop, int dimension, const EndMotion& a, const EndMotion& b,
                         CodeList& code) {
  std::vector<Row> rows;
  if (dimension != 3) {
    // The plane: a point (or a revolute, the same) is x and y; a prismatic
    // is the slide across the axis and the angle (its sine) between the frames.
    if (loop.type != ir::LoopType::kPrismatic) return {point_row(a, b, 0), point_row(a, b, 1)};
    const ir::Vec3 across{-loop.axis[1], loop.axis[0], 0.0};  // e_z x axis
    return {slide_row(a, b, across, code), orientation_row(a, b, across, loop.axis, code)};
  }
  const std::array<ir::Vec3, 2> n = perpendicular_pair(loop.axis);
  switch (loop.type) {
    case ir::LoopType::kPoint:
      return {point_row(a, b, 0), point_row(a, b, 1), point_row(a, b, 2)};
    case ir::LoopType::kRevolute:
      // b's copy of the axis stays perpendicular to b's n1, n2: the axes stay parallel.
      return {point_row(a, b, 0), point_row(a, b, 1), point_row(a, b, 2),
              orientation_row(a, b, loop.axis, n[0], code), orientation_row(a, b, loop.axis, n[1], code)};
    case ir::LoopType::kPrismatic:
      // Across the axis twice, the axes parallel, and no twist about them.
      return {slide_row(a, b, n[0], code), slide_row(a, b, n[1], code),
              orientation_row(a, b, loop.axis, n[0], code), orientation_row(a, b, loop.axis, n[1], code),
              orientation_row(a, b, n[0], n[1], code)};
  }
  return rows;
}

/// The velocity coordinates that move `body`, from its own to the root's.
std::vector<int> path_of(int body, const LoopKinematics& kin) {
  std::vector<int> path;
  if (body < 0) return path;
  for (int j = kin.last_velocity[body]; j >= 0; j = kin.velocity_parent[j]) path.push_back(j);
  return path;
}

std::string index(const std::string& array, int i) { return array + "[" + std::to_string(i) + "]"; }

}  // namespace

std::array<ir::Vec3, 2> perpendicular_pair(const ir::Vec3& axis) {
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (std::fabs(axis[k]) < std::fabs(axis[least])) least = k;
  ir::Vec3 e{0.0, 0.0, 0.0};
  e[least] = 1.0;
  ir::Vec3 n1{axis[1] * e[2] - axis[2] * e[1], axis[2] * e[0] - axis[0] * e[2], axis[0] * e[1] - axis[1] * e[0]};
  const double length = std::sqrt(n1[0] * n1[0] + n1[1] * n1[1] + n1[2] * n1[2]);
  for (double& c : n1) c /= length;
  const ir::Vec3 n2{axis[1] * n1[2] - axis[2] * n1[1], axis[2] * n1[0] - axis[0] * n1[2],
                    axis[0] * n1[1] - axis[1] * n1[0]};
  return {n1, n2};
}

LoopKernels derive_loop_constraints(const ir::Model& model, const LoopKinematics& kin, const std::string& v_name,
                                    CodeList& code) {
  LoopKernels out;
  const int nv = static_cast<int>(kin.columns.size());
  out.constraints = {"loop_constraints", "const double* q, double* Phi",
                     "Closed loops: constraint values Phi(q), nc entries (m, or the sine or cosine of an angle).",
                     {}, {}};
  out.jacobian = {"loop_jacobian", "const double* q, double* J",
                  "Closed loops: J, row-major nc x nv, with Phi' = J " + v_name + ".", {}, {}};
  out.gamma = {"loop_gamma", "const double* q, const double* " + v_name + ", double* gamma",
               "Closed loops: gamma = -(dJ/dt) " + v_name + ", nc entries, so that Phi'' = 0 reads J " + v_name +
                   "' = gamma.",
               {}, {}};
  for (const ir::LoopConstraint& loop : model.constraints) {
    const EndMotion a = end_motion(loop.a, kin, code);
    const EndMotion b = end_motion(loop.b, kin, code);
    const std::vector<Row> rows = rows_of(loop, model.dimension, a, b, code);
    out.entries.push_back({loop.name, static_cast<int>(loop.type), out.rows, static_cast<int>(rows.size())});
    const std::vector<int> path_a = path_of(a.body, kin), path_b = path_of(b.body, kin);
    for (const Row& row : rows) {
      const int r = out.rows++;
      out.constraints.outputs.push_back({index("Phi", r), code.define(row.value)});
      // The spatial force each end contributes: (c_w + p x c_p, c_p) at the ground origin.
      std::array<ex, 6> force_a, force_b;
      const Vec3x ma = add(row.c_wa, cross(a.point, row.c_pa)), mb = add(row.c_wb, cross(b.point, row.c_pb));
      for (int c = 0; c < 3; ++c) {
        force_a[c] = code.define(ma[c]);
        force_a[3 + c] = code.define(row.c_pa[c]);
        force_b[c] = code.define(mb[c]);
        force_b[3 + c] = code.define(row.c_pb[c]);
      }
      std::vector<ex> entry(nv, 0);
      auto add_end = [&](const std::vector<int>& path, const std::array<ex, 6>& force) {
        for (int j : path)
          for (int c = 0; c < 6; ++c) entry[j] += kin.columns[j][c] * force[c];
      };
      add_end(path_a, force_a);
      add_end(path_b, force_b);
      for (int j = 0; j < nv; ++j) out.jacobian.outputs.push_back({index("J", r * nv + j), code.define(entry[j])});
      out.gamma.outputs.push_back({index("gamma", r), code.define(-row.second_rate)});
    }
  }
  for (Kernel* k : {&out.constraints, &out.jacobian, &out.gamma}) k->statements = code.closure(k->outputs);
  return out;
}

}  // namespace mbfe::gen
