// `mbfe simulate` on a beam-only model with `policy: mass`, through the real
// binary, against a modal integration written here: the modes from Eigen's
// generalised symmetric eigen-solver on the dense M and K, each mode's
// m_j eta'' + c_j eta' + k_j eta = phi_j^T P stepped by a hand-written RK4.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "frontend/parse_model.h"
#include "runtime/fem/beam_system.h"
#include "tests/support/cli.h"
#include "tests/support/process.h"

namespace mbfe::test {
namespace {

// 4 elements of the paper beam's section (8 DOF, omega 74 to 6.0e3 rad/s);
// the cap at 2e3 rad/s changes the four modes whose fastest root is above it.
const char* const kBeam = R"(model: mass_policy_beam
beams:
  - name: b
    origin: [0, 0]
    length: 1.0
    elements: 4
    section: {area: 25.0e-6, inertia: 5.208333333333333e-11}
    material: {youngs_modulus: 2.1e11, density: 7860}
    supports: [{at: 0.0, type: pinned}, {at: 1.0, type: pinned}]
    damping: {rayleigh: {alpha: 3.0e-3, beta: 1.5e-4}}
    loads: [{type: point, at: 0.5, value: -10.0}]
    adjustment: {omega_limit: 2.0e3, margin: 0.1, policy: mass}
)";

constexpr double kOmegaLimit = 2e3, kMargin = 0.1;
constexpr double kStep = 1e-5;  // RK4's limit for the capped root 2.74e3 1/s is 1e-3 s
constexpr int kSteps = 2000;
// The same RK4 on the same modal equations, in another summation order and
// with modes from another eigen-solver (8 DOF: ~1e-13 of the largest entry).
constexpr double kSameMethodRel = 1e-9;
// s: a row's time read back from CSV against s * kStep.
constexpr double kRowTimeTol = 1e-12;

struct Mode {
  double m = 1.0, c = 0.0, k = 0.0, p = 0.0;
};

/// One RK4 step of m eta'' + c eta' + k eta = p, (eta, v) in place.
void rk4_step(const Mode& d, double h, double& eta, double& v) {
  const auto acc = [&d](double e, double w) { return (d.p - d.c * w - d.k * e) / d.m; };
  const double k1e = v, k1v = acc(eta, v);
  const double k2e = v + 0.5 * h * k1v, k2v = acc(eta + 0.5 * h * k1e, v + 0.5 * h * k1v);
  const double k3e = v + 0.5 * h * k2v, k3v = acc(eta + 0.5 * h * k2e, v + 0.5 * h * k2v);
  const double k4e = v + h * k3v, k4v = acc(eta + h * k3e, v + h * k3v);
  eta += h / 6.0 * (k1e + 2.0 * k2e + 2.0 * k3e + k4e);
  v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
}

TEST(SimulateBeam, PolicyMassIsTheModalIntegrationWithRaisedModalMasses) {
  TempDir dir;
  const fs::path model = dir / "beam.yaml", csv = dir / "out.csv";
  spit(model, kBeam);
  const CliRun r = run_cli("simulate " + quote(model.string()) + " --quiet --integrator rk4 --step " +
                           std::to_string(kStep) + " --t-end " + std::to_string(kSteps * kStep) +
                           " --every 1 --probe b@0.5 --out " + quote(csv.string()));
  ASSERT_EQ(r.status, 0) << r.all();
  const Csv out = read_csv(csv.string());
  ASSERT_EQ(out.rows.size(), static_cast<std::size_t>(kSteps + 1));
  ASSERT_EQ(out.header.size(), 2u);

  // The oracle's modes.
  const ir::Model ir = frontend::parse_model_text(kBeam, "beam.yaml");
  const runtime::BeamSystem sys = runtime::assemble_beam(ir.beams.at(0), ir.gravity);
  const Eigen::MatrixXd M(sys.M), K(sys.K);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);  // Phi^T M Phi = I
  ASSERT_EQ(eig.info(), Eigen::Success);
  const int n = static_cast<int>(M.rows());
  const Eigen::MatrixXd& phi = eig.eigenvectors();
  int midspan = -1;  // the free DOF of w at node 2 (s = 0.5)
  for (int i = 0; i < n; ++i)
    if (sys.free_dof[i] == 2 * 2) midspan = i;
  ASSERT_GE(midspan, 0);
  std::vector<Mode> modes(n);
  int capped = 0;
  for (int j = 0; j < n; ++j) {
    const double w = std::sqrt(eig.eigenvalues()[j]);
    Mode& d = modes[j];
    d.k = w * w;
    d.c = sys.rayleigh_alpha + sys.rayleigh_beta * w * w;
    d.p = phi.col(j).dot(sys.P);
    const double disc = d.c * d.c - 4.0 * d.k;
    const double fastest = disc >= 0.0 ? 0.5 * (d.c + std::sqrt(disc)) : w;
    if (fastest > kOmegaLimit) {
      d.m = d.k / (kOmegaLimit * kOmegaLimit);
      d.c = d.m * (2.0 + kMargin) * kOmegaLimit;
      ++capped;
    }
  }
  ASSERT_GE(capped, 2);
  ASSERT_LE(capped, n - 2);

  std::vector<double> eta(n, 0.0), v(n, 0.0);
  double peak = 0.0, worst = 0.0;
  for (int s = 0; s <= kSteps; ++s) {
    double w = 0.0;
    for (int j = 0; j < n; ++j) w += phi(midspan, j) * eta[j];
    peak = std::max(peak, std::abs(w));
    worst = std::max(worst, std::abs(out.rows[s][1] - w));
    EXPECT_NEAR(out.rows[s][0], s * kStep, kRowTimeTol);
    for (int j = 0; j < n; ++j) rk4_step(modes[j], kStep, eta[j], v[j]);
  }
  EXPECT_GT(peak, 1e-3);  // the 10 N load bends the beam by millimetres
  EXPECT_LT(worst, kSameMethodRel * peak) << "largest difference " << worst << " m against a peak of " << peak << " m";
}

}  // namespace
}  // namespace mbfe::test
