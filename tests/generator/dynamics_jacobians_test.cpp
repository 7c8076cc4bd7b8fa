// The closed-form tangents of the generated `dynamics_jacobians` kernel
// against central differences of the generated `dynamics` kernel
// (tau = M a + F - Q), at seeded random states of the shipped coupled models:
// revolute and prismatic joints, a branched tree, gravity, spring-dampers and
// a driven joint's coordinate among them.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>
#include <string>
#include <vector>

#include "api/mbfe.h"

namespace mbfe {
namespace {

// Central differences with step h err by ~h^2 |tau'''| + eps |tau| / h; at
// h = 1e-5 on O(1) coordinates both are ~1e-10 of the entries' scale.
constexpr double kDifferenceStep = 1e-5;
constexpr double kRelativeTol = 1e-6;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::VectorXd tau(const mbfe_model_v1& m, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                    const Eigen::VectorXd& a, double t) {
  const int n = m.num_coordinates;
  RowMajor M(n, n);
  Eigen::VectorXd F(n), Q(n);
  m.dynamics(q.data(), qd.data(), t, M.data(), F.data(), Q.data());
  return M * a + F - Q;
}

void check_model(const std::string& path) {
  SCOPED_TRACE(path);
  const Model model = Model::load(std::string(MBFE_SOURCE_DIR) + "/" + path);
  const mbfe_model_v1& m = *model.solver();
  ASSERT_NE(m.dynamics_jacobians, nullptr);
  const int n = m.num_coordinates;
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd q(n), qd(n), a(n);
    for (int i = 0; i < n; ++i) {
      q[i] = u(rng);
      qd[i] = 2.0 * u(rng);
      a[i] = 5.0 * u(rng);
    }
    const double t = 0.3 + 0.1 * trial;
    RowMajor K(n, n), C(n, n);
    m.dynamics_jacobians(q.data(), qd.data(), a.data(), t, K.data(), C.data());
    RowMajor K_fd(n, n), C_fd(n, n);
    for (int j = 0; j < n; ++j) {
      for (int pass = 0; pass < 2; ++pass) {
        Eigen::VectorXd qp = q, qm = q, vp = qd, vm = qd;
        (pass == 0 ? qp : vp)[j] += kDifferenceStep;
        (pass == 0 ? qm : vm)[j] -= kDifferenceStep;
        const Eigen::VectorXd col = (tau(m, qp, vp, a, t) - tau(m, qm, vm, a, t)) / (2.0 * kDifferenceStep);
        (pass == 0 ? K_fd : C_fd).col(j) = col;
      }
    }
    const double scale = 1.0 + std::max(K_fd.cwiseAbs().maxCoeff(), C_fd.cwiseAbs().maxCoeff());
    EXPECT_LT((K - K_fd).cwiseAbs().maxCoeff(), kRelativeTol * scale) << "K\n" << K << "\nvs\n" << K_fd;
    EXPECT_LT((C - C_fd).cwiseAbs().maxCoeff(), kRelativeTol * scale) << "C\n" << C << "\nvs\n" << C_fd;
  }
}

TEST(DynamicsJacobians, MatchCentralDifferencesOfTheDynamicsKernel) {
  for (const char* file : {"paper_platform.yaml", "double_pendulum_beam.yaml", "bridge_moving_mass.yaml",
                           "bridge_two_axle_vehicle.yaml"})
    check_model(std::string("models/") + file);
}

// Outputs of the rigid kernels that share a compound part (two wheels of one
// body): the tangents are derived from the outputs, not from the printed
// kernels' common-subexpression temporaries.
TEST(DynamicsJacobians, OutputsSharingAPartOfTheirExpressions) {
  check_model("tests/fuzz/regressions/cse_temporary_in_rigid_outputs.yaml");
}

TEST(DynamicsJacobians, RigidOnlyModelsGoWithout) {
  // Rigid models never take the coupled implicit path; their kernels stay
  // small (generate_solver.cpp).
  const Model model = Model::load(std::string(MBFE_SOURCE_DIR) + "/models/chain_5.yaml");
  EXPECT_EQ(model.solver()->dynamics_jacobians, nullptr);
}

}  // namespace
}  // namespace mbfe
