// The adjusted structure's operator (runtime/structure/low_rank_structure.h)
// against dense references built here from every mode of a small beam:
// M_adj, C_adj, K_adj = (M Phi) diag(m, c, k) (M Phi)^T (eq (27) with the
// policy's modal values), their products, inverses and the free
// acceleration by dense solves. Both bases: M (policy cap, eq (27)) and K
// (the policy mass, built by hand here). Ranges spread over a longer q_c.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "runtime/damping/modal_adjustment.h"
#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_analysis.h"
#include "runtime/structure/adjusted_parts.h"
#include "runtime/structure/low_rank_structure.h"

namespace mbfe::runtime {
namespace {

// Completeness M Phi Phi^T M = M holds to the dense eigen-solver's accuracy,
// ~1e-12 of the largest entry for 16 DOF; the operators sum terms up to
// k* |M| against results of |K|: 1e-9 relative leaves three orders over that.
constexpr double kDenseTol = 1e-9;

/// A short version of the paper beam: 8 elements, pinned-pinned, 16 DOF.
ir::Beam small_beam() {
  ir::Beam b;
  b.name = "b";
  b.length = 1.0;
  b.elements = 8;
  b.area = 25e-6;
  b.second_moment = 0.005 * 0.005 * 0.005 * 0.005 / 12.0;
  b.youngs_modulus = 2.1e11;
  b.density = 7860;
  b.supports = {{0.0, ir::SupportType::kPinned, 0, {}}, {1.0, ir::SupportType::kPinned, 8, {}}};
  b.rayleigh_alpha = 3e-3;
  b.rayleigh_beta = 1.5e-4;
  return b;
}

ir::Adjustment cap(double omega_limit) {
  ir::Adjustment a;
  a.present = true;
  a.policy = ir::AdjustmentPolicy::kCap;
  a.omega_limit = omega_limit;
  a.margin = 0.1;
  return a;
}

struct Fixture {
  BeamSystem sys = assemble_beam(small_beam(), {0.0, -9.81});
  ModalBasis basis = modal_analysis(sys);
  std::vector<ModalDynamics> original = rayleigh_modes(basis.omega, sys.rayleigh_alpha, sys.rayleigh_beta);
  // 8 elements: omega up to ~1e5; a limit of 1e4 caps about half the modes.
  AdjustedModes adjusted = adjust_modes(original, cap(1e4));
  int n() const { return static_cast<int>(sys.M.rows()); }
  /// (M Phi) diag(values) (M Phi)^T over every mode.
  Eigen::MatrixXd eq27(const Eigen::VectorXd& values) const {
    const Eigen::MatrixXd u = sys.M * basis.phi;
    return u * values.asDiagonal() * u.transpose();
  }
};

Eigen::VectorXd modal(const AdjustedModes& a, double ModalDynamics::*field) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(a.modes.size()));
  for (std::size_t j = 0; j < a.modes.size(); ++j) out[static_cast<Eigen::Index>(j)] = a.modes[j].*field;
  return out;
}

/// The policy mass by hand: capped modes keep k_j and get m_j = k_j / k*,
/// c_j = m_j c*; kept modes unchanged. Base K.
LowRankStructure::Parts mass_parts(const Fixture& f, std::vector<LowRankStructure::Range> ranges) {
  const AdjustedModes& a = f.adjusted;
  int kept = 0;
  while (kept < static_cast<int>(a.change.size()) && a.change[kept] != ModeChange::kAdjusted) ++kept;
  const double ks = a.k_star, cs = a.c_star;
  LowRankStructure::Parts p;
  p.name = "mass";
  p.ranges = std::move(ranges);
  p.M = f.sys.M;
  p.K = f.sys.K;
  p.P = f.sys.P;
  p.base = LowRankStructure::Base::kStiffness;
  p.phi = f.basis.phi.leftCols(kept);
  p.k = f.basis.omega.head(kept).array().square().matrix();
  p.mass = {1.0 / ks, (1.0 - p.k.array() / ks).matrix()};
  p.damping = {cs / ks, Eigen::VectorXd(kept)};
  p.stiffness = {1.0, Eigen::VectorXd::Zero(kept)};
  for (int j = 0; j < kept; ++j) p.damping.d[j] = a.modes[j].c - cs * p.k[j] / ks;
  return p;
}

