// Hand derivation of the contact kernels of models/double_pendulum_beam.yaml.
//
// Pendulum: as tests/reference/double_pendulum.cpp (M, F, Q reused from there).
// Tip:   p(q) = h + l1 e(th1) + l2 e(th2),  th1 = q1, th2 = q1 + q2,
//        e(a) = (cos a, sin a), n(a) = (-sin a, cos a).
//   dp/dq1 = l1 n(th1) + l2 n(th2),  dp/dq2 = l2 n(th2),
//   velocity p' = l1 n(th1) th1' + l2 n(th2) th2',
//   velocity-quadratic acceleration a_v = -l1 e(th1) th1'^2 - l2 e(th2) th2'^2
//   (p'' = (dp/dq) q'' + a_v).
// Beam frame: ex = (cos alpha, sin alpha), ey = (-sin alpha, cos alpha), origin o:
//   x_P = (p - o).ex,  y_P = (p - o).ey.
// Deflection on the element [s0, s0 + le], xi = (s - s0)/le:
//   w(s) = N(xi) . qe,  N = [1 - 3xi^2 + 2xi^3, le (xi - 2xi^2 + xi^3), 3xi^2 - 2xi^3,
//                            le (-xi^2 + xi^3)],  qe = [w1, w1', w2, w2'];
//   w_s = N_s . qe (N_s = dN/ds = N'(xi)/le), w_ss = N_ss . qe.
//
// slider_pin: s = x_P(q),  Phi = w(s, qe) - y_P(q).
//   J_b = w_s(s) dx_P/dq - dy_P/dq               (1 x 2)
//   J_e = N(xi(s))                                (1 x 4)
//   Phi' = J_b q' + J_e qe', with s' = p'.ex.
//   Phi'' = J_b q'' + J_e qe'' + w_ss s'^2 + 2 s' (N_s . qe') + w_s (a_v.ex) - a_v.ey
//   (d/dt of w_s(s, qe) = w_ss s' + N_s . qe';  d/dt N(s) = N_s s'), hence
//   gamma = -(w_ss s'^2 + 2 s' (N_s . qe') + w_s (a_v.ex) - a_v.ey).
//
// pin at s = a (constant): Phi1 = a - x_P(q), Phi2 = w(a, qe) - y_P(q);
//   J_b = [-dx_P/dq; -dy_P/dq],  J_e = [0 0 0 0; N(xi(a))],
//   gamma = -[-a_v.ex; -a_v.ey] = [a_v.ex; a_v.ey].
#include "tests/reference/double_pendulum_beam.h"

#include <cmath>

