// RigidSystem against oracles: a single pendulum written here as an ABI model
// (closed-form acceleration and energy), and the hand-coded double pendulum.
#include "runtime/multibody/rigid_system.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "runtime/errors/multibody_errors.h"
#include "tests/reference/double_pendulum.h"
#include "tests/reference/double_pendulum_beam.h"

namespace mbfe::runtime {
namespace {

// Single pendulum: revolute at the origin, COM at [c, 0], gravity (0, -g).
// M = I + m c^2, F = 0, Q = -m g c cos q. Parameters are globals because the
// ABI takes plain C function pointers.
double g_m = 2.0, g_c = 0.4, g_I = 0.03;
constexpr double kG = 9.81;

void pend_mass(const double*, double* M) { M[0] = g_I + g_m * g_c * g_c; }
void pend_f(const double*, const double*, double* F) { F[0] = 0.0; }
void pend_q(const double* q, const double*, double, double* Q) {
  Q[0] = -g_m * kG * g_c * std::cos(q[0]);
}
void pend_point(const double* q, int, int, double* xy) {
  xy[0] = g_c * std::cos(q[0]);
  xy[1] = g_c * std::sin(q[0]);
}
const char* const kPendNames[] = {"arm"};

mbfe_model_v1 pendulum_model() {
  mbfe_model_v1 m{};
  m.abi_version = MBFE_MODEL_ABI_VERSION;
  m.model_name = "single_pendulum";
  m.num_coordinates = 1;
  m.coordinate_names = kPendNames;
  m.mass_matrix = pend_mass;
  m.inertial_forces = pend_f;
  m.generalized_forces = pend_q;
  m.point_position = pend_point;
  return m;
}

void rk4_step(OdeSystem& sys, double t, double h, Eigen::VectorXd& y) {
  Eigen::VectorXd k1, k2, k3, k4;
  sys.rhs(t, y, k1);
  sys.rhs(t + h / 2, y + h / 2 * k1, k2);
  sys.rhs(t + h / 2, y + h / 2 * k2, k3);
  sys.rhs(t + h, y + h * k3, k4);
  y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
}

// Generated kernel vs the closed form: a few roundings of O(1) values.
constexpr double kPendulumRel = 1e-14;
// Near cos q = 0 the closed form is tiny; its absolute rounding.
constexpr double kPendulumAbs = 1e-15;

TEST(RigidSystem, SinglePendulumAccelerationIsClosedForm) {
  const mbfe_model_v1 model = pendulum_model();
  RigidSystem sys(model, {{"arm", g_m, g_I}});
  ASSERT_EQ(sys.size(), 2);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 20; ++i) {
    Eigen::VectorXd y(2), ydot;
    y << u(rng), u(rng);
    sys.rhs(0.0, y, ydot);
    const double want = -g_m * kG * g_c * std::cos(y(0)) / (g_I + g_m * g_c * g_c);
    EXPECT_EQ(ydot(0), y(1));
    EXPECT_NEAR(ydot(1), want, kPendulumRel * std::abs(want) + kPendulumAbs);
  }
  EXPECT_EQ(sys.name(0), "arm");
  EXPECT_EQ(sys.name(1), "arm_dot");
}

TEST(RigidSystem, Rk4ConservesPendulumEnergy) {
  // RK4 at h = 1e-3 on a pendulum with omega ~ 5 rad/s: energy error per
  // period ~ (omega h)^5 ~ 3e-12; 1e-9 relative over 2 s is a safe bound.
  constexpr double kEnergyTol = 1e-9;
  const mbfe_model_v1 model = pendulum_model();
  RigidSystem sys(model);
  Eigen::VectorXd y(2);
  y << -0.3, 2.0;
  auto energy = [&](const Eigen::VectorXd& s) {
    return sys.kinetic_energy(s) + g_m * kG * g_c * std::sin(s(0));
  };
  const double e0 = energy(y);
  for (int i = 0; i < 2000; ++i) rk4_step(sys, i * 1e-3, 1e-3, y);
  EXPECT_LT(std::abs(energy(y) - e0), kEnergyTol * std::abs(e0));
}

TEST(RigidSystem, MasslessBodyGivesNamedError) {
  const double m_save = g_m, I_save = g_I;
  g_m = 0.0;
  g_I = 0.0;
  const mbfe_model_v1 model = pendulum_model();
  RigidSystem sys(model, {{"arm", 0.0, 0.0}});
  Eigen::VectorXd y(2), ydot;
  y << 0.1, 0.0;
  try {
    sys.rhs(0.25, y, ydot);
    ADD_FAILURE() << "expected SingularMassMatrixError";
  } catch (const SingularMassMatrixError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("arm"), std::string::npos) << msg;
    EXPECT_NE(msg.find("t = 0.25"), std::string::npos) << msg;
    EXPECT_NE(msg.find("mass 0 and inertia 0"), std::string::npos) << msg;
    ASSERT_EQ(e.coordinates().size(), 1u);
    EXPECT_EQ(e.coordinates()[0], "arm");
    ASSERT_EQ(e.massless_bodies().size(), 1u);
  }
  g_m = m_save;
  g_I = I_save;
}

