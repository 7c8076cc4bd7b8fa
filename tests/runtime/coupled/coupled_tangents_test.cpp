// A coupled model linearised from its own tangents (runtime/coupled/
// coupled_tangents.h) and its spectrum (tangent_spectrum.h):
//   - products by A against central differences of the accelerations
//     (the whole right-hand side, an independent path: evaluate and solve)
//   - shifted solves against products (A - sigma I) x
//   - the Arnoldi ends of the spectrum against the dense eigenvalues of the
//     same A (the oracle), on a model small enough for both
//   - the shipped vehicle models released from their static equilibrium:
//     no eigenvalue counted as growing, a zero pair per driven coordinate
//   - a free coordinate (a defective zero pair) recognised as a zero mode,
//     densely and by Arnoldi (whose shift then moves off the singular A)
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <complex>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "api/mbfe.h"
#include "runtime/coupled/coupled_tangents.h"
#include "runtime/coupled/linearization.h"
#include "runtime/coupled/tangent_spectrum.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/static_start.h"

namespace mbfe::runtime {
namespace {

std::string model_path(const std::string& name) { return std::string(MBFE_SOURCE_DIR) + "/models/" + name + ".yaml"; }

struct Linearized {
  Model model;
  std::shared_ptr<CoupledDynamics> dynamics;
  Eigen::VectorXd q0, qd0;
};

// The model at its static start, as the advisor linearises it.
Linearized at_static_start(const std::string& name, bool adjusted) {
  LoadOptions quiet;
  quiet.quiet = true;
  Linearized out{Model::load(model_path(name), quiet), nullptr, {}, {}};
  const AssembledModel& am = out.model.assembled();
  out.dynamics = am.make_dynamics(adjusted);
  am.initial_coordinates(out.q0, out.qd0);
  out.dynamics->impose_motion(0.0, out.q0, out.qd0);
  coupled_static_start(am.ir(), out.dynamics, out.q0, out.qd0);
  return out;
}

// The accelerations of the free coordinates at (q, qd), driven ones imposed.
Eigen::VectorXd free_accelerations(CoupledDynamics& dyn, const CoupledTangents& tangents, Eigen::VectorXd q,
                                   Eigen::VectorXd qd) {
  Eigen::VectorXd a, lambda;
  dyn.impose_motion(0.0, q, qd);
  dyn.evaluate(0.0, q, qd);
  dyn.solve_augmented(0.0, a, lambda);
  Eigen::VectorXd out(tangents.size());
  for (int i = 0; i < tangents.size(); ++i) out[i] = a[tangents.free_coordinates()[i]];
  return out;
}

// Central differences of the accelerations along a random direction carry
// truncation (h^2 a''') and round-off (eps |terms| / h); with a step of 1e-6 of
// the state's size both are below 1e-6 of |A x| on these models (the
// adjusted beams' operators cancel terms 1e4 times their result, which the
// quotient sees and the tangents do not).
constexpr double kDifferenceAgreement = 1e-5;
constexpr double kDifferenceStep = 1e-6;

void expect_tangents_match_differences(const std::string& name, bool adjusted) {
  SCOPED_TRACE(name + (adjusted ? " adjusted" : " original"));
  Linearized lin = at_static_start(name, adjusted);
  CoupledTangents tangents(*lin.dynamics, 0.0, lin.q0, lin.qd0);
  const int nf = tangents.size();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd x(2 * nf), ax(2 * nf);
  for (int i = 0; i < 2 * nf; ++i) x[i] = u(rng);
  tangents.apply_state_matrix(x.data(), ax.data());
  EXPECT_EQ((ax.head(nf) - x.tail(nf)).norm(), 0.0);  // the top block is [0, I]

  const double scale = std::max(1.0, std::max(lin.q0.cwiseAbs().maxCoeff(), lin.qd0.cwiseAbs().maxCoeff()));
  const double h = kDifferenceStep * scale;
  Eigen::VectorXd qp = lin.q0, qm = lin.q0, vp = lin.qd0, vm = lin.qd0;
  for (int i = 0; i < nf; ++i) {
    const int j = tangents.free_coordinates()[i];
    qp[j] += h * x[i];
    qm[j] -= h * x[i];
    vp[j] += h * x[nf + i];
    vm[j] -= h * x[nf + i];
  }
  const Eigen::VectorXd quotient = (free_accelerations(*lin.dynamics, tangents, qp, vp) -
                                    free_accelerations(*lin.dynamics, tangents, qm, vm)) /
                                   (2.0 * h);
  EXPECT_LE((quotient - ax.tail(nf)).norm(), kDifferenceAgreement * ax.tail(nf).norm());
}

TEST(CoupledTangents, ProductsByAMatchDifferencesOfTheRightHandSide) {
  for (const char* name : {"bridge_moving_mass", "bridge_two_axle_vehicle"})
    for (bool adjusted : {false, true}) expect_tangents_match_differences(name, adjusted);
}

// A shifted solve is the inverse of (A - sigma I) up to the LU's round-off,
// relative to the size of the terms the residual cancels: S = sigma^2 M +
// sigma C + K has a condition of about omega_max^2 / omega_min^2 ~ 1e10 on
// the vehicle, and the residual measured is up to 2.4e-10 of the terms.
constexpr double kSolveResidual = 1e-8;

TEST(CoupledTangents, ShiftedSolvesInvertTheShiftedProduct) {
  for (bool adjusted : {false, true}) {
    SCOPED_TRACE(adjusted ? "adjusted" : "original");
    Linearized lin = at_static_start("bridge_two_axle_vehicle", adjusted);
    CoupledTangents tangents(*lin.dynamics, 0.0, lin.q0, lin.qd0);
    const int n = 2 * tangents.size();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::VectorXd b(n), x(n), ax(n);
    for (int i = 0; i < n; ++i) b[i] = u(rng);
    for (double sigma : {0.0, -50.0}) {
      tangents.factorize_shifted(sigma);
      tangents.solve_shifted(b.data(), x.data());
      tangents.apply_state_matrix(x.data(), ax.data());
      EXPECT_LE((ax - sigma * x - b).norm(), kSolveResidual * (ax.norm() + std::abs(sigma) * x.norm() + b.norm()))
          << "sigma " << sigma << ", |A x| " << ax.norm();
    }
  }
}

// Arnoldi's Ritz residuals are below 1e-6 |lambda| on the balanced A
// (tangent_spectrum.cpp), and an eigenvalue's error is that times its
// condition (1.3e-6 |lambda| measured on the vehicle's fastest pair). The
// dense QR of the balanced A is good to ~1e-12 of max |lambda| here.
constexpr double kArnoldiAgreement = 1e-5;

TEST(TangentSpectrum, ArnoldiEndsMatchTheDenseEigenvalues) {
  for (bool adjusted : {false, true}) {
    SCOPED_TRACE(adjusted ? "adjusted" : "original");
    Linearized lin = at_static_start("bridge_two_axle_vehicle", adjusted);
    CoupledTangents tangents(*lin.dynamics, 0.0, lin.q0, lin.qd0);
    const StateSpectrum dense = tangent_spectrum(tangents);
    ASSERT_TRUE(dense.complete);
    TangentSpectrumOptions arnoldi;
    arnoldi.max_dense_states = 0;
    const StateSpectrum ends = tangent_spectrum(tangents, arnoldi);
    EXPECT_FALSE(ends.complete);
    ASSERT_GE(ends.eigenvalues.size(), static_cast<std::size_t>(kFastestEigenvalues + kSlowestEigenvalues - 2));
    // Every eigenvalue found is one of the dense ones.
    for (const auto& l : ends.eigenvalues) {
      double nearest = 1e300;
      for (const auto& m : dense.eigenvalues) nearest = std::min(nearest, std::abs(m - l));
      EXPECT_LE(nearest, kArnoldiAgreement * std::max(std::abs(l), 1.0)) << l;
    }
    // The fastest and the slowest are among them.
    const double fastest = std::abs(dense.eigenvalues.back());
    EXPECT_NEAR(std::abs(ends.eigenvalues.back()), fastest, kArnoldiAgreement * fastest);
    EXPECT_NEAR(std::abs(ends.eigenvalues.front()), std::abs(dense.eigenvalues.front()),
                kArnoldiAgreement * std::max(std::abs(dense.eigenvalues.front()), 1.0));
  }
}

TEST(TangentSpectrum, VehiclesAtTheirStaticEquilibriumHaveNoGrowingEigenvalue) {
  for (const char* name : {"bridge_moving_mass", "bridge_two_axle_vehicle", "vehicle_bridge_30m"}) {
    for (bool adjusted : {false, true}) {
      SCOPED_TRACE(std::string(name) + (adjusted ? " adjusted" : " original"));
      LoadOptions quiet;
      quiet.quiet = true;
      const Model model = Model::load(model_path(name), quiet);
      const ModelSpectrum spectrum = model.spectrum(adjusted);
      EXPECT_EQ(spectrum.growing, 0);
      EXPECT_EQ(split_growing(spectrum.full).growing, 0);
      EXPECT_TRUE(spectrum.full.complete);
      // The driven carriage's pair, exactly zero.
      EXPECT_GE(std::count(spectrum.full.eigenvalues.begin(), spectrum.full.eigenvalues.end(),
                           std::complex<double>(0.0, 0.0)),
                2);
    }
  }
}

// The moving-mass bridge with a 10 kg slider on a horizontal prismatic joint
// that nothing holds or damps: z'' = 0, a defective zero pair beside the
// driven carriage's, started as written (a mechanism has no static start).
TEST(TangentSpectrum, AFreeCoordinateIsAZeroModeDenselyAndByArnoldi) {
  std::ifstream in(model_path("bridge_moving_mass"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string beams = "\nbeams:";
  ASSERT_NE(yaml.find(beams), std::string::npos);
  yaml.replace(yaml.find(beams), beams.size(),
               "\n  - name: free_slider\n    parent: ground\n    joint: {type: prismatic, axis: [1, 0], at: [0.0, 5.0]}\n"
               "    mass: 10.0\n    inertia: 0.0\nbeams:");
  const std::string start = "initial: {static: true}";
  ASSERT_NE(yaml.find(start), std::string::npos);
  yaml.replace(yaml.find(start), start.size(), "initial: {static: false}");
  LoadOptions quiet;
  quiet.quiet = true;
  const Model model = Model::parse(yaml, "free_slider.yaml", quiet);
  const AssembledModel& am = model.assembled();
  for (bool adjusted : {false, true}) {
    SCOPED_TRACE(adjusted ? "adjusted" : "original");
    std::shared_ptr<CoupledDynamics> dynamics = am.make_dynamics(adjusted);
    Eigen::VectorXd q0, qd0;
    am.initial_coordinates(q0, qd0);
    dynamics->impose_motion(0.0, q0, qd0);
    CoupledTangents tangents(*dynamics, 0.0, q0, qd0);
    TangentSpectrumOptions arnoldi;
    arnoldi.max_dense_states = 0;
    for (const StateSpectrum& spectrum : {tangent_spectrum(tangents), tangent_spectrum(tangents, arnoldi)}) {
      SCOPED_TRACE(spectrum.complete ? "dense" : "Arnoldi");
      const auto zeros = std::count(spectrum.eigenvalues.begin(), spectrum.eigenvalues.end(), std::complex<double>(0.0, 0.0));
      // The carriage's pair and the slider's. Arnoldi sees a defective
      // eigenvalue once (it has one eigenvector): 3 there.
      EXPECT_EQ(zeros, spectrum.complete ? 4 : 3);
      // The slowest nonzero one is a physical mode (the deck's first, 12.76 rad/s, or slower), not round-off.
      for (const auto& l : spectrum.eigenvalues)
        if (l != 0.0) EXPECT_GT(std::abs(l), 1.0) << l;
    }
  }
}

}  // namespace
}  // namespace mbfe::runtime
