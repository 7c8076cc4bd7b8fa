// Acceleration probes: the forms parse_probe takes, and in a coupled run the
// acceleration columns of a beam point (BEAM@S:acc) and of a body
// (BODY:acc) against central differences of the run's own rate columns.
// (The beam model's deck acceleration against the closed-form series is in
// moving_force_test.cpp.)
#include "runtime/simulation/beam_probes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "frontend/parse_model.h"
#include "runtime/simulation/simulate.h"

namespace mbfe {
namespace {

TEST(ParseProbe, DisplacementAccelerationAndBody) {
  const runtime::ProbeSpec d = runtime::parse_probe("deck@10");
  EXPECT_EQ(d.beam, "deck");
  EXPECT_EQ(d.s, 10.0);
  EXPECT_FALSE(d.acceleration);
  const runtime::ProbeSpec a = runtime::parse_probe("deck@7.5:acc");
  EXPECT_EQ(a.beam, "deck");
  EXPECT_EQ(a.s, 7.5);
  EXPECT_TRUE(a.acceleration);
  EXPECT_FALSE(a.body);
  EXPECT_EQ(a.label, "deck@7.5:acc");
  const runtime::ProbeSpec b = runtime::parse_probe("wheel:acc");
  EXPECT_EQ(b.beam, "wheel");
  EXPECT_TRUE(b.acceleration && b.body);
  EXPECT_THROW(runtime::parse_probe("wheel"), runtime::InvalidRequest);
  EXPECT_THROW(runtime::parse_probe(":acc"), runtime::InvalidRequest);
  EXPECT_THROW(runtime::parse_probe("deck@x:acc"), runtime::InvalidRequest);
  // Any other suffix: the message names the one there is.
  try {
    runtime::parse_probe("deck@10:vel");
    ADD_FAILURE() << "accepted";
  } catch (const runtime::InvalidRequest& e) {
    EXPECT_NE(std::string(e.what()).find("'deck@10:vel': unknown suffix ':vel'; the only one is :acc (the "
                                         "acceleration, m/s^2)"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("e.g. deck@10:acc"), std::string::npos) << e.what();
  }
}

TEST(ParseProbe, AnAccelerationOnATruncatedBeamIsRefusedFromTheModelFileAlone) {
  // The ten-span catenary as shipped (both wires under policy truncate),
  // parsed only: no modal analysis, no solver.
  const ir::Model model =
      frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/pantograph_catenary_250.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("rk4");
  request.probes = {runtime::parse_probe("contact_wire@300"), runtime::parse_probe("contact_wire@300:acc")};
  try {
    runtime::check_request_early(model, request);
    ADD_FAILURE() << "accepted";
  } catch (const runtime::InvalidInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("probe 'contact_wire@300:acc': beam 'contact_wire' has policy truncate"), std::string::npos) << m;
    EXPECT_EQ(m.find("messenger"), std::string::npos) << m;
    EXPECT_NE(m.find("'contact_wire@300'"), std::string::npos) << m;  // the displacement it may probe
  }
  // The displacement, a body's acceleration, or the original model: fine.
  request.probes = {runtime::parse_probe("contact_wire@300"), runtime::parse_probe("head:acc")};
  EXPECT_NO_THROW(runtime::check_request_early(model, request));
  request.probes = {runtime::parse_probe("contact_wire@300:acc")};
  request.adjust = false;
  EXPECT_NO_THROW(runtime::check_request_early(model, request));
}

class Rows : public runtime::SimulationObserver {
 public:
  void begin(const runtime::OutputLayout& layout) override {
    columns = layout.columns;
    units = layout.units;
  }
  void row(const runtime::OutputRow& row) override { values.push_back(row.values); }
  std::size_t column(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
      if (columns[i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  std::vector<std::string> columns, units;
  std::vector<std::vector<double>> values;
};

TEST(AccelerationProbes, CoupledColumnsAreTheDerivativesOfTheRates) {
  // The shipped moving-mass bridge (adjusted, RK4), every step written.
  const Model model = Model::load(std::string(MBFE_SOURCE_DIR) + "/models/bridge_moving_mass.yaml");
  runtime::SimulationRequest request = model.request();
  request.step = 1e-4;
  request.t_end = 0.3;
  request.every = 1;
  request.probes = {runtime::parse_probe("deck@10"), runtime::parse_probe("deck@10:acc"),
                    runtime::parse_probe("wheel:acc")};
  Rows rows;
  const runtime::SimulationReport report = model.simulate(request, rows);
  ASSERT_TRUE(report.message.empty()) << report.message;
  const std::size_t deck_rate = rows.column("deck@10_dot"), deck_acc = rows.column("deck@10:acc");
  const std::size_t wheel_rate = rows.column("wheel_dot"), wheel_acc = rows.column("wheel:acc");
  // The accelerations come last, after the displacement probe and its rate.
  EXPECT_EQ(rows.columns[rows.columns.size() - 2], "deck@10:acc");
  EXPECT_EQ(rows.units[deck_acc], "m/s^2");
  EXPECT_EQ(rows.units[wheel_acc], "m/s^2");
  // Central differences of the rates over 2 h = 2e-4 s: O(h^2 a''') where the
  // motion is smooth. The tyre's force jumps at a lift-off or a landing, and
  // so does the acceleration: rows next to one are left out.
  const std::size_t force = rows.column("force_tyre");
  double worst_deck = 0.0, worst_wheel = 0.0, peak_deck = 0.0, peak_wheel = 0.0;
  int compared = 0;
  for (std::size_t i = 1; i + 1 < rows.values.size(); ++i) {
    const auto& a = rows.values[i - 1];
    const auto& b = rows.values[i];
    const auto& c = rows.values[i + 1];
    if ((a[force] > 0) != (b[force] > 0) || (b[force] > 0) != (c[force] > 0)) continue;
    const double h2 = c[0] - a[0];
    worst_deck = std::max(worst_deck, std::abs((c[deck_rate] - a[deck_rate]) / h2 - b[deck_acc]));
    worst_wheel = std::max(worst_wheel, std::abs((c[wheel_rate] - a[wheel_rate]) / h2 - b[wheel_acc]));
    peak_deck = std::max(peak_deck, std::abs(b[deck_acc]));
    peak_wheel = std::max(peak_wheel, std::abs(b[wheel_acc]));
    ++compared;
  }
  EXPECT_GT(compared, 2500);
  EXPECT_GT(peak_deck, 0.0);
  EXPECT_GT(peak_wheel, 0.0);
  // The fastest mode kept (omega_limit 2000 rad/s) has omega h = 0.2: a
  // central difference is (omega h)^2 / 6 = 0.7 % off on it.
  constexpr double kDifferenceTol = 0.02;  // of the peak
  EXPECT_LT(worst_deck, kDifferenceTol * peak_deck) << "peak " << peak_deck;
  EXPECT_LT(worst_wheel, kDifferenceTol * peak_wheel) << "peak " << peak_wheel;
}

}  // namespace
}  // namespace mbfe