/// The mass policy's modal values over every mode.
void mass_modal(const Fixture& f, Eigen::VectorXd& m, Eigen::VectorXd& c, Eigen::VectorXd& k) {
  const int n = f.n();
  m.resize(n);
  c.resize(n);
  k.resize(n);
  for (int j = 0; j < n; ++j) {
    k[j] = f.basis.omega[j] * f.basis.omega[j];
    const bool capped = f.adjusted.change[j] == ModeChange::kAdjusted;
    m[j] = capped ? k[j] / f.adjusted.k_star : 1.0;
    c[j] = capped ? m[j] * f.adjusted.c_star : f.adjusted.modes[j].c;
  }
}

double rel(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

TEST(LowRankStructure, CapMatricesEqualDenseEq27) {
  const Fixture f;
  ASSERT_GT(f.adjusted.adjusted, 2);
  ASSERT_LT(f.adjusted.adjusted, 14);
  const LowRankStructure s(adjusted_parts("b", {{0, f.n()}}, f.sys.M, f.sys.K, f.sys.P, f.basis, f.adjusted));
  EXPECT_EQ(s.rank(), f.n() - f.adjusted.adjusted);  // only the kept modes
  EXPECT_FALSE(s.every_mode());
  EXPECT_LT(rel(s.dense(s.stiffness()), f.eq27(modal(f.adjusted, &ModalDynamics::k))), kDenseTol);
  EXPECT_LT(rel(s.dense(s.damping()), f.eq27(modal(f.adjusted, &ModalDynamics::c))), kDenseTol);
  EXPECT_LT(rel(s.dense(s.mass()), Eigen::MatrixXd(f.sys.M)), kDenseTol);
}

TEST(LowRankStructure, NothingAdjustedGivesBackTheOriginalMatrices) {
  const Fixture f;
  ir::Adjustment none;
  none.policy = ir::AdjustmentPolicy::kNone;
  const LowRankStructure s(
      adjusted_parts("b", {{0, f.n()}}, f.sys.M, f.sys.K, f.sys.P, f.basis, adjust_modes(f.original, none)));
  EXPECT_LT(rel(s.dense(s.stiffness()), Eigen::MatrixXd(f.sys.K)), kDenseTol);
  EXPECT_LT(rel(s.dense(s.damping()), Eigen::MatrixXd(f.sys.C)), kDenseTol);
}

TEST(LowRankStructure, MassPolicyMatricesEqualDenseEq27) {
  const Fixture f;
  const LowRankStructure s(mass_parts(f, {{0, f.n()}}));
  Eigen::VectorXd m, c, k;
  mass_modal(f, m, c, k);
  EXPECT_LT(rel(s.dense(s.mass()), f.eq27(m)), kDenseTol);
  EXPECT_LT(rel(s.dense(s.damping()), f.eq27(c)), kDenseTol);
  // The stiffness is the beam's own: the static compliance is exact.
  EXPECT_LT(rel(s.dense(s.stiffness()), Eigen::MatrixXd(f.sys.K)), kDenseTol);
}

// Every operation against the dense matrices, for both bases, on a structure
// whose coordinates sit at an offset inside a longer q_c.
void expect_operations_match(const LowRankStructure& s, int offset, int total) {
  const int n = s.size();
  const Eigen::MatrixXd Md = s.dense(s.mass()), Cd = s.dense(s.damping()), Kd = s.dense(s.stiffness());
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q(total), v(total), r(total), a(total), f = Eigen::VectorXd::Zero(total);
  for (int i = 0; i < total; ++i) {
    q[i] = 1e-3 * u(rng);
    v[i] = 1e-1 * u(rng);
    r[i] = u(rng);
    a[i] = 10.0 * u(rng);
  }
  LowRankStructure::Workspace ws = s.make_workspace();
  const auto mine = [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(x.segment(offset, n)); };
  // C v + K q, M a: added on its range only.
  s.add_internal_force(q.data(), v.data(), f.data(), ws);
  const Eigen::VectorXd force = Cd * mine(v) + Kd * mine(q);
  EXPECT_LT((mine(f) - force).norm(), kDenseTol * force.norm());
  EXPECT_EQ(f.head(offset).norm(), 0.0);
  EXPECT_EQ(f.tail(total - offset - n).norm(), 0.0);
  Eigen::VectorXd inertia = Eigen::VectorXd::Zero(total);
  s.add_inertia(a.data(), inertia.data(), ws);
  EXPECT_LT((mine(inertia) - Md * mine(a)).norm(), kDenseTol * (Md * mine(a)).norm());
  // The free acceleration against a dense solve, with loads r and without.
  Eigen::VectorXd acc = Eigen::VectorXd::Constant(total, 7.0);
  s.free_acceleration(q.data(), v.data(), r.data(), acc.data(), ws);
  const Eigen::VectorXd expected = Md.ldlt().solve(s.loads() + mine(r) - Cd * mine(v) - Kd * mine(q));
  EXPECT_LT((mine(acc) - expected).norm(), kDenseTol * expected.norm());
  EXPECT_EQ(acc[0], offset > 0 ? 7.0 : acc[0]);  // outside its range: untouched
  s.free_acceleration(q.data(), v.data(), nullptr, acc.data(), ws);
  const Eigen::VectorXd unloaded = Md.ldlt().solve(s.loads() - Cd * mine(v) - Kd * mine(q));
  EXPECT_LT((mine(acc) - unloaded).norm(), kDenseTol * unloaded.norm());
  // M_adj^-1 r.
  Eigen::VectorXd x;
  s.solve_mass(mine(r), x, ws);
  EXPECT_LT((Md * x - mine(r)).norm(), kDenseTol * mine(r).norm());
  // A combination's term, and apply() of it.
  const LowRankStructure::Term t = s.combination(1.0, 2e-3, 3e-7);
  Eigen::VectorXd y;
  s.apply(t, mine(q), y, ws);
  const Eigen::MatrixXd combined = Md + 2e-3 * Cd + 3e-7 * Kd;
  EXPECT_LT((y - combined * mine(q)).norm(), kDenseTol * (combined * mine(q)).norm());
}

TEST(LowRankStructure, CapOperationsMatchDense) {
  const Fixture f;
  const int offset = 5, total = f.n() + 11;
  expect_operations_match(
      LowRankStructure(adjusted_parts("b", {{offset, f.n()}}, f.sys.M, f.sys.K, f.sys.P, f.basis, f.adjusted)), offset,
      total);
}

TEST(LowRankStructure, MassPolicyOperationsMatchDense) {
  const Fixture f;
  const int offset = 3, total = f.n() + 4;
  expect_operations_match(LowRankStructure(mass_parts(f, {{offset, f.n()}})), offset, total);
}

TEST(LowRankStructure, MassPolicyKeepsTheStaticDeflectionAndTheCapsRoots) {
  const Fixture f;
  const LowRankStructure s(mass_parts(f, {{0, f.n()}}));
  // At rest under P the free acceleration vanishes exactly at K^-1 P.
  const Eigen::VectorXd q = Eigen::MatrixXd(f.sys.K).ldlt().solve(f.sys.P);
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(f.n());
  Eigen::VectorXd a(f.n());
  LowRankStructure::Workspace ws = s.make_workspace();
  s.free_acceleration(q.data(), v.data(), nullptr, a.data(), ws);
  // Its terms are of the size k* |q| (B^-1 r / mu_M and mu_K q / mu_M).
  EXPECT_LT(a.norm(), kDenseTol * f.adjusted.k_star * q.norm());
  // Its generalized eigenvalues (M_adj, C_adj, K_adj) are the cap's: the same
  // state-space roots as the cap, mode by mode.
  const LowRankStructure capped(adjusted_parts("b", {{0, f.n()}}, f.sys.M, f.sys.K, f.sys.P, f.basis, f.adjusted));
  const auto roots = [](const LowRankStructure& st) {
    const int n = st.size();
    const Eigen::MatrixXd Minv = Eigen::MatrixXd(st.dense(st.mass())).inverse();
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
    A.topRightCorner(n, n).setIdentity();
    A.bottomLeftCorner(n, n) = -Minv * st.dense(st.stiffness());
    A.bottomRightCorner(n, n) = -Minv * st.dense(st.damping());
    Eigen::VectorXd moduli = Eigen::EigenSolver<Eigen::MatrixXd>(A).eigenvalues().cwiseAbs();
    std::sort(moduli.data(), moduli.data() + moduli.size());
    return moduli;
  };
  const Eigen::VectorXd a_roots = roots(s), c_roots = roots(capped);
  // A dense non-symmetric eigenproblem with roots from 1e2 to 1.4e4, the
  // cap's root repeated once per capped mode (a multiple root the solver
  // spreads by ~1e-8 relative).
  constexpr double kRootTol = 1e-6;
  EXPECT_LT((a_roots - c_roots).cwiseAbs().maxCoeff(), kRootTol * c_roots.maxCoeff());
}

TEST(LowRankStructure, StackedRangesGatherAndScatter) {
  // Two ranges of 3 and 2 coordinates, the second before the first in q_c.
  LowRankStructure::Parts p;
  p.name = "two";
  p.ranges = {{6, 3}, {1, 2}};
  Eigen::MatrixXd m = Eigen::MatrixXd::Identity(5, 5) * 2.0;
  p.M = m.sparseView();
  p.K = p.M;
  p.P = Eigen::VectorXd::Zero(5);
  p.base = LowRankStructure::Base::kMass;
  p.phi.resize(5, 0);
  p.mass = {1.0, Eigen::VectorXd()};
  p.damping = {0.5, Eigen::VectorXd()};
  p.stiffness = {4.0, Eigen::VectorXd()};
  const LowRankStructure s(p);
  const Eigen::VectorXd qc = Eigen::VectorXd::LinSpaced(10, 0.0, 9.0);
  Eigen::VectorXd x;
  s.gather(qc.data(), x);
  EXPECT_EQ(x, (Eigen::VectorXd(5) << 6, 7, 8, 1, 2).finished());
  Eigen::VectorXd back = Eigen::VectorXd::Zero(10);
  s.scatter_add(x, back.data());
  EXPECT_EQ(back, (Eigen::VectorXd(10) << 0, 1, 2, 0, 0, 0, 6, 7, 8, 0).finished());
}

TEST(LowRankStructure, RefusesPartsThatDoNotFit) {
  const Fixture f;
  LowRankStructure::Parts p = adjusted_parts("b", {{0, f.n()}}, f.sys.M, f.sys.K, f.sys.P, f.basis, f.adjusted);
  p.ranges = {{0, f.n() - 1}};
  EXPECT_THROW(LowRankStructure{p}, std::invalid_argument);
  p = adjusted_parts("b", {{0, f.n()}}, f.sys.M, f.sys.K, f.sys.P, f.basis, f.adjusted);
  p.damping.d.resize(1);
  EXPECT_THROW(LowRankStructure{p}, std::invalid_argument);
  // The policy mass on a beam nothing holds: K is singular.
  LowRankStructure::Parts loose = mass_parts(f, {{0, f.n()}});
  loose.K = 0.0 * loose.K;
  EXPECT_THROW(LowRankStructure{loose}, std::exception);
}

}  // namespace
}  // namespace mbfe::runtime
