// Generated M, F, Q of random planar trees (revolute and prismatic joints,
// branches, every kind of load) against an independent numerical oracle
// written straight from the conventions of the model format:
//   M = sum_i m_i J_i^T J_i + I_i Jw_i^T Jw_i      (J_i: centre-of-mass Jacobian)
//   F = sum_i m_i J_i^T a_i(q, qd, qdd = 0)          (a_i: its velocity-product acceleration)
//   Q = sum_i J_i^T m_i g + J_P^T f + Jw^T tau - k (q - rest) - c qd
// with J and a from finite differences of the forward kinematics.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "frontend/parse_model.h"
#include "api/solver_cache.h"

namespace mbfe {
namespace {

// Central differences of O(1) positions: h = 1e-5 gives truncation ~1e-10 and
// round-off ~1e-11 for first derivatives; the second derivative uses h = 1e-4
// (truncation ~1e-8, round-off ~1e-8). Relative agreement is checked to:
constexpr double kJacobianTol = 1e-7;
constexpr double kBiasTol = 1e-5;
// Two kernels doing the same arithmetic in another order differ by a few ulps
// of the largest entry; 1e-13 of it is ~500 ulps.
constexpr double kSameArithmeticTol = 1e-13;

struct Pose {
  std::vector<double> angle;
  std::vector<Eigen::Vector2d> origin;
};

Eigen::Matrix2d rot(double a) {
  Eigen::Matrix2d r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return r;
}

Pose forward(const ir::Model& m, const Eigen::VectorXd& q) {
  Pose pose;
  for (std::size_t i = 0; i < m.bodies.size(); ++i) {
    const auto& b = m.bodies[i];
    const double pa = b.parent < 0 ? 0.0 : pose.angle[b.parent];
    const Eigen::Vector2d po = b.parent < 0 ? Eigen::Vector2d::Zero() : pose.origin[b.parent];
    Eigen::Vector2d at(b.joint.at[0], b.joint.at[1]);
    if (b.joint.type == ir::JointType::kPrismatic) at += q[i] * Eigen::Vector2d(b.joint.axis[0], b.joint.axis[1]);
    pose.origin.push_back(po + rot(pa) * at);
    pose.angle.push_back(b.joint.type == ir::JointType::kRevolute ? pa + q[i] : pa);
  }
  return pose;
}

Eigen::Vector2d point(const ir::Model& m, const Eigen::VectorXd& q, int body, const ir::Vec2& local) {
  const Pose pose = forward(m, q);
  return pose.origin[body] + rot(pose.angle[body]) * Eigen::Vector2d(local[0], local[1]);
}

Eigen::MatrixXd point_jacobian(const ir::Model& m, const Eigen::VectorXd& q, int body, const ir::Vec2& local) {
  constexpr double h = 1e-5;
  Eigen::MatrixXd J(2, q.size());
  for (int k = 0; k < q.size(); ++k) {
    Eigen::VectorXd qp = q, qm = q;
    qp[k] += h;
    qm[k] -= h;
    J.col(k) = (point(m, qp, body, local) - point(m, qm, body, local)) / (2 * h);
  }
  return J;
}

Eigen::RowVectorXd angle_jacobian(const ir::Model& m, int body) {
  Eigen::RowVectorXd Jw = Eigen::RowVectorXd::Zero(m.bodies.size());
  for (int a = body; a >= 0; a = m.bodies[a].parent)
    if (m.bodies[a].joint.type == ir::JointType::kRevolute) Jw[a] = 1.0;
  return Jw;
}

// Acceleration of a body point when qdd = 0: d^2/ds^2 p(q + s qd) at s = 0.
Eigen::Vector2d bias_acceleration(const ir::Model& m, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                  int body, const ir::Vec2& local) {
  constexpr double h = 1e-4;
  return (point(m, q + h * qd, body, local) - 2 * point(m, q, body, local) + point(m, q - h * qd, body, local)) /
         (h * h);
}

std::string random_tree_yaml(std::mt19937& rng, int bodies) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.1, 2.0);
  std::ostringstream y;
  y.precision(17);
  y << "model: random_tree\ngravity: [" << u(rng) << ", -9.81]\nbodies:\n";
  for (int i = 0; i < bodies; ++i) {
    const int parent = i == 0 ? -1 : static_cast<int>(rng() % i);
    const bool prismatic = rng() % 3 == 0;
    y << "  - name: b" << i << "\n    parent: " << (parent < 0 ? "ground" : "b" + std::to_string(parent)) << "\n";
    if (prismatic)
      y << "    joint: {type: prismatic, axis: [" << u(rng) << ", " << u(rng) << "], at: [" << u(rng) << ", " << u(rng)
        << "]}\n";
    else
      y << "    joint: {type: revolute, at: [" << u(rng) << ", " << u(rng) << "]}\n";
    y << "    mass: " << pos(rng) << "\n    inertia: " << pos(rng) * 0.1 << "\n    com: [" << u(rng) << ", "
      << u(rng) << "]\n    points: {p: [" << u(rng) << ", " << u(rng) << "]}\n";
  }
  y << "loads:\n";
  for (int i = 0; i < bodies; ++i) {
    y << "  - {type: force, body: b" << i << ", point: p, value: [" << u(rng) << ", " << u(rng) << "]}\n";
    y << "  - {type: torque, body: b" << i << ", value: " << u(rng) << "}\n";
    y << "  - {type: spring_damper, joint: b" << i << ", stiffness: " << pos(rng) << ", damping: " << pos(rng)
      << ", rest: " << u(rng) << "}\n";
  }
  return y.str();
}

