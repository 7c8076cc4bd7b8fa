// The public API (api/mbfe.h) against closed forms and the command line: a
// pendulum given as text, the linked solver of the double pendulum, requests
// the runtime must refuse, and two threads simulating one Model.
#include "api/mbfe.h"
#include "tests/support/recorded_rows.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "frontend/parse_model.h"
#include "tests/support/cli.h"

extern "C" const mbfe_model_v1* mbfe_model_double_pendulum(void);

namespace mbfe {
namespace {

// A uniform rod of mass m, length l, hinged at one end: I_hinge = m l^2 / 3.
constexpr double kMass = 2.0, kLength = 0.6, kGravity = 9.81;
const std::string kPendulum = R"(model: api_pendulum
gravity: [0, -9.81]
bodies:
  - name: rod
    parent: ground
    joint: {type: revolute, at: [0, 0]}
    mass: 2.0
    inertia: 0.06          # m l^2 / 12
    com: [0.3, 0]
initial: {q: {rod: -1.5707963267948966}}
)";

// Kernels evaluate the same closed-form expressions in another order:
// a few ulps of O(1) values.
constexpr double kKernelTol = 1e-14;
// Eigenvalues of a dense 2x2 linearisation by central differences
// (relative step 1e-6): ~1e-9 relative.
constexpr double kLinearizationTol = 1e-7;

std::string source_path(const std::string& relative) { return std::string(MBFE_SOURCE_DIR) + "/" + relative; }

using Rows = test::RecordedRows;

runtime::SimulationRequest rk4(double step, double t_end) {
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("rk4");
  request.step = step;
  request.t_end = t_end;
  return request;
}

TEST(ApiModel, ParsedPendulumEvaluatesToItsClosedForm) {
  const Model model = Model::parse(kPendulum, "pendulum.yaml");
  EXPECT_EQ(model.kind(), runtime::ModelKind::kRigid);
  State state;
  state.q = {0.4};
  state.qd = {1.5};
  const Evaluation e = model.evaluate(state);
  const double inertia = kMass * kLength * kLength / 3.0;
  EXPECT_NEAR(e.M(0, 0), inertia, kKernelTol);
  EXPECT_NEAR(e.F[0], 0.0, kKernelTol);
  // Q = -m g (l/2) cos q: gravity's moment about the hinge.
  EXPECT_NEAR(e.Q[0], -kMass * kGravity * 0.5 * kLength * std::cos(0.4), kKernelTol);
  EXPECT_FALSE(e.has_constraints);
}

// Hanging at rest (q = -pi/2): lambda = +-i sqrt(m g (l/2) / I_hinge).
TEST(ApiModel, SpectrumOfTheHangingPendulumAndItsStepLimits) {
  const Model model = Model::parse(kPendulum, "pendulum.yaml");
  const runtime::ModelSpectrum s = model.spectrum(false);
  ASSERT_EQ(s.full.eigenvalues.size(), 2u);
  const double omega = std::sqrt(kMass * kGravity * 0.5 * kLength / (kMass * kLength * kLength / 3.0));
  EXPECT_TRUE(s.linearized);
  EXPECT_NEAR(std::abs(s.full.eigenvalues[0].imag()), omega, kLinearizationTol * omega);
  EXPECT_NEAR(s.full.eigenvalues[0].real(), 0.0, kLinearizationTol * omega);
  bool saw_forward_euler = false;
  for (const runtime::StepLimitRow& row : model.step_limits()) {
    EXPECT_FALSE(row.adjusted);  // no beams, no adjusted model
    if (row.integrator.name != "forward_euler") continue;
    saw_forward_euler = true;
    EXPECT_EQ(row.original.kind, runtime::StepLimit::Kind::kNone);  // an undamped oscillator
  }
  EXPECT_TRUE(saw_forward_euler);
  EXPECT_THROW(model.spectrum(true), runtime::InvalidInput);
}

TEST(ApiModel, LinkedSolverMatchesTheCachedOneAndRefusesAnotherVersionOfTheFile) {
  const std::string path = source_path("models/double_pendulum.yaml");
  const Model linked = Model::with_solver(path, mbfe_model_double_pendulum());
  const Model cached = Model::load(path);
  State state;
  state.q = {0.3, -0.2};
  state.qd = {1.0, 0.5};
  EXPECT_EQ(linked.evaluate(state).M, cached.evaluate(state).M);
  EXPECT_EQ(linked.evaluate(state).Q, cached.evaluate(state).Q);
  EXPECT_TRUE(linked.solver_library().empty());
  EXPECT_FALSE(cached.solver_library().empty());

  // The same model with one more comment line: another SHA-256.
  const std::string edited = ::testing::TempDir() + "/double_pendulum_edited.yaml";
  {
    std::ifstream in(path);
    std::ofstream out(edited);
    out << in.rdbuf() << "# edited\n";
  }
  try {
    Model::with_solver(edited, mbfe_model_double_pendulum());
    FAIL() << "a solver of another version of the file was accepted";
  } catch (const ir::ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("another version of this file"), std::string::npos) << e.what();
  }
  std::remove(edited.c_str());
}

