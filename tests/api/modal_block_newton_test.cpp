// The Newton matrix of a model with low-rank adjusted beams, solved two
// ways: with the beams as blocks of known inverse and a Woodbury correction
// over the coupled rows (modal_block_solver.h), and with the sparse LU and
// the Woodbury correction over the kept modes, tested before against eq (27).
// The two-span catenary: slack droppers, a contact pressing from below, a
// driven carriage. Both with the policy cap (blocks on B = M) and the policy
// mass (blocks on B = K, whose modal values are the modes' stiffness).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <string>

#include "api/mbfe.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/coupled/coupled_implicit_system.h"
#include "tests/support/two_span_catenary.h"

namespace mbfe {
namespace {

// The two forms solve the same matrix in another order; its condition
// number under the static weight (c_q = 1e8) is near 1e7: 3e-8 of the
// largest entry measured there (1e-15 at generalized-alpha's weights), and
// 1e-7 leaves room. A wrong coupling term is off by its whole size.
constexpr double kSameSolutionTol = 1e-7;

class ModalBlockNewton : public testing::TestWithParam<std::string> {};

TEST_P(ModalBlockNewton, BlocksSolveAsTheWoodburyOverTheKeptModes) {
  const Model model = Model::parse(
      test::with_wire_adjustment("{omega_limit: 800.0, margin: 0.1, policy: " + GetParam() + "}"), "blocks.yaml");
  auto dyn_blocks = model.assembled().make_dynamics(true);
  auto dyn_modes = model.assembled().make_dynamics(true);
  runtime::CoupledImplicitSystem blocks(dyn_blocks);
  runtime::CoupledImplicitSystem modes(dyn_modes, /*modal_blocks=*/false);
  ASSERT_TRUE(blocks.uses_modal_blocks());
  ASSERT_FALSE(modes.uses_modal_blocks());
  Eigen::VectorXd q, qd;
  model.assembled().initial_coordinates(q, qd);
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Wires lowered a little and shaken: the contact presses, some droppers are slack.
  for (int i = dyn_blocks->nb(); i < q.size(); ++i) {
    q[i] = -1e-3 + 1e-3 * u(rng);
    qd[i] = 1e-2 * u(rng);
  }
  const Eigen::VectorXd a = Eigen::VectorXd::Zero(q.size()), lambda;
  const double h = 2e-4;
  // The static start's weight, and generalized-alpha's (beta h^2, gamma h).
  for (const auto& [c_q, c_v] : {std::pair{1e8, 0.0}, std::pair{0.3 * h * h, 0.6 * h}}) {
    blocks.factorize(0.0, q, qd, a, lambda, c_q, c_v);
    modes.factorize(0.0, q, qd, a, lambda, c_q, c_v);
    for (int trial = 0; trial < 3; ++trial) {
      Eigen::VectorXd r(q.size()), da_blocks, da_modes, dl;
      for (int i = 0; i < r.size(); ++i) r[i] = u(rng);
      const Eigen::VectorXd c;
      blocks.solve(r, c, da_blocks, dl);
      modes.solve(r, c, da_modes, dl);
      // The driven carriage's row is a_d = r_d: exact in the block form,
      // which leaves that row out of the correction; the Woodbury over the
      // kept modes mixes 3e-8 of the stiff rows into it under the static weight.
      const std::vector<int>& driven = dyn_blocks->driven();
      ASSERT_EQ(driven.size(), 1u);
      EXPECT_EQ(da_blocks[driven[0]], r[driven[0]]);
      const Eigen::VectorXd rest = da_modes.tail(da_modes.size() - 1);
      const double scale = rest.cwiseAbs().maxCoeff();
      ASSERT_GT(scale, 0.0);
      EXPECT_LT((da_blocks.tail(rest.size()) - rest).cwiseAbs().maxCoeff(), kSameSolutionTol * scale)
          << "c_q " << c_q << ", c_v " << c_v << ", trial " << trial;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Policies, ModalBlockNewton, testing::Values("cap", "mass"),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace mbfe