void expect_close(const Eigen::MatrixXd& got, const Eigen::MatrixXd& want, double tol, const char* what) {
  const double scale = std::max(1.0, want.cwiseAbs().maxCoeff());
  EXPECT_LT((got - want).cwiseAbs().maxCoeff() / scale, tol) << what << "\ngot:\n" << got << "\nwant:\n" << want;
}

TEST(GeneratedRigidDynamics, MatchesNumericalOracleOnRandomTrees) {
  std::mt19937 rng(424242);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), rate(-2.0, 2.0);
  for (int bodies : {1, 3, 6}) {
    const ir::Model m = frontend::parse_model_text(random_tree_yaml(rng, bodies), "random_tree.yaml");
    const LoadedSolver solver = load_solver(m, /*quiet=*/true);
    const int n = bodies;
    for (int trial = 0; trial < 30; ++trial) {
      Eigen::VectorXd q(n), qd(n);
      for (int i = 0; i < n; ++i) {
        q[i] = angle(rng);
        qd[i] = rate(rng);
      }
      Eigen::MatrixXd M_oracle = Eigen::MatrixXd::Zero(n, n);
      Eigen::VectorXd F_oracle = Eigen::VectorXd::Zero(n), Q_oracle = Eigen::VectorXd::Zero(n);
      const Eigen::Vector2d g(m.gravity[0], m.gravity[1]);
      for (int i = 0; i < n; ++i) {
        const auto& b = m.bodies[i];
        const Eigen::MatrixXd J = point_jacobian(m, q, i, b.com);
        const Eigen::RowVectorXd Jw = angle_jacobian(m, i);
        M_oracle += b.mass * J.transpose() * J + b.inertia * Jw.transpose() * Jw;
        F_oracle += b.mass * J.transpose() * bias_acceleration(m, q, qd, i, b.com);
        Q_oracle += J.transpose() * (b.mass * g);
      }
      for (const auto& load : m.loads) {
        const auto& b = m.bodies[load.body];
        if (load.type == ir::LoadType::kForce)
          Q_oracle += point_jacobian(m, q, load.body, b.points[load.point].position).transpose() *
                      Eigen::Vector2d(load.force[0].evaluate(0.0), load.force[1].evaluate(0.0));
        else if (load.type == ir::LoadType::kTorque)
          Q_oracle += angle_jacobian(m, load.body).transpose() * load.torque.evaluate(0.0);
        else
          Q_oracle[load.body] += -load.stiffness * (q[load.body] - load.rest) - load.damping * qd[load.body];
      }
      Eigen::MatrixXd M(n, n);
      Eigen::VectorXd F(n), Q(n);
      // NaN first: an entry the kernel leaves unwritten fails the comparison.
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> M_rows =
          Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>::Constant(
              n, n, std::numeric_limits<double>::quiet_NaN());
      solver.model->mass_matrix(q.data(), M_rows.data());
      M = M_rows;
      solver.model->inertial_forces(q.data(), qd.data(), F.data());
      solver.model->generalized_forces(q.data(), qd.data(), 0.0, Q.data());
      expect_close(M, M_oracle, kJacobianTol, "M");
      expect_close(F, F_oracle, kBiasTol, "F");
      expect_close(Q, Q_oracle, kJacobianTol, "Q");
    }
  }
}