// Whatever the path, a solver recorded for one version of a model file is not
// paired with another's IR: same name, same coordinates, another SHA-256.
TEST(ApiModel, FromIrRefusesASolverOfAnotherVersionOfTheFile) {
  const std::string path = source_path("models/double_pendulum.yaml");
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  const ir::Model same = frontend::parse_model_text(text.str(), path);
  EXPECT_NO_THROW(Model::from_ir(same, mbfe_model_double_pendulum()));
  const ir::Model edited = frontend::parse_model_text(text.str() + "# edited\n", path);
  try {
    Model::from_ir(edited, mbfe_model_double_pendulum());
    FAIL() << "a solver of another version of the file was accepted";
  } catch (const runtime::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(edited.source_sha256), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(same.source_sha256), std::string::npos) << e.what();
  }
  // An IR built in memory has no file behind it, so nothing to compare.
  ir::Model built = same;
  built.source_sha256.clear();
  EXPECT_NO_THROW(Model::from_ir(built, mbfe_model_double_pendulum()));
}

TEST(ApiModel, SimulationRowsEqualTheCommandLine) {
  const std::string path = "models/double_pendulum.yaml";
  const Model model = Model::load(source_path(path));
  Rows rows;
  const runtime::SimulationReport report = model.simulate(rk4(1e-3, 0.5), rows);
  ASSERT_TRUE(report.message.empty()) << report.message;
  EXPECT_EQ(rows.columns, (std::vector<std::string>{"t", "link1", "link2", "link1_dot", "link2_dot"}));
  EXPECT_EQ(rows.units, (std::vector<std::string>{"s", "rad", "rad", "rad/s", "rad/s"}));
  const std::string csv = ::testing::TempDir() + "/api_vs_cli.csv";
  const test::CliRun cli = test::run_cli("simulate " + path + " --integrator rk4 --step 1e-3 --t-end 0.5 --quiet --out " + csv);
  ASSERT_EQ(cli.status, 0) << cli.err;
  const test::Csv table = test::read_csv(csv);
  ASSERT_EQ(table.rows.size(), rows.values.size());
  for (std::size_t r = 0; r < rows.values.size(); ++r) EXPECT_EQ(table.rows[r], rows.values[r]) << "row " << r;
  std::remove(csv.c_str());
}

TEST(ApiModel, RequestsTheModelCannotRunAreInvalidInput) {
  const Model pendulum = Model::parse(kPendulum, "pendulum.yaml");
  Rows rows;
  runtime::SimulationRequest probe = rk4(1e-3, 0.1);
  probe.probes = {runtime::parse_probe("beam1@0.5")};
  EXPECT_THROW(pendulum.simulate(probe, rows), runtime::InvalidInput);  // no beams
  runtime::SimulationRequest alpha = rk4(1e-3, 0.1);
  alpha.integrator = runtime::parse_integrator("generalized_alpha");
  EXPECT_THROW(pendulum.simulate(alpha, rows), runtime::InvalidInput);  // nonlinear model
  EXPECT_THROW(pendulum.simulate(rk4(-1.0, 0.1), rows), runtime::InvalidInput);
  EXPECT_THROW(runtime::parse_probe("beam1"), runtime::InvalidInput);
  EXPECT_THROW(runtime::parse_probe("beam1@x"), runtime::InvalidInput);

  const Model beam = Model::load(source_path("models/cantilever.yaml"));
  runtime::SimulationRequest adjusted = rk4(1e-5, 1e-3);
  adjusted.adjust = true;
  ASSERT_FALSE(beam.assembled().has_adjustment());
  EXPECT_THROW(beam.simulate(adjusted, rows), runtime::InvalidInput);
  runtime::SimulationRequest unknown = rk4(1e-5, 1e-3);
  unknown.probes = {runtime::parse_probe("no_such_beam@0.5")};
  EXPECT_THROW(beam.simulate(unknown, rows), runtime::InvalidInput);
  State state;
  EXPECT_THROW(beam.evaluate(state), runtime::InvalidInput);  // no bodies
  state.q = {1.0, 2.0, 3.0};
  EXPECT_THROW(pendulum.evaluate(state), runtime::InvalidInput);
}

