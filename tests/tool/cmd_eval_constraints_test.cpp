// `mbfe eval --json` constraints block against finite
// differences of Phi from `mbfe eval` itself, for both shipped coupled models:
// J_b = dPhi/dq_b, J_c = dPhi/dq_c and gamma = -(dJ/dt) q'.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli.h"

namespace mbfe::coupled_test {
namespace {

// Central-difference step: with h = 1e-6 the truncation error h^2 |Phi'''| / 6
// is ~1e-13 and the round-off eps |Phi| / h ~1e-10 (Phi ~ 1 m at most).
constexpr double kFdStep = 1e-6;
// J_b entries are O(1) (m/rad); the two error terms above bound the
// difference quotient to ~1e-10: 1e-7 leaves three orders of margin.
constexpr double kJacobianTol = 1e-7;
// gamma is differenced from J(q +- h q') q': the same two error terms, times
// |q'| ~ 1: 1e-6 absolute on values of order 0.1..10 m/s^2.
constexpr double kGammaTol = 1e-6;

std::string list(const std::vector<double>& v) {
  std::ostringstream os;
  os.precision(17);
  for (std::size_t i = 0; i < v.size(); ++i) os << (i ? "," : "") << v[i];
  return os.str();
}

nlohmann::json eval(const std::string& model, const std::vector<double>& q, const std::vector<double>& qd,
                    const std::vector<double>& qc, const std::vector<double>& qcd) {
  const test::CliRun r = test::run_cli("eval " + model + " --json --q " + list(q) + " --qd " + list(qd) + " --qc " + list(qc) +
                               " --qcd " + list(qcd));
  EXPECT_EQ(r.status, 0) << r.all();
  return nlohmann::json::parse(r.out).at("constraints");
}

struct State {
  std::vector<double> q, qd, qc, qcd;
};

void check_model(const std::string& model, const State& x0, int nc_expected, int rows_expected) {
  SCOPED_TRACE(model);
  const nlohmann::json c0 = eval(model, x0.q, x0.qd, x0.qc, x0.qcd);
  const auto jb = c0.at("Jb").get<std::vector<std::vector<double>>>();
  const auto jc = c0.at("Jc").get<std::vector<std::vector<double>>>();
  const auto gamma = c0.at("gamma").get<std::vector<double>>();
  const int m = static_cast<int>(c0.at("Phi").size());
  ASSERT_EQ(m, rows_expected);
  ASSERT_EQ(static_cast<int>(jc.at(0).size()), nc_expected);
  const int nb = static_cast<int>(x0.q.size());
  // J_b column by column.
  for (int j = 0; j < nb; ++j) {
    State p = x0, mi = x0;
    p.q[j] += kFdStep;
    mi.q[j] -= kFdStep;
    const auto fp = eval(model, p.q, p.qd, p.qc, p.qcd).at("Phi").get<std::vector<double>>();
    const auto fm = eval(model, mi.q, mi.qd, mi.qc, mi.qcd).at("Phi").get<std::vector<double>>();
    for (int r = 0; r < m; ++r)
      EXPECT_NEAR(jb[r][j], (fp[r] - fm[r]) / (2 * kFdStep), kJacobianTol) << "J_b row " << r << " col " << j;
  }
  // J_c: the columns where some row is nonzero (the elements holding the
  // contact points) and a few others, which must be zero.
  std::vector<int> cols;
  for (int k = 0; k < nc_expected; ++k) {
    bool nz = false;
    for (int r = 0; r < m; ++r) nz = nz || jc[r][k] != 0.0;
    if (nz || k % 37 == 5) cols.push_back(k);
  }
  EXPECT_GE(cols.size(), 4u);
  for (int k : cols) {
    State p = x0, mi = x0;
    p.qc[k] += kFdStep;
    mi.qc[k] -= kFdStep;
    const auto fp = eval(model, p.q, p.qd, p.qc, p.qcd).at("Phi").get<std::vector<double>>();
    const auto fm = eval(model, mi.q, mi.qd, mi.qc, mi.qcd).at("Phi").get<std::vector<double>>();
    for (int r = 0; r < m; ++r)
      EXPECT_NEAR(jc[r][k], (fp[r] - fm[r]) / (2 * kFdStep), kJacobianTol) << "J_c row " << r << " col " << k;
  }
  // gamma = -d/de [J(q + e q') q'] at e = 0.
  auto jqd = [&](double e) {
    State s = x0;
    for (int j = 0; j < nb; ++j) s.q[j] += e * x0.qd[j];
    for (int k = 0; k < nc_expected; ++k) s.qc[k] += e * x0.qcd[k];
    const nlohmann::json c = eval(model, s.q, s.qd, s.qc, s.qcd);
    const auto b = c.at("Jb").get<std::vector<std::vector<double>>>();
    const auto cc = c.at("Jc").get<std::vector<std::vector<double>>>();
    std::vector<double> out(m, 0.0);
    for (int r = 0; r < m; ++r) {
      for (int j = 0; j < nb; ++j) out[r] += b[r][j] * x0.qd[j];
      for (int k = 0; k < nc_expected; ++k) out[r] += cc[r][k] * x0.qcd[k];
    }
    return out;
  };
  const auto gp = jqd(kFdStep), gm = jqd(-kFdStep);
  for (int r = 0; r < m; ++r)
    EXPECT_NEAR(gamma[r], -(gp[r] - gm[r]) / (2 * kFdStep), kGammaTol) << "gamma row " << r;
}

State random_state(int nb, int nc, const std::vector<double>& q0, unsigned seed, double q_spread) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  State s;
  for (int j = 0; j < nb; ++j) {
    s.q.push_back(q0[j] + q_spread * u(rng));
    s.qd.push_back(u(rng));
  }
  for (int k = 0; k < nc; ++k) {
    // Beam states of a few mm and mm/s (rotations a few mrad).
    s.qc.push_back(2e-3 * u(rng));
    s.qcd.push_back(5e-2 * u(rng));
  }
  return s;
}

TEST(CoupledEval, DoublePendulumBeamConstraintsMatchFiniteDifferences) {
  // 50 elements pinned-pinned: 102 DOFs - 2 fixed = 100 beam coordinates; one slider row.
  const State x = random_state(2, 100, {-1.3874443249943893, -0.9342922220176699}, 11, 0.05);
  check_model("models/double_pendulum_beam.yaml", x, 100, 1);
}

TEST(CoupledEval, PaperPlatformConstraintsMatchFiniteDifferences) {
  // Two beams of 100 coordinates; a pin (2 rows) and a slider (1 row).
  const State x =
      random_state(4, 200, {0.01822105589941761, -0.5341715556266442, 0.1, 1.475522133987186}, 7, 0.02);
  check_model("models/paper_platform.yaml", x, 200, 3);
}

TEST(CoupledEval, WrongBeamCoordinateCountIsAUsageError) {
  const test::CliRun r = test::run_cli("eval models/double_pendulum_beam.yaml --json --q 0,0 --qc 1,2,3");
  EXPECT_EQ(r.status, 2) << r.all();
  EXPECT_NE(r.all().find("expected 100 (beam coordinates in contract order)"), std::string::npos) << r.all();
}

// The initial angles are printed to 17 digits: Phi ~ |J| * 1e-16 m.
constexpr double kClosedPhiTol = 1e-14;

TEST(CoupledEval, DefaultsToZeroBeamCoordinates) {
  // At the shipped initial state with the beam undeformed the slider is closed.
  const test::CliRun r = test::run_cli(
      "eval models/double_pendulum_beam.yaml --json --q -1.3874443249943893,-0.9342922220176699");
  ASSERT_EQ(r.status, 0) << r.all();
  const nlohmann::json c = nlohmann::json::parse(r.out).at("constraints");
  ASSERT_EQ(c.at("Phi").size(), 1u);
  // The initial angles are printed to 17 digits: Phi ~ |J| * 1e-16.
  EXPECT_NEAR(c.at("Phi")[0].get<double>(), 0.0, kClosedPhiTol);
  EXPECT_EQ(c.at("Jc")[0].size(), 100u);
}

}  // namespace
}  // namespace mbfe::coupled_test