// A fixed tree with both joint types and branches (so M has zero entries for
// bodies on different branches, and the emitted assembly loop walks a parent
// table instead of counting down). Checks M of mass_matrix and M, F, Q of the
// fused dynamics kernel against the oracle; M starts filled with NaN so an
// entry the kernels forget to write fails.
constexpr const char* kBranchedMixedTree = R"(model: branched_mixed
gravity: [0.3, -9.81]
bodies:
  - {name: cart, parent: ground, joint: {type: prismatic, axis: [1, 0.2], at: [0.1, -0.3]}, mass: 2.0, inertia: 0.1, com: [0.05, 0.02]}
  - {name: arm, parent: cart, joint: {type: revolute, at: [0.2, 0.1]}, mass: 1.2, inertia: 0.08, com: [0.4, -0.05]}
  - {name: slider, parent: arm, joint: {type: prismatic, axis: [0.6, -0.8], at: [0.7, 0.1]}, mass: 0.7, inertia: 0.02, com: [0.1, 0.1]}
  - {name: hand, parent: slider, joint: {type: revolute, at: [0.15, 0]}, mass: 0.4, inertia: 0.01, com: [0.2, 0.03]}
  - {name: elbow, parent: arm, joint: {type: revolute, at: [0.9, -0.1]}, mass: 0.9, inertia: 0.05, com: [0.3, 0.0]}
  - {name: wheel, parent: cart, joint: {type: revolute, at: [-0.4, 0]}, mass: 0.5, inertia: 0.03, com: [0, 0.1]}
  - {name: pole, parent: ground, joint: {type: revolute, at: [1.5, 0.5]}, mass: 1.0, inertia: 0.07, com: [0.25, 0.0]}
  - {name: rider, parent: elbow, joint: {type: prismatic, axis: [0, 1], at: [0.5, 0]}, mass: 0.3, inertia: 0.004, com: [0.02, -0.01]}
)";

TEST(GeneratedRigidDynamics, BranchedMixedTreeMatchesOracleInBothKernels) {
  const ir::Model m = frontend::parse_model_text(kBranchedMixedTree, "branched_mixed.yaml");
  const int n = static_cast<int>(m.bodies.size());
  // What the test is for: both joint types, and bodies on different branches.
  int prismatic = 0, unrelated_pairs = 0;
  for (const auto& b : m.bodies) prismatic += b.joint.type == ir::JointType::kPrismatic;
  for (int r = 0; r < n; ++r)
    for (int c = r + 1; c < n; ++c) {
      bool related = false;
      for (int a = c; a >= 0; a = m.bodies[a].parent) related = related || a == r;
      unrelated_pairs += !related;
    }
  ASSERT_GE(prismatic, 2);
  ASSERT_LT(prismatic, n);
  ASSERT_GE(unrelated_pairs, 5);

  const LoadedSolver solver = load_solver(m, /*quiet=*/true);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), rate(-2.0, 2.0);
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q(n), qd(n);
    for (int i = 0; i < n; ++i) {
      q[i] = angle(rng);
      qd[i] = rate(rng);
    }
    Eigen::MatrixXd M_oracle = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd F_oracle = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) {
      const auto& b = m.bodies[i];
      const Eigen::MatrixXd J = point_jacobian(m, q, i, b.com);
      const Eigen::RowVectorXd Jw = angle_jacobian(m, i);
      M_oracle += b.mass * J.transpose() * J + b.inertia * Jw.transpose() * Jw;
      F_oracle += b.mass * J.transpose() * bias_acceleration(m, q, qd, i, b.com);
    }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    RowMajor M = RowMajor::Constant(n, n, nan);
    solver.model->mass_matrix(q.data(), M.data());
    expect_close(M, M_oracle, kJacobianTol, "M (mass_matrix)");
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) EXPECT_EQ(M(r, c), M(c, r)) << "M not symmetric at " << r << ", " << c;

    RowMajor M_fused = RowMajor::Constant(n, n, nan);
    Eigen::VectorXd F(n), Q(n), F_fused(n), Q_fused(n);
    solver.model->inertial_forces(q.data(), qd.data(), F.data());
    solver.model->generalized_forces(q.data(), qd.data(), 0.0, Q.data());
    solver.model->dynamics(q.data(), qd.data(), 0.0, M_fused.data(), F_fused.data(), Q_fused.data());
    expect_close(M_fused, M_oracle, kJacobianTol, "M (dynamics)");
    expect_close(F_fused, F_oracle, kBiasTol, "F (dynamics)");
    // The fused kernel is the same arithmetic as the separate ones, up to the
    // order CSE puts it in.
    expect_close(M_fused, M, kSameArithmeticTol, "M: dynamics vs mass_matrix");
    expect_close(F_fused, F, kSameArithmeticTol, "F: dynamics vs inertial_forces");
    expect_close(Q_fused, Q, kSameArithmeticTol, "Q: dynamics vs generalized_forces");
  }
}

}  // namespace
}  // namespace mbfe
