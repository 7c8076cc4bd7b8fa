// An undamped spatial model integrated with the generated kernels conserves
// its energy: a spherical pendulum carrying a revolute link and a slider on a
// spring (joints about skew axes, joint rotations, full inertia tensors),
// under gravity. The runtime does not take spatial models yet, so the test
// integrates M v' = Q - F, q' = G(q) v itself with classical RK4 and
// normalises the quaternion after each step, as an integrator would.
// Energy: E = 1/2 v^T M v - sum m g . p_com + 1/2 k (q - rest)^2, the centres
// of mass read through points placed on them.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "api/solver_cache.h"
#include "frontend/parse_model.h"
#include "ir/coordinate_layout.h"

namespace mbfe {
namespace {

constexpr const char* kModel = R"(model: spatial_energy
dimension: 3
gravity: [0.5, -0.3, -9.81]
bodies:
  - name: ball
    parent: ground
    joint: {type: spherical, at: [0.1, 0, 1.5], rotation: [0.2, -0.1, 0.3]}
    mass: 2.0
    inertia: [0.05, 0.04, 0.02, 0.003, -0.002, 0.001]
    com: [0.05, 0.02, -0.4]
    points: {c: [0.05, 0.02, -0.4]}
  - name: elbow
    parent: ball
    joint: {type: revolute, axis: [1, 0.5, -0.2], at: [0, 0, -0.8], rotation: [0, 0.4, 0]}
    mass: 1.2
    inertia: [0.03, 0.03, 0.01, 0, 0.002, 0]
    com: [0.02, 0.0, -0.3]
    points: {c: [0.02, 0.0, -0.3]}
  - name: slider
    parent: elbow
    joint: {type: prismatic, axis: [0.3, 0, -1], at: [0, 0.05, -0.5]}
    mass: 0.6
    inertia: [0.004, 0.005, 0.006, 0, 0, 0.0005]
    com: [0, 0.03, 0]
    points: {c: [0, 0.03, 0]}
loads:
  - {type: spring_damper, joint: slider, stiffness: 80, damping: 0, rest: 0.1}
)";

constexpr double kStiffness = 80.0, kRest = 0.1;  // the slider's spring, as in the model
constexpr double kStep = 5e-4;                    // s
constexpr double kDuration = 2.0;                 // s: several swings, ~70 turns of the spring
// RK4's energy drift here is 4.3e-6 J at h = 2e-3 and 2.7e-7 J at 1e-3 (the
// 16x of a fourth-order method), so about 1.7e-8 J, 7e-10 of the largest
// kinetic energy (26 J), at 5e-4. 1e-8 of it is well above that, and far
// below the 5e-4 that a Coriolis term off by 0.05 % makes. (A gyroscopic
// term w x I w does no work: this test cannot see it, the oracles do.)
constexpr double kEnergyTol = 1e-8;

struct System {
  const mbfe_model_v1* k;
  ir::Model model;
  ir::CoordinateLayout layout;

  Eigen::VectorXd rates(const Eigen::VectorXd& x) const {
    const int nq = layout.num_positions, nv = layout.num_velocities;
    const Eigen::VectorXd q = x.head(nq), v = x.tail(nv);
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M(nv, nv);
    Eigen::VectorXd F(nv), Q(nv), dx(nq + nv);
    k->dynamics(q.data(), v.data(), 0.0, M.data(), F.data(), Q.data());
    k->position_derivative(q.data(), v.data(), dx.data());
    dx.tail(nv) = M.ldlt().solve(Q - F);
    return dx;
  }

  double energy(const Eigen::VectorXd& x) const {
    const int nq = layout.num_positions, nv = layout.num_velocities;
    const Eigen::VectorXd q = x.head(nq), v = x.tail(nv);
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M(nv, nv);
    k->mass_matrix(q.data(), M.data());
    double e = 0.5 * v.dot(M * v);
    const Eigen::Vector3d g(model.gravity3[0], model.gravity3[1], model.gravity3[2]);
    for (std::size_t b = 0; b < model.bodies.size(); ++b) {
      Eigen::Vector3d com;
      k->point_position3(q.data(), static_cast<int>(b), 0, com.data());
      e -= model.bodies[b].mass * g.dot(com);
    }
    const double stretch = q[layout.first_position[2]] - kRest;
    return e + 0.5 * kStiffness * stretch * stretch;
  }
};

TEST(GeneratedSpatialDynamics, UndampedRunConservesEnergy) {
  System sys{nullptr, frontend::parse_model_text(kModel, "spatial_energy.yaml"), {}};
  sys.layout = ir::coordinate_layout(sys.model);
  sys.k = load_solver(sys.model, /*quiet=*/true).model;
  const int nq = sys.layout.num_positions;
  ASSERT_EQ(nq, 6);
  ASSERT_EQ(sys.layout.num_velocities, 5);
  // Tilted, spinning and stretched: every coordinate moves.
  Eigen::VectorXd x(nq + 5);
  x << Eigen::Vector4d(0.9, 0.3, -0.2, 0.25).normalized(), 0.7, 0.25, 1.5, -2.0, 0.8, 3.0, -0.5;
  const double e0 = sys.energy(x);
  double scale = 0.0, worst = 0.0;
  for (int step = 0; step * kStep < kDuration; ++step) {
    const Eigen::VectorXd k1 = sys.rates(x);
    const Eigen::VectorXd k2 = sys.rates(x + 0.5 * kStep * k1);
    const Eigen::VectorXd k3 = sys.rates(x + 0.5 * kStep * k2);
    const Eigen::VectorXd k4 = sys.rates(x + kStep * k3);
    x += kStep / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    x.head(4).normalize();  // the quaternion stays unit: the integrator's job
    const Eigen::VectorXd v = x.tail(5);
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M(5, 5);
    sys.k->mass_matrix(x.data(), M.data());
    scale = std::max(scale, 0.5 * v.dot(M * v));
    worst = std::max(worst, std::fabs(sys.energy(x) - e0));
  }
  ASSERT_GT(scale, 1.0);  // it moved
  EXPECT_LT(worst / scale, kEnergyTol) << "energy drift " << worst << " J of a kinetic energy up to " << scale << " J";
}

}  // namespace
}  // namespace mbfe
