// A static start that cannot hold says what holds nothing, found before
// Newton: a wheel over no beam at t = 0 (the two-axle vehicle started with its
// rear axle behind the approach slab; a train's second vehicle behind it), a
// beam its supports leave free to turn (one pin); not "Newton lost hold ...
// check the units". And policy mass refuses a beam not held against rigid
// motion before a run, where it would blow up in one step.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "api/mbfe.h"

namespace mbfe {
namespace {

const std::string kVehicle = std::string(MBFE_SOURCE_DIR) + "/models/bridge_two_axle_vehicle.yaml";

class Ignore : public runtime::SimulationObserver {
 public:
  void row(const runtime::OutputRow&) override {}
};

/// The message of a static start of `path` with `overrides`, or "(started)".
std::string static_start_message(const std::string& path, const ir::ModelOverrides& overrides,
                                 std::optional<bool> adjust = std::nullopt) {
  LoadOptions options;
  options.overrides = overrides;
  const Model model = Model::load(path, options);
  runtime::SimulationRequest request = model.request();
  request.t_end = request.step;
  request.static_start = true;
  request.adjust = adjust;
  Ignore ignore;
  try {
    model.simulate(request, ignore);
  } catch (const ir::ModelError& e) {
    return e.what();
  }
  return "(started)";
}

TEST(StaticStartHints, AWheelBehindTheApproachIsNamedWithItsContacts) {
  // The carriage at x = -9: the rear wheel (2 m behind) is at x = -11, 1 m
  // behind the approach slab that starts at -10.
  const std::string m = static_start_message(kVehicle, {{"bodies.carriage.joint.at", "[-9.0, 0.0]"}});
  EXPECT_NE(m.find("static start of model 'bridge_two_axle_vehicle': "), std::string::npos) << m;
  EXPECT_NE(m.find("no equilibrium holds: body 'rear_wheel' is over no beam at t = 0: its contacts 'rear_approach' (s "
                   "= -1 m; beam "
                   "'approach' spans 0 to 10 m), 'rear_deck' (s = -11 m; beam 'deck' spans 0 to 20 m), 'rear_exit' "
                   "(s = -31 m; beam 'exit' spans 0 to 10 m) hold nothing up"),
            std::string::npos)
      << m;
  EXPECT_EQ(m.find("'front_wheel' is over no beam"), std::string::npos) << m;
  EXPECT_EQ(m.find("units"), std::string::npos) << m;
  // Both axles on the approach: it starts.
  EXPECT_EQ(static_start_message(kVehicle, {{"bodies.carriage.joint.at.0", "-7.0"}}), "(started)");
}

TEST(StaticStartHints, ATrainsSecondVehicleBehindTheApproachIsNamed) {
  // The hand-written vehicle's approach, deck and exit, with a train of two
  // such vehicles in its place: the second starts 6.5 m behind the first.
  LoadOptions options;
  std::string text =
      "model: two_vehicles\ngravity: [0, -9.81]\n"
      "train:\n  name: ice\n  speed: 20.0\n  front: -1.0\n  on: [approach, deck]\n  as: vehicles\n"
      "  vehicles: [{axles: [1.0, 5.0], load: 44145, length: 6.5, count: 2}]\n"
      "  suspension: {wheel_mass: 500, inertia: 1.2e4, stiffness: 4.0e5, damping: 1.0e4, height: 1.0,\n"
      "               contact: {stiffness: 2.0e6, damping: 2.0e3}}\n"
      "beams:\n"
      "  - {name: approach, origin: [-10.0, 0.0], length: 10.0, elements: 10, section: {area: 0.05, inertia: 1.0e-3},\n"
      "     material: {youngs_modulus: 2.1e11, density: 7850}, supports: [{at: 0.0, type: pinned}, {at: 10.0, type: "
      "pinned}]}\n"
      "  - {name: deck, origin: [0.0, 0.0], length: 20.0, elements: 20, section: {area: 0.1, inertia: 5.0e-3},\n"
      "     material: {youngs_modulus: 2.1e11, density: 7850}, supports: [{at: 0.0, type: pinned}, {at: 20.0, type: "
      "pinned}]}\n"
      "initial: {static: true}\nsimulation: {integrator: rk4, step: 1.0e-4, t_end: 1.0e-4}\n";
  const Model model = Model::parse(text, "two_vehicles.yaml", options);
  runtime::SimulationRequest request = model.request();
  Ignore ignore;
  try {
    model.simulate(request, ignore);
    ADD_FAILURE() << "started";
  } catch (const ir::ModelError& e) {
    const std::string m = e.what();
    // Vehicle 2's axles are at -7.5 and -11.5: its rear wheel is off the approach.
    EXPECT_NE(m.find("body 'ice_v2_w2' is over no beam at t = 0: its contacts 'ice_v2_w2_approach' (s = -1.5 m"),
              std::string::npos)
        << m;
    EXPECT_EQ(m.find("'ice_v1_w"), std::string::npos) << m;
    EXPECT_EQ(m.find("units"), std::string::npos) << m;
  }
}

TEST(StaticStartHints, ABeamOnOnePinIsNamed) {
  const std::string m = static_start_message(kVehicle, {{"beams.deck.supports", "[{at: 0.0, type: pinned}]"}}, false);
  EXPECT_NE(m.find("beam 'deck' has 1 support at s = 0 m, which leaves it free to turn or move as a rigid body"),
            std::string::npos)
      << m;
  EXPECT_EQ(m.find("units"), std::string::npos) << m;
}

TEST(PolicyMass, ABeamItsSupportsDoNotHoldIsRefusedBeforeTheRun) {
  LoadOptions options;
  options.overrides = {{"beams.deck.supports", "[{at: 0.0, type: pinned}]"}};
  const Model model = Model::load(kVehicle, options);
  runtime::SimulationRequest request = model.request();
  request.t_end = 0.01;
  request.static_start = false;
  Ignore ignore;
  try {
    model.simulate(request, ignore);
    ADD_FAILURE() << "ran";
  } catch (const runtime::InvalidInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("bridge_two_axle_vehicle.yaml:64:17: beam 'deck': policy mass keeps every mode's stiffness"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("use policy: cap"), std::string::npos) << m;
  }
  // The cap has no such need: the same beam runs under it (the vehicle is on
  // the approach, the loose deck swings on its pin under its weight).
  options.overrides.push_back({"beams.deck.adjustment.policy", "cap"});
  const Model capped = Model::load(kVehicle, options);
  const runtime::SimulationReport report = capped.simulate(request, ignore);
  EXPECT_TRUE(report.message.empty()) << report.message;
}

}  // namespace
}  // namespace mbfe