TEST(ApiModel, EvaluateGivesTheLoopsAsTheCommandLineDoes) {
  const std::vector<double> q = {
      0.3, 0.9899856611293864, 0.0, -0.12626445504008477, 0.06313222752004238, 0.48405728739343046};
  const std::vector<double> qd = {10.0, 0.1, -0.2, 0.3, 0.5};
  std::ostringstream args;
  args.precision(17);
  args << "eval " << MBFE_SOURCE_DIR << "/models/slider_crank_3d.yaml --json --q ";
  for (std::size_t i = 0; i < q.size(); ++i) args << (i ? "," : "") << q[i];
  args << " --qd ";
  for (std::size_t i = 0; i < qd.size(); ++i) args << (i ? "," : "") << qd[i];
  const test::CliRun r = test::run_cli(args.str());
  ASSERT_EQ(r.status, 0) << r.all();
  const nlohmann::json loops = nlohmann::json::parse(r.out).at("loops");
  const Model model = Model::load(std::string(MBFE_SOURCE_DIR) + "/models/slider_crank_3d.yaml");
  State state;
  state.q = q;
  state.qd = qd;
  const Evaluation e = model.evaluate(state);
  ASSERT_TRUE(e.has_loops);
  const auto phi = loops.at("Phi").get<std::vector<double>>();
  const auto j = loops.at("J").get<std::vector<std::vector<double>>>();
  const auto gamma = loops.at("gamma").get<std::vector<double>>();
  ASSERT_EQ(e.loop_phi.size(), static_cast<Eigen::Index>(phi.size()));
  ASSERT_EQ(e.loop_j.rows(), static_cast<Eigen::Index>(j.size()));
  ASSERT_EQ(e.loop_j.cols(), 5);
  // The JSON prints the shortest text that reads back as the same double.
  for (std::size_t i = 0; i < phi.size(); ++i) {
    EXPECT_EQ(e.loop_phi[i], phi[i]) << i;
    EXPECT_EQ(e.loop_gamma[i], gamma[i]) << i;
    for (std::size_t c = 0; c < j[i].size(); ++c) EXPECT_EQ(e.loop_j(i, c), j[i][c]) << i << ", " << c;
  }
  EXPECT_FALSE(Model::parse(kPendulum, "pendulum.yaml").evaluate(State{}).has_loops);
}

TEST(ApiModel, EvaluateRefusesAQuaternionOffUnitLength) {
  // A free body, 1 kg, Ixx 0.1, centre of mass 0.5 m along y: about the
  // body's x axis M = Ixx + m 0.5^2 = 0.35 for a unit quaternion, whatever
  // the turn. (1, 0, 0, 1) is no rotation; the kernels would read it as one.
  const Model model = Model::parse(
      "model: tumbler\ndimension: 3\nbodies:\n"
      "  - {name: box, parent: ground, joint: {type: free}, mass: 1.0, inertia: [0.1, 0.2, 0.3, 0, 0, 0],"
      " com: [0, 0.5, 0]}\n",
      "tumbler.yaml");
  State state;
  state.q = {0, 0, 0, 1, 0, 0, 1};
  try {
    model.evaluate(state);
    FAIL() << "a quaternion of norm sqrt(2) was evaluated";
  } catch (const runtime::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("q: the quaternion of body 'box' (box_qw .. box_qz) has norm 1.414213562, "
                                         "expected 1 (within 1e-06)"),
              std::string::npos)
        << e.what();
  }
  const double h = std::sqrt(0.5);
  state.q = {0, 0, 0, h, 0, 0, h};
  EXPECT_NEAR(model.evaluate(state).M(3, 3), 0.35, kKernelTol);
  EXPECT_NEAR(model.evaluate(State{}).M(3, 3), 0.35, kKernelTol);  // empty q: the identity quaternion
}

// Every call builds the workspace it writes: two threads on one Model give
// the rows one thread gives.
TEST(ApiModel, TwoThreadsSimulateOneModel) {
  const Model model = Model::load(source_path("models/paper_platform.yaml"));
  runtime::SimulationRequest request = rk4(1e-5, 0.005);
  Rows alone, first, second;
  model.simulate(request, alone);
  std::thread a([&] { model.simulate(request, first); });
  std::thread b([&] { model.simulate(request, second); });
  a.join();
  b.join();
  EXPECT_EQ(first.values, alone.values);
  EXPECT_EQ(second.values, alone.values);
}

}  // namespace
}  // namespace mbfe
