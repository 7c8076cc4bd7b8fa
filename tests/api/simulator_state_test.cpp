// mbfe::Simulator's state, read and set: a state set back is the state read
// (the models of each kind: rigid, beams, coupled, closed loops); a run
// restarted from the state it reached goes on as it did; a state off the
// closed loops is projected onto them (the oracle: the loops' own Phi, from
// Model::evaluate); a state of the wrong size or not finite is refused.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "api/simulator.h"

namespace mbfe {
namespace {

// A state read, set and read again passes through the run's own conversions
// (modal coordinates of a beam-only model and back, a loop model's
// consistency step on an already consistent state): round-off of the state's
// size, far below any physical change.
constexpr double kRoundTripRel = 1e-12;
// Two runs that take the same steps from the same state do the same
// arithmetic (an autonomous model: time enters nowhere).
constexpr double kSameRunRel = 1e-13;
// The loops' projection closes Phi to its Newton tolerance (1e-10 m or so);
// the perturbation below opens it by about 1e-2 m.
constexpr double kClosedLoop = 1e-9;
constexpr double kPerturbation = 1e-2;

Model load(const std::string& file) { return Model::load(std::string(MBFE_SOURCE_DIR) + "/models/" + file); }

double relative(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).norm() / std::max(b.norm(), 1e-300);
}

class StateRoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(StateRoundTrip, AStateSetBackIsTheStateRead) {
  const Model model = load(GetParam());
  runtime::SimulationRequest request = model.request();
  Simulator sim(model, request);
  sim.advance_steps(20);
  Eigen::VectorXd q, qd;
  sim.state(q, qd);
  ASSERT_GT(q.size(), 0);
  const std::vector<double> outputs = sim.outputs();
  sim.set_state(q, qd);
  Eigen::VectorXd q2, qd2;
  sim.state(q2, qd2);
  ASSERT_EQ(q2.size(), q.size());
  ASSERT_EQ(qd2.size(), qd.size());
  EXPECT_LE(relative(q2, q), kRoundTripRel);
  EXPECT_LE(relative(qd2, qd), kRoundTripRel);
  const std::vector<double> again = sim.outputs();
  ASSERT_EQ(again.size(), outputs.size());
  for (std::size_t k = 0; k < outputs.size(); ++k)
    EXPECT_NEAR(again[k], outputs[k], kRoundTripRel * std::max(1.0, std::abs(outputs[k])))
        << "output " << k;
}

INSTANTIATE_TEST_SUITE_P(ModelKinds, StateRoundTrip,
                         ::testing::Values("double_pendulum.yaml", "paper_beam.yaml", "bridge_moving_mass.yaml",
                                           "four_bar.yaml", "double_pendulum_3d.yaml"),
                         [](const ::testing::TestParamInfo<const char*>& info) {
                           std::string name = info.param;
                           name = name.substr(0, name.find('.'));
                           for (char& c : name)
                             if (c == '_') c = 'X';
                           return name;
                         });

TEST(SimulatorState, ARunRestartedFromItsStateGoesOnAsItDid) {
  const Model model = load("double_pendulum.yaml");
  const runtime::SimulationRequest request = model.request();
  constexpr int kFirst = 300, kSecond = 300;
  Simulator through(model, request);
  through.advance_steps(kFirst);
  Eigen::VectorXd q_mid, qd_mid;
  through.state(q_mid, qd_mid);
  through.advance_steps(kSecond);
  Eigen::VectorXd q_end, qd_end;
  through.state(q_end, qd_end);

  Simulator restarted(model, request);
  restarted.set_state(q_mid, qd_mid);
  restarted.advance_steps(kSecond);
  Eigen::VectorXd q, qd;
  restarted.state(q, qd);
  EXPECT_LE(relative(q, q_end), kSameRunRel);
  EXPECT_LE(relative(qd, qd_end), kSameRunRel);
  // And it moved: the state after the second stretch is not the one set.
  EXPECT_GT(relative(q, q_mid), 1e-3);
}

TEST(SimulatorState, AStateOffTheLoopsIsProjectedOntoThem) {
  const Model model = load("four_bar.yaml");
  Simulator sim(model, model.request());
  sim.advance_steps(10);
  Eigen::VectorXd q, qd;
  sim.state(q, qd);
  Eigen::VectorXd off = q;
  off[0] += kPerturbation;
  const auto loop_phi = [&](const Eigen::VectorXd& at) {
    State s;
    s.q.assign(at.data(), at.data() + at.size());
    const Evaluation e = model.evaluate(s);
    EXPECT_TRUE(e.has_loops);
    return e.loop_phi.cwiseAbs().maxCoeff();
  };
  ASSERT_GT(loop_phi(off), 0.1 * kPerturbation) << "the perturbation does not open the loop";
  sim.set_state(off, qd);
  Eigen::VectorXd projected, rates;
  sim.state(projected, rates);
  EXPECT_LE(loop_phi(projected), kClosedLoop);
}

TEST(SimulatorState, AStateOfTheWrongSizeOrNotFiniteIsRefused) {
  const Model model = load("bridge_moving_mass.yaml");
  Simulator sim(model, model.request());
  Eigen::VectorXd q, qd;
  sim.state(q, qd);
  try {
    sim.set_state(q.head(q.size() - 1), qd);
    FAIL() << "a state one coordinate short was taken";
  } catch (const runtime::InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("expected " + std::to_string(q.size())), std::string::npos) << what;
  }
  Eigen::VectorXd bad = qd;
  bad[0] = std::numeric_limits<double>::quiet_NaN();
  try {
    sim.set_state(q, bad);
    FAIL() << "a NaN rate was taken";
  } catch (const runtime::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
  // The run is where it was: the refused states changed nothing.
  Eigen::VectorXd q2, qd2;
  sim.state(q2, qd2);
  EXPECT_EQ(q2, q);
  EXPECT_EQ(qd2, qd);
}

}  // namespace
}  // namespace mbfe