namespace mbfe::reference {

namespace {

const DoublePendulumBeamParams& P() { return double_pendulum_beam_params(); }

Eigen::Vector2d e_of(double a) { return {std::cos(a), std::sin(a)}; }
Eigen::Vector2d n_of(double a) { return {-std::sin(a), std::cos(a)}; }

struct TipKinematics {
  Eigen::Vector2d p;      // m, ground
  Eigen::Vector2d dp[2];  // dp/dq_j
  Eigen::Vector2d ex, ey;
  double x, y;            // m, beam frame
  double dx[2], dy[2];    // d(x, y)/dq_j
};

TipKinematics tip(const double* q) {
  const DoublePendulumBeamParams& pr = P();
  const double th1 = q[0], th2 = q[0] + q[1];
  TipKinematics k;
  k.p = pr.pendulum.hinge + pr.pendulum.l1 * e_of(th1) + pr.l2 * e_of(th2);
  k.dp[1] = pr.l2 * n_of(th2);
  k.dp[0] = pr.pendulum.l1 * n_of(th1) + k.dp[1];
  k.ex = e_of(pr.beam_angle);
  k.ey = n_of(pr.beam_angle);
  k.x = (k.p - pr.beam_origin).dot(k.ex);
  k.y = (k.p - pr.beam_origin).dot(k.ey);
  for (int j = 0; j < 2; ++j) {
    k.dx[j] = k.dp[j].dot(k.ex);
    k.dy[j] = k.dp[j].dot(k.ey);
  }
  return k;
}

Eigen::Vector2d tip_velocity(const double* q, const double* qd) {
  const DoublePendulumBeamParams& pr = P();
  const double th1 = q[0], th2 = q[0] + q[1];
  return pr.pendulum.l1 * n_of(th1) * qd[0] + pr.l2 * n_of(th2) * (qd[0] + qd[1]);
}

Eigen::Vector2d tip_quadratic_acceleration(const double* q, const double* qd) {
  const DoublePendulumBeamParams& pr = P();
  const double th1 = q[0], th2 = q[0] + q[1];
  const double w1 = qd[0], w2 = qd[0] + qd[1];
  return -pr.pendulum.l1 * e_of(th1) * w1 * w1 - pr.l2 * e_of(th2) * w2 * w2;
}

Eigen::Map<const Eigen::Vector4d> qe_of(const double* qe) {
  return Eigen::Map<const Eigen::Vector4d>(qe);
}

// --- rigid part -----------------------------------------------------------

void mass_matrix_fn(const double* q, double* M) {
  const Eigen::Matrix2d m = mass_matrix(P().pendulum, Eigen::Vector2d(q[0], q[1]));
  M[0] = m(0, 0); M[1] = m(0, 1); M[2] = m(1, 0); M[3] = m(1, 1);
}
void inertial_forces_fn(const double* q, const double* qd, double* F) {
  const Eigen::Vector2d f =
      inertial_forces(P().pendulum, Eigen::Vector2d(q[0], q[1]), Eigen::Vector2d(qd[0], qd[1]));
  F[0] = f(0); F[1] = f(1);
}
void generalized_forces_fn(const double* q, const double*, double, double* Q) {
  const Eigen::Vector2d f = generalized_forces(P().pendulum, Eigen::Vector2d(q[0], q[1]));
  Q[0] = f(0); Q[1] = f(1);
}
void point_position_fn(const double* q, int body, int /*point*/, double* xy) {
  const DoublePendulumBeamParams& pr = P();
  Eigen::Vector2d r = pr.pendulum.hinge + pr.pendulum.l1 * e_of(q[0]);
  if (body == 1) r += pr.l2 * e_of(q[0] + q[1]);
  xy[0] = r(0); xy[1] = r(1);
}

// --- slider_pin -------------------------------------------------------------

double slider_position(const double* q) { return tip(q).x; }

void slider_phi(const double* q, const double* qe, double s0, double le, double* Phi) {
  const TipKinematics k = tip(q);
  const double xi = (k.x - s0) / le;
  Phi[0] = hermite_n(xi, le).dot(qe_of(qe)) - k.y;
}

void slider_jacobians(const double* q, const double* qe, double s0, double le, double* Jb,
                      double* Je) {
  const TipKinematics k = tip(q);
  const double xi = (k.x - s0) / le;
  const double w_s = hermite_dn(xi, le).dot(qe_of(qe));
  for (int j = 0; j < 2; ++j) Jb[j] = w_s * k.dx[j] - k.dy[j];
  const Eigen::Vector4d n = hermite_n(xi, le);
  for (int j = 0; j < 4; ++j) Je[j] = n(j);
}

void slider_gamma(const double* q, const double* qd, const double* qe, const double* qed,
                  double s0, double le, double* gamma) {
  const TipKinematics k = tip(q);
  const double xi = (k.x - s0) / le;
  const Eigen::Vector4d ns = hermite_dn(xi, le);
  const double w_s = ns.dot(qe_of(qe));
  const double w_ss = hermite_ddn(xi, le).dot(qe_of(qe));
  const double sd = tip_velocity(q, qd).dot(k.ex);
  const Eigen::Vector2d av = tip_quadratic_acceleration(q, qd);
  gamma[0] = -(w_ss * sd * sd + 2.0 * sd * ns.dot(qe_of(qed)) + w_s * av.dot(k.ex) -
               av.dot(k.ey));
}

// --- pin --------------------------------------------------------------------

double pin_position(const double*) { return kPinAt; }

void pin_phi(const double* q, const double* qe, double s0, double le, double* Phi) {
  const TipKinematics k = tip(q);
  Phi[0] = kPinAt - k.x;
  Phi[1] = hermite_n((kPinAt - s0) / le, le).dot(qe_of(qe)) - k.y;
}

void pin_jacobians(const double* q, const double*, double s0, double le, double* Jb,
                   double* Je) {
  const TipKinematics k = tip(q);
  for (int j = 0; j < 2; ++j) {
    Jb[j] = -k.dx[j];
    Jb[2 + j] = -k.dy[j];
  }
  const Eigen::Vector4d n = hermite_n((kPinAt - s0) / le, le);
  for (int j = 0; j < 4; ++j) {
    Je[j] = 0.0;
    Je[4 + j] = n(j);
  }
}

void pin_gamma(const double* q, const double* qd, const double*, const double*, double,
               double, double* gamma) {
  const TipKinematics k = tip(q);
  const Eigen::Vector2d av = tip_quadratic_acceleration(q, qd);
  gamma[0] = av.dot(k.ex);
  gamma[1] = av.dot(k.ey);
}

const char* const kNames[] = {"link1", "link2"};

const mbfe_contact_kernels_v1 kSlider[] = {{"tip_slider", 1, 0, 0.0, 1, slider_position,
                                            slider_phi, slider_jacobians, slider_gamma}};
const mbfe_contact_kernels_v1 kPin[] = {
    {"tip_pin", 0, 0, kPinAt, 2, pin_position, pin_phi, pin_jacobians, pin_gamma}};

mbfe_model_v1 make_model(const char* name, const mbfe_contact_kernels_v1* contacts) {
  mbfe_model_v1 m{};
  m.abi_version = MBFE_MODEL_ABI_VERSION;
  m.model_name = name;
  m.model_sha256 = "hand-coded";
  m.generator_version = "hand-coded";
  m.num_coordinates = 2;
  m.coordinate_names = kNames;
  m.mass_matrix = mass_matrix_fn;
  m.inertial_forces = inertial_forces_fn;
  m.generalized_forces = generalized_forces_fn;
  m.point_position = point_position_fn;
  m.num_contacts = 1;
  m.contacts = contacts;
  return m;
}

}  // namespace

const DoublePendulumBeamParams& double_pendulum_beam_params() {
  static const DoublePendulumBeamParams params = [] {
    DoublePendulumBeamParams p;
    p.pendulum.m1 = 1.0;
    p.pendulum.m2 = 1.0;
    p.pendulum.l1 = 0.7;
    p.pendulum.c1 = 0.35;
    p.pendulum.c2 = 0.35;
    p.pendulum.I1 = 1.0 * 0.7 * 0.7 / 12.0;
    p.pendulum.I2 = 1.0 * 0.7 * 0.7 / 12.0;
    p.pendulum.gravity = {0.0, -9.81};
    p.pendulum.hinge = {1.0, 1.2};
    return p;
  }();
  return params;
}

const mbfe_model_v1* double_pendulum_beam_model() {
  static const mbfe_model_v1 model = make_model("double_pendulum_beam", kSlider);
  return &model;
}

const mbfe_model_v1* double_pendulum_beam_pin_model() {
  static const mbfe_model_v1 model = make_model("double_pendulum_beam_pin", kPin);
  return &model;
}

Eigen::Vector4d hermite_n(double xi, double le) {
  const double x2 = xi * xi, x3 = x2 * xi;
  return {1.0 - 3.0 * x2 + 2.0 * x3, le * (xi - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3,
          le * (x3 - x2)};
}

Eigen::Vector4d hermite_dn(double xi, double le) {
  const double x2 = xi * xi;
  return Eigen::Vector4d(-6.0 * xi + 6.0 * x2, le * (1.0 - 4.0 * xi + 3.0 * x2),
                         6.0 * xi - 6.0 * x2, le * (3.0 * x2 - 2.0 * xi)) /
         le;
}

Eigen::Vector4d hermite_ddn(double xi, double le) {
  return Eigen::Vector4d(-6.0 + 12.0 * xi, le * (-4.0 + 6.0 * xi), 6.0 - 12.0 * xi,
                         le * (6.0 * xi - 2.0)) /
         (le * le);
}

}  // namespace mbfe::reference