const char* const kWheelNames[] = {"front_wheel", "rear_wheel"};

TEST(RigidSystem, ASingularMassMatrixTellsNoMassFromIllConditioning) {
  mbfe_model_v1 model{};
  model.abi_version = MBFE_MODEL_ABI_VERSION;
  model.model_name = "wheels";
  model.num_coordinates = 2;
  model.coordinate_names = kWheelNames;
  const std::vector<BodyInertia> bodies = {{"front_wheel", 1500.0, 0.0}, {"rear_wheel", 1500.0, 0.0}};
  const auto message = [&](const Eigen::Matrix2d& M) {
    try {
      throw_singular_mass_matrix(model, bodies, M, 0.4);
    } catch (const SingularMassMatrixError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // Two 1.5 t wheels coupled by a grown state: eigenvalues 3000 and 7.5e-10,
  // singular to 1e-10 of the largest, yet each coordinate moves mass.
  Eigen::Matrix2d grown;
  grown << 1500.0, 1500.0, 1500.0, 1500.0 * (1.0 + 1e-12);
  const std::string ill = message(grown);
  EXPECT_EQ(ill.find("move no mass"), std::string::npos) << ill;
  EXPECT_EQ(ill.find("Give the bodies"), std::string::npos) << ill;
  EXPECT_NE(ill.find("numerically only: front_wheel, rear_wheel move mass"), std::string::npos) << ill;
  EXPECT_NE(ill.find("`mbfe advise` or `mbfe stability`"), std::string::npos) << ill;
  // A zero diagonal entry: that coordinate, and only it, moves no mass.
  const std::string none = message(Eigen::Vector2d(1500.0, 0.0).asDiagonal().toDenseMatrix());
  EXPECT_NE(none.find("these coordinates move no mass: rear_wheel."), std::string::npos) << none;
}

const char* const kBallPositions[] = {"ball_qw", "ball_qx", "ball_qy", "ball_qz"};
const char* const kBallVelocities[] = {"ball_wx", "ball_wy", "ball_wz"};

TEST(RigidSystem, ASingularMassMatrixNamesVelocityCoordinates) {
  // A ball joint: 4 position coordinates (its quaternion), 3 velocity
  // coordinates (its angular velocity), and M is 3 x 3 over the latter.
  mbfe_model_v1 model{};
  model.abi_version = MBFE_MODEL_ABI_VERSION;
  model.model_name = "ball";
  model.num_coordinates = 4;
  model.coordinate_names = kBallPositions;
  model.num_velocities = 3;
  model.velocity_names = kBallVelocities;
  const std::vector<BodyInertia> bodies = {{"ball", 1.0, 0.0}};
  std::string message;
  try {
    throw_singular_mass_matrix(model, bodies, Eigen::Vector3d(0.0, 0.2, 0.0).asDiagonal().toDenseMatrix(), 0.0);
  } catch (const SingularMassMatrixError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("these coordinates move no mass: ball_wx, ball_wz."), std::string::npos) << message;
  EXPECT_EQ(message.find("ball_q"), std::string::npos) << message;
}

TEST(RigidSystem, WrongSizesAreRejected) {
  const mbfe_model_v1 model = pendulum_model();
  EXPECT_THROW((RigidSystem(model, {{"a", 1, 1}, {"b", 1, 1}})), std::invalid_argument);
  RigidSystem sys(model);
  Eigen::VectorXd y(3), ydot;
  y.setZero();
  EXPECT_THROW(sys.rhs(0.0, y, ydot), std::invalid_argument);
  RigidTerms terms;
  EXPECT_THROW(evaluate_rigid_terms(model, Eigen::VectorXd(2), Eigen::VectorXd(1), 0.0, terms),
               std::invalid_argument);
}

TEST(RigidSystem, DoublePendulumMatchesReference) {
  // Same closed forms in a different order: a few ulps after a 2 x 2 solve.
  constexpr double kTol = 1e-12;
  const mbfe_model_v1& model = *reference::double_pendulum_beam_model();
  const reference::DoublePendulumParams& p = reference::double_pendulum_beam_params().pendulum;
  RigidSystem sys(model);
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  for (int i = 0; i < 100; ++i) {
    Eigen::VectorXd y(4), ydot;
    y << u(rng), u(rng), u(rng), u(rng);
    sys.rhs(0.0, y, ydot);
    const Eigen::Vector2d q = y.head<2>(), qd = y.tail<2>();
    const Eigen::Vector2d want = reference::mass_matrix(p, q).ldlt().solve(
        reference::generalized_forces(p, q) - reference::inertial_forces(p, q, qd));
    EXPECT_LT((ydot.tail<2>() - want).norm(), kTol * (1.0 + want.norm()));
    RigidTerms terms;
    evaluate_rigid_terms(model, y.head(2), y.tail(2), 0.0, terms);
    EXPECT_LT((terms.M - reference::mass_matrix(p, q)).norm(), kTol);
  }
}

}  // namespace
}  // namespace mbfe::runtime
