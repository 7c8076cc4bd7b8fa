// A joined structure (two tensioned wires and three taut droppers, one
// adjustment block of scope 'joined') against the dense generalized
// eigenproblem of its stacked matrices, written out here:
//   K_s = diag(K_1, K_2) + sum_l k_l g_l g_l^T,  M_s = diag(M_1, M_2),
// g_l the difference of the shape-function rows at the link's two ends.
// Its modes' frequencies, M-orthonormality and modal damping phi^T C_s phi.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/damping/beam_model.h"
#include "runtime/fem/beam_system.h"
#include "runtime/structure/joined_structures.h"

namespace mbfe::runtime {
namespace {

// Two dense symmetric eigensolvers on 80 DOF with frequencies spanning 1e3:
// ~1e-10 relative with a margin.
constexpr double kFrequencyTol = 1e-8;
constexpr double kOrthonormalTol = 1e-9;
constexpr double kModalDampingTol = 1e-8;

constexpr double kSpan = 10.0;
constexpr int kElements = 20;  // 0.5 m
constexpr double kDropperStiffness = 1e5;  // N/m
const std::vector<double> kDropperAt = {2.5, 5.0, 7.5};

ir::Beam wire(const std::string& name, double tension) {
  ir::Beam b;
  b.name = name;
  b.length = kSpan;
  b.elements = kElements;
  b.area = 1.2e-4;
  b.second_moment = 1e-9;
  b.youngs_modulus = 1e11;
  b.density = 8900.0;
  b.tension = tension;
  b.rayleigh_alpha = 0.05;
  b.rayleigh_beta = 1e-4;
  b.supports = {{0.0, ir::SupportType::kPinned, -1, {}}, {kSpan, ir::SupportType::kPinned, -1, {}}};
  b.adjustment.present = true;
  b.adjustment.policy = ir::AdjustmentPolicy::kCap;
  b.adjustment.scope = ir::AdjustmentScope::kJoined;
  b.adjustment.omega_limit = 300.0;
  return b;
}

ir::Model two_wires() {
  ir::Model m;
  m.source_path = "wires.yaml";
  m.beams = {wire("contact", 20000.0), wire("messenger", 15000.0)};
  for (std::size_t i = 0; i < kDropperAt.size(); ++i) {
    ir::Link l;
    l.name = "dropper" + std::to_string(i);
    l.a = {0, kDropperAt[i]};
    l.b = {1, kDropperAt[i]};
    l.stiffness = kDropperStiffness;
    m.links.push_back(l);
  }
  return m;
}

TEST(JoinedStructures, ModesAreThoseOfTheDenseStackedStructure) {
  const ir::Model model = two_wires();
  const BeamModel beams = analyse_beams(model);
  const std::vector<JoinedStructure> joined = joined_structures(model, beams, 1000);
  ASSERT_EQ(joined.size(), 1u);
  const JoinedStructure& s = joined[0];
  EXPECT_EQ(s.beams, (std::vector<int>{0, 1}));
  EXPECT_EQ(s.links, (std::vector<int>{0, 1, 2}));
  const int n = beams.dof;
  ASSERT_EQ(s.dof, n);

  // The stacked matrices, dense.
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n), K = M, C = M;
  for (const BeamPart& part : beams.beams) {
    const int o = part.offset, nb = static_cast<int>(part.system.K.rows());
    M.block(o, o, nb, nb) = Eigen::MatrixXd(part.system.M);
    K.block(o, o, nb, nb) = Eigen::MatrixXd(part.system.K);
    C.block(o, o, nb, nb) = Eigen::MatrixXd(part.system.C);
  }
  for (const ir::Link& l : model.links) {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
    for (const auto& [end, sign] : {std::pair{l.b, 1.0}, std::pair{l.a, -1.0}}) {
      const BeamPart& part = beams.beams[static_cast<std::size_t>(end.beam)];
      const BeamPointWeights w = point_weights(part.system, end.at);
      for (int j = 0; j < 4; ++j)
        if (w.free_index[j] >= 0) g[part.offset + w.free_index[j]] += sign * w.w[j];
    }
    K += l.stiffness * g * g.transpose();
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(K, M);
  ASSERT_EQ(dense.info(), Eigen::Success);
  const Eigen::VectorXd omega_dense = dense.eigenvalues().cwiseSqrt();

  ASSERT_EQ(s.basis.omega.size(), n);  // every mode (below the dense limit)
  for (int j = 0; j < n; ++j)
    EXPECT_NEAR(s.basis.omega[j], omega_dense[j], kFrequencyTol * omega_dense[j]) << "mode " << j;
  const Eigen::MatrixXd& phi = s.basis.phi;
  EXPECT_LT((phi.transpose() * M * phi - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(), kOrthonormalTol);
  ASSERT_EQ(s.original.size(), static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const double c = phi.col(j).dot(C * phi.col(j));
    EXPECT_NEAR(s.original[j].c, c, kModalDampingTol * std::max(1.0, std::abs(c))) << "mode " << j;
    EXPECT_NEAR(s.original[j].k, omega_dense[j] * omega_dense[j], kFrequencyTol * omega_dense[j] * omega_dense[j]);
  }
  // The droppers stiffen the pair: the lowest joined mode is above either wire's own.
  EXPECT_GT(omega_dense[0], std::min(beams.beams[0].basis.omega[0], beams.beams[1].basis.omega[0]));
  EXPECT_EQ(joined_name(model, s.beams), "'contact+messenger'");
}

}  // namespace
}  // namespace mbfe::runtime
