// A train of moving forces on a linear bridge: its midspan acceleration is the
// sum of the accelerations of its axles crossing one at a time, each written
// by hand as a single moving load (whose own response
// tests/runtime/simulation/moving_force_test.cpp checks against the modal
// series). The train's expansion (positions, signs, loads) is what is tested.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "api/mbfe.h"

namespace mbfe {
namespace {

const char* kBridge =
    "beams:\n"
    "  - name: deck\n"
    "    origin: [4.0, 0.0]\n"
    "    length: 20.0\n"
    "    elements: 20\n"
    "    section: {area: 6.0, inertia: 0.45}\n"
    "    material: {youngs_modulus: 3.5e10, density: 2500}\n"
    "    supports: [{at: 0.0, type: pinned}, {at: 20.0, type: pinned}]\n"
    "    damping: {rayleigh: {alpha: 0.4551, beta: 7.910e-5}}\n";

class Probes : public runtime::SimulationObserver {
 public:
  void row(const runtime::OutputRow& row) override {
    acc.push_back(row.values[1]);  // values[0] is t
    w.push_back(row.values[2]);
  }
  std::vector<double> acc, w;
};

Probes run(const std::string& text) {
  const Model model = Model::parse(text, "train_check.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("trapezoid");
  request.step = 1e-3;
  request.t_end = 1.5;  // the train crosses in about 1 s
  request.every = 1;
  request.probes = {runtime::parse_probe("deck@10:acc"), runtime::parse_probe("deck@10")};
  Probes probes;
  const runtime::SimulationReport report = model.simulate(request, probes);
  EXPECT_TRUE(report.message.empty()) << report.message;
  return probes;
}

TEST(Train, MovingForcesSuperpose) {
  // Three axles at 0, 2.5 and 7 m behind the leading one, which is at x = 1
  // at t = 0; the deck starts at x = 4, so axle i is at s = 1 - a_i - 4 + v t.
  const std::vector<double> behind = {0.0, 2.5, 7.0}, load = {1.0e5, 2.0e5, 1.5e5};
  const Probes train = run(std::string("model: train\n") + kBridge +
                           "train:\n  speed: 25.0\n  front: 1.0\n  vehicles:\n"
                           "    - {axles: [0.5, 3.0, 7.5], loads: [1.0e5, 2.0e5, 1.5e5]}\n");
  std::vector<double> sum_acc(train.acc.size(), 0.0), sum_w(train.w.size(), 0.0);
  for (std::size_t i = 0; i < behind.size(); ++i) {
    char line[160];
    std::snprintf(line, sizeof line, "    loads: [{type: moving, value: %.17g, speed: 25.0, start: %.17g}]\n", -load[i],
                  1.0 - behind[i] - 4.0);
    const Probes one = run(std::string("model: axle\n") + kBridge + line);
    ASSERT_EQ(one.acc.size(), train.acc.size());
    for (std::size_t k = 0; k < one.acc.size(); ++k) {
      sum_acc[k] += one.acc[k];
      sum_w[k] += one.w[k];
    }
  }
  double peak_acc = 0.0, peak_w = 0.0, worst_acc = 0.0, worst_w = 0.0;
  for (std::size_t k = 0; k < train.acc.size(); ++k) {
    peak_acc = std::max(peak_acc, std::abs(sum_acc[k]));
    peak_w = std::max(peak_w, std::abs(sum_w[k]));
    worst_acc = std::max(worst_acc, std::abs(train.acc[k] - sum_acc[k]));
    worst_w = std::max(worst_w, std::abs(train.w[k] - sum_w[k]));
  }
  // The same linear steps on the same matrices: only the rounding of the
  // sums differs.
  constexpr double kSuperpositionTol = 1e-9;  // of the peak
  EXPECT_GT(peak_acc, 0.01);
  EXPECT_GT(peak_w, 1e-5);
  EXPECT_LT(worst_acc, kSuperpositionTol * peak_acc);
  EXPECT_LT(worst_w, kSuperpositionTol * peak_w);
}

}  // namespace
}  // namespace mbfe
