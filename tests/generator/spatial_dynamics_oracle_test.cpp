// Generated M, F, Q, point positions and position rates of random spatial
// trees (revolute and prismatic joints about random axes, fixed joint
// rotations, full inertia tensors, spherical and free joints, every kind of
// load) against an independent numerical oracle written straight from the
// conventions of the model format (tests/support/spatial_oracle.h):
//   M = sum_i m_i Jv_i^T Jv_i + Jw_i^T I_i Jw_i   (Jv: centre-of-mass Jacobian, Jw: angular)
//   F = sum_i m_i Jv_i^T a_i + Jw_i^T (I_i alpha_i + w_i x I_i w_i)   (a, alpha: at v' = 0)
//   Q = sum_i Jv_i^T m_i g + Jp^T f + Jw^T tau - k (q - rest) - c v
// with I_i = R_i I R_i^T and the Jacobians and accelerations from finite
// differences of the forward kinematics along the velocity coordinates.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "api/solver_cache.h"
#include "frontend/parse_model.h"
#include "tests/support/random_spatial_tree.h"
#include "tests/support/spatial_oracle.h"

namespace mbfe {
namespace {

using test::random_spatial_tree_yaml;
using test::random_state;
using test::vec;

// Finite differences of O(1) positions (spatial_oracle.h): first derivatives
// to ~1e-10, the second-order ones to ~1e-8. Relative agreement checked to:
constexpr double kJacobianTol = 1e-7;
constexpr double kBiasTol = 1e-5;
// Two kernels doing the same arithmetic in another order differ by a few ulps
// of the largest entry; 1e-13 of it is ~500 ulps.
constexpr double kSameArithmeticTol = 1e-13;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Oracle {
  Eigen::MatrixXd M;
  Eigen::VectorXd F, Q;
};

Oracle oracle(const ir::Model& m, const ir::CoordinateLayout& layout, const Eigen::VectorXd& q,
              const Eigen::VectorXd& v, double t) {
  const int nv = layout.num_velocities;
  Oracle o{Eigen::MatrixXd::Zero(nv, nv), Eigen::VectorXd::Zero(nv), Eigen::VectorXd::Zero(nv)};
  const test::SpatialPose pose = test::spatial_pose(m, layout, q);
  const Eigen::Vector3d g = vec(m.gravity3);
  for (std::size_t i = 0; i < m.bodies.size(); ++i) {
    const ir::Body& b = m.bodies[i];
    const int body = static_cast<int>(i);
    const Eigen::MatrixXd Jv = test::point_jacobian(m, layout, q, body, vec(b.com3));
    const Eigen::MatrixXd Jw = test::angular_jacobian(m, layout, q, body);
    const Eigen::Matrix3d inertia = pose.rotation[i] * test::inertia_matrix(b.inertia3) * pose.rotation[i].transpose();
    const Eigen::Vector3d w = Jw * v;
    o.M += b.mass * Jv.transpose() * Jv + Jw.transpose() * inertia * Jw;
    o.F += b.mass * Jv.transpose() * test::point_bias_acceleration(m, layout, q, v, body, vec(b.com3)) +
           Jw.transpose() * (inertia * test::angular_bias_acceleration(m, layout, q, v, body) + w.cross(inertia * w));
    o.Q += Jv.transpose() * (b.mass * g);
  }
  for (const ir::Load& load : m.loads) {
    const ir::Body& b = m.bodies[load.body];
    if (!load.window.contains(t)) continue;
    if (load.type == ir::LoadType::kForce) {
      const Eigen::Vector3d f(load.force3[0].evaluate(t), load.force3[1].evaluate(t), load.force3[2].evaluate(t));
      o.Q += test::point_jacobian(m, layout, q, load.body, vec(b.points[load.point].position3)).transpose() * f;
    } else if (load.type == ir::LoadType::kTorque) {
      const Eigen::Vector3d tau(load.torque3[0].evaluate(t), load.torque3[1].evaluate(t), load.torque3[2].evaluate(t));
      o.Q += test::angular_jacobian(m, layout, q, load.body).transpose() * tau;
    } else {
      const int k = layout.first_position[load.body], j = layout.first_velocity[load.body];
      o.Q[j] += -load.stiffness * (q[k] - load.rest) - load.damping * v[j];
    }
  }
  return o;
}

void expect_close(const Eigen::MatrixXd& got, const Eigen::MatrixXd& want, double tol, const char* what) {
  const double scale = std::max(1.0, want.cwiseAbs().maxCoeff());
  EXPECT_LT((got - want).cwiseAbs().maxCoeff() / scale, tol) << what << "\ngot:\n" << got << "\nwant:\n" << want;
}

void check_tree(const ir::Model& m, std::mt19937& rng, int trials) {
  const ir::CoordinateLayout layout = ir::coordinate_layout(m);
  const LoadedSolver solver = load_solver(m, /*quiet=*/true);
  const mbfe_model_v1& k = *solver.model;
  const int nq = layout.num_positions, nv = layout.num_velocities;
  ASSERT_EQ(k.dimension, 3);
  ASSERT_EQ(k.num_coordinates, nq);
  ASSERT_EQ(k.num_velocities, nv);
  ASSERT_NE(k.position_derivative, nullptr);
  ASSERT_NE(k.point_position3, nullptr);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int trial = 0; trial < trials; ++trial) {
    Eigen::VectorXd q, v;
    random_state(rng, m, layout, q, v);
    const double t = trial % 2 ? 0.7 : 0.3;  // each time-windowed load on in one, off in the other
    const Oracle o = oracle(m, layout, q, v, t);
    // NaN first: an entry the kernel leaves unwritten fails the comparison.
    RowMajor M = RowMajor::Constant(nv, nv, nan), M_fused = RowMajor::Constant(nv, nv, nan);
    Eigen::VectorXd F(nv), Q(nv), F_fused(nv), Q_fused(nv);
    k.mass_matrix(q.data(), M.data());
    k.inertial_forces(q.data(), v.data(), F.data());
    k.generalized_forces(q.data(), v.data(), t, Q.data());
    k.dynamics(q.data(), v.data(), t, M_fused.data(), F_fused.data(), Q_fused.data());
    expect_close(M, o.M, kJacobianTol, "M");
    expect_close(F, o.F, kBiasTol, "F");
    expect_close(Q, o.Q, kJacobianTol, "Q");
    for (int r = 0; r < nv; ++r)
      for (int c = 0; c < nv; ++c) EXPECT_EQ(M(r, c), M(c, r)) << "M not symmetric at " << r << ", " << c;
    expect_close(M_fused, M, kSameArithmeticTol, "M: dynamics vs mass_matrix");
    expect_close(F_fused, F, kSameArithmeticTol, "F: dynamics vs inertial_forces");
    expect_close(Q_fused, Q, kSameArithmeticTol, "Q: dynamics vs generalized_forces");

    // Points, and q' = G(q) v against d/ds (q (+) s v).
    for (std::size_t b = 0; b < m.bodies.size(); ++b) {
      Eigen::Vector3d xyz;
      k.point_position3(q.data(), static_cast<int>(b), 0, xyz.data());
      expect_close(xyz, test::spatial_point(m, layout, q, static_cast<int>(b), vec(m.bodies[b].points[0].position3)),
                   kSameArithmeticTol, "point");
    }
    Eigen::VectorXd qdot = Eigen::VectorXd::Constant(nq, nan);
    k.position_derivative(q.data(), v.data(), qdot.data());
    const double h = test::kFirstStep;
    const Eigen::VectorXd qdot_oracle =
        (test::step_positions(m, layout, q, h * v) - test::step_positions(m, layout, q, -h * v)) / (2 * h);
    expect_close(qdot, qdot_oracle, kJacobianTol, "qdot");
  }
}

TEST(GeneratedSpatialDynamics, RevolutePrismaticTreesMatchOracle) {
  std::mt19937 rng(20240611);
  for (int bodies : {1, 3, 5}) {
    SCOPED_TRACE(bodies);
    check_tree(frontend::parse_model_text(random_spatial_tree_yaml(rng, bodies, false), "tree.yaml"), rng, 10);
  }
}

TEST(GeneratedSpatialDynamics, QuaternionJointsMatchOracle) {
  std::mt19937 rng(77);
  for (int bodies : {3, 5}) {
    SCOPED_TRACE(bodies);
    check_tree(frontend::parse_model_text(random_spatial_tree_yaml(rng, bodies, true), "tree.yaml"), rng, 10);
  }
}

}  // namespace
}  // namespace mbfe
