// `train:` in a model file: the HSLM trains' axles against the standard's
// geometry built here another way, the expansion into moving loads and into
// multibody vehicles (against the hand-written models/bridge_two_axle_vehicle.yaml),
// and the errors.
#include "frontend/expand_train.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "frontend/hslm_trains.h"
#include "frontend/parse_model.h"
#include "tests/support/model_error.h"

namespace mbfe::frontend {
using namespace mbfe::ir;
namespace {

// Positions are sums of a few decimals: exact to a few ulp of ~400 m.
constexpr double kPositionTol = 1e-12;
// kg: masses the expansion writes as shortest round-trip text from a few
// products and quotients, against the same numbers by hand: round-off.
constexpr double kMassRoundOff = 1e-9;

std::string error_of(const std::string& text) { return test::model_error_of(text); }

/// An HSLM-A train built from EN 1991-2:2003 Figure 6.12 the other way round:
/// the front half (power car, end coach's own bogie), the articulated
/// bogies, and the rear half as the front half mirrored about the train's middle.
std::vector<double> hslm_by_symmetry(int n, double coach, double d) {
  const std::vector<double> front = {0.0, 3.0, 14.0, 17.0, 17.0 + 3.525, 17.0 + 3.525 + 3.0};
  const double end_bogie = 17.0 + 3.525 + 1.5;  // the end coach's own bogie centre
  std::vector<double> axles = front;
  for (int k = 1; k <= n + 1; ++k) {
    axles.push_back(end_bogie + k * coach - d / 2.0);
    axles.push_back(end_bogie + k * coach + d / 2.0);
  }
  // The rear end coach's bogie is (N + 2) D behind the front one; its power
  // car mirrors the front's.
  const double total = 2.0 * end_bogie + (n + 2) * coach;
  for (auto it = front.rbegin(); it != front.rend(); ++it) axles.push_back(total - *it);
  return axles;
}

void expect_hslm(const char* name, int n, double coach, double d, double load) {
  const HslmTrain* train = find_hslm_train(name);
  ASSERT_NE(train, nullptr) << name;
  const std::vector<TrainAxle> axles = hslm_axles(*train);
  const std::vector<double> expected = hslm_by_symmetry(n, coach, d);
  ASSERT_EQ(axles.size(), static_cast<std::size_t>(2 * n + 14)) << name;
  ASSERT_EQ(axles.size(), expected.size()) << name;
  for (std::size_t i = 0; i < axles.size(); ++i) {
    EXPECT_NEAR(axles[i].position, expected[i], kPositionTol) << name << " axle " << i + 1;
    EXPECT_EQ(axles[i].load, load) << name << " axle " << i + 1;
  }
}

// The rows of EN 1991-2:2003 Table 6.3 (N, D m, d m, P kN), typed here again.
TEST(HslmTrains, A1AxlesMatchTheStandardsGeometry) { expect_hslm("A1", 18, 18.0, 2.0, 170e3); }
TEST(HslmTrains, A2AxlesMatchTheStandardsGeometry) { expect_hslm("A2", 17, 19.0, 3.5, 200e3); }
TEST(HslmTrains, A3AxlesMatchTheStandardsGeometry) { expect_hslm("A3", 16, 20.0, 2.0, 180e3); }
TEST(HslmTrains, A4AxlesMatchTheStandardsGeometry) { expect_hslm("A4", 15, 21.0, 3.0, 190e3); }
TEST(HslmTrains, A5AxlesMatchTheStandardsGeometry) { expect_hslm("A5", 14, 22.0, 2.0, 170e3); }
TEST(HslmTrains, A6AxlesMatchTheStandardsGeometry) { expect_hslm("A6", 13, 23.0, 2.0, 180e3); }
TEST(HslmTrains, A7AxlesMatchTheStandardsGeometry) { expect_hslm("A7", 13, 24.0, 2.0, 190e3); }
TEST(HslmTrains, A8AxlesMatchTheStandardsGeometry) { expect_hslm("A8", 12, 25.0, 2.5, 190e3); }
TEST(HslmTrains, A9AxlesMatchTheStandardsGeometry) { expect_hslm("A9", 11, 26.0, 2.0, 210e3); }
TEST(HslmTrains, A10AxlesMatchTheStandardsGeometry) { expect_hslm("A10", 11, 27.0, 2.0, 210e3); }

TEST(HslmTrains, TenTrainsAndNoOther) {
  EXPECT_EQ(hslm_trains().size(), 10u);
  EXPECT_NE(find_hslm_train("A5"), nullptr);
  EXPECT_EQ(find_hslm_train("A11"), nullptr);
  EXPECT_EQ(find_hslm_train("a1"), nullptr);
}

const char* kBridge =
    "model: t\n"
    "beams:\n"
    "  - name: deck\n"
    "    origin: [10.0, 0.0]\n"
    "    length: 20.0\n"
    "    elements: 20\n"
    "    section: {area: 6.0, inertia: 0.45}\n"
    "    material: {youngs_modulus: 3.5e10, density: 2500}\n"
    "    supports: [{at: 0.0, type: pinned}, {at: 20.0, type: pinned}]\n";

TEST(ExpandTrain, HslmBecomesOneMovingLoadPerAxle) {
  const Model model = parse_model_text(std::string(kBridge) + "train: {hslm: A2, speed: 80.0, front: 5.0}\n", "x.yaml");
  const std::vector<TrainAxle> axles = hslm_axles(*find_hslm_train("A2"));
  const auto& loads = model.beams[0].moving_loads;
  ASSERT_EQ(loads.size(), axles.size());
  for (std::size_t i = 0; i < loads.size(); ++i) {
    // The leading axle is at x = 5 at t = 0; the beam's s = 0 at x = 10.
    EXPECT_NEAR(loads[i].start, 5.0 - axles[i].position - 10.0, kPositionTol) << i;
    EXPECT_EQ(loads[i].speed, 80.0);
    EXPECT_EQ(loads[i].t0, 0.0);
    EXPECT_EQ(loads[i].value.evaluate(0.0), -200e3);
    EXPECT_EQ(loads[i].name, "train_a" + std::to_string(i + 1));
  }
}

TEST(ExpandTrain, VehiclesFollowEachOtherByTheirLength) {
  const Model model = parse_model_text(std::string(kBridge) +
                                           "train:\n  name: freight\n  speed: 20\n  vehicles:\n"
                                           "    - {axles: [1.5, 6.5], loads: [1.0e5, 1.2e5], length: 9.0, count: 2}\n"
                                           "    - {axles: [2.0, 4.0, 6.0], load: 8.0e4}\n",
                                       "x.yaml");
  // Vehicle fronts at 0, 9, 18; the third's length defaults to 2 + 6.
  const std::vector<double> at = {1.5, 6.5, 10.5, 15.5, 20.0, 22.0, 24.0};
  const std::vector<double> load = {1.0e5, 1.2e5, 1.0e5, 1.2e5, 8.0e4, 8.0e4, 8.0e4};
  const auto& loads = model.beams[0].moving_loads;
  ASSERT_EQ(loads.size(), at.size());
  for (std::size_t i = 0; i < at.size(); ++i) {
    EXPECT_NEAR(loads[i].start, 0.0 - (at[i] - at[0]) - 10.0, kPositionTol) << i;
    EXPECT_EQ(loads[i].value.evaluate(1.0), -load[i]) << i;
    EXPECT_EQ(loads[i].name, "freight_a" + std::to_string(i + 1));
  }
}

/// Ground position of a body's frame origin at q = 0 (planar, prismatic and
/// revolute joints at rest: the `at` offsets add up).
Vec2 rest_position(const Model& model, int body) {
  Vec2 p{0.0, 0.0};
  for (int b = body; b >= 0; b = model.bodies[b].parent) {
    p[0] += model.bodies[b].joint.at[0];
    p[1] += model.bodies[b].joint.at[1];
  }
  return p;
}

int body_named(const Model& model, const std::string& name) {
  for (std::size_t b = 0; b < model.bodies.size(); ++b)
    if (model.bodies[b].name == name) return static_cast<int>(b);
  return -1;
}

// The hand-written two-axle vehicle of models/bridge_two_axle_vehicle.yaml
// (8000 kg body, two 500 kg wheels 4 m apart, on three beams), as a train.
TEST(ExpandTrain, VehiclesMatchTheHandWrittenTwoAxleModel) {
  const std::string path = std::string(MBFE_SOURCE_DIR) + "/models/bridge_two_axle_vehicle.yaml";
  const Model hand = load_model_file(path);
  std::string text;
  {
    // The same file with its bodies, loads and contacts replaced by a train.
    std::ifstream in(path);
    std::string line;
    bool skipping = false;
    while (std::getline(in, line)) {
      const bool top = !line.empty() && line[0] != ' ' && line[0] != '#';
      if (top)
        skipping = line.rfind("bodies:", 0) == 0 || line.rfind("loads:", 0) == 0 || line.rfind("contacts:", 0) == 0;
      if (!skipping) text += line + "\n";
    }
  }
  const double g = 9.81;
  const double axle = (8000.0 / 2.0 + 500.0) * g;  // N, each axle
  text +=
      "train:\n  name: car\n  speed: 20.0\n  front: -3.0\n  as: vehicles\n"
      "  vehicles:\n    - {axles: [1.0, 5.0], load: " +
      std::to_string(axle) +
      ", length: 6.0}\n"
      "  suspension: {wheel_mass: 500.0, inertia: 1.2e4, stiffness: 4.0e5, damping: 1.0e4, height: 1.0,\n"
      "               contact: {stiffness: 2.0e6, damping: 2.0e3}}\n";
  const Model train = parse_model_text(text, "x.yaml");

  ASSERT_EQ(train.bodies.size(), hand.bodies.size());
  ASSERT_EQ(train.contacts.size(), hand.contacts.size());
  ASSERT_EQ(train.loads.size(), hand.loads.size());
  // The carriage and the bounce slide stand elsewhere by design (the file's
  // carriage is 2 m behind the body's centre); the bodies that carry mass
  // and their points stand where the file puts them.
  const std::vector<std::pair<std::string, std::string>> same = {{"car_carriage", "carriage"},
                                                                 {"car_v1_bounce", "bounce"},
                                                                 {"car_v1", "pitch"},
                                                                 {"car_v1_w1", "front_wheel"},
                                                                 {"car_v1_w2", "rear_wheel"}};
  const int first_placed = 2;
  for (std::size_t k = 0; k < same.size(); ++k) {
    const auto& [mine, theirs] = same[k];
    const int a = body_named(train, mine), b = body_named(hand, theirs);
    ASSERT_GE(a, 0) << mine;
    ASSERT_GE(b, 0) << theirs;
    EXPECT_NEAR(train.bodies[a].mass, hand.bodies[b].mass, kMassRoundOff * 8000.0) << mine;
    EXPECT_EQ(train.bodies[a].inertia, hand.bodies[b].inertia) << mine;
    EXPECT_EQ(train.bodies[a].joint.type, hand.bodies[b].joint.type) << mine;
    EXPECT_EQ(train.bodies[a].joint.axis, hand.bodies[b].joint.axis) << mine;
    if (static_cast<int>(k) < first_placed) continue;
    const Vec2 pa = rest_position(train, a), pb = rest_position(hand, b);
    EXPECT_NEAR(pa[0], pb[0], kPositionTol) << mine;
    EXPECT_NEAR(pa[1], pb[1], kPositionTol) << mine;
  }
  EXPECT_EQ(train.bodies[0].joint.motion->evaluate(2.0), 40.0);
  for (std::size_t k = 0; k < train.loads.size(); ++k) {
    EXPECT_EQ(train.loads[k].stiffness, hand.loads[k].stiffness);
    EXPECT_EQ(train.loads[k].damping, hand.loads[k].damping);
  }
  // One contact per wheel and beam, as the file's six.
  for (const Contact& c : train.contacts) {
    EXPECT_EQ(c.type, ContactType::kSliderSpring);
    EXPECT_TRUE(c.unilateral);
    EXPECT_EQ(c.stiffness, 2.0e6);
    EXPECT_EQ(c.damping, 2.0e3);
    EXPECT_EQ(c.name, train.bodies[c.body].name + "_" + train.beams[c.beam].name);
  }
  EXPECT_EQ(train.contacts[0].name, "car_v1_w1_approach");
  EXPECT_EQ(train.contacts[5].name, "car_v1_w2_exit");
  EXPECT_TRUE(train.initial.static_start);
}

// Unequal axles: the body's mass and centre are what statics asks for each
// wheel to carry its axle's load: moments about the leading axle,
// (P2 - m g) a = (P1 + P2 - 2 m g) c.
TEST(ExpandTrain, VehicleBodyBalancesUnequalAxleLoads) {
  const double g = 9.81, m = 800.0, p1 = 1.2e5, p2 = 0.8e5, a = 10.0;
  const Model model = parse_model_text(std::string(kBridge) +
                                           "gravity: [0, -9.81]\n"
                                           "train:\n  speed: 10\n  front: 12.0\n  as: vehicles\n"
                                           "  vehicles: [{axles: [2.0, 12.0], loads: [1.2e5, 0.8e5]}]\n"
                                           "  suspension: {wheel_mass: 800, inertia: 2.0e5, stiffness: 1.0e6, height: "
                                           "1.5, contact: {stiffness: 1.0e9}}\n",
                                       "x.yaml");
  const int body = body_named(model, "train_v1");
  ASSERT_GE(body, 0);
  const double centre = a * (p2 - m * g) / (p1 + p2 - 2.0 * m * g);
  EXPECT_NEAR(model.bodies[body].mass, (p1 + p2) / g - 2.0 * m, kMassRoundOff);
  EXPECT_NEAR(rest_position(model, body)[0], 12.0 - centre, kPositionTol);
  EXPECT_NEAR(rest_position(model, body)[1], 1.5, kPositionTol);
  EXPECT_NEAR(rest_position(model, body_named(model, "train_v1_w2"))[0], 12.0 - a, kPositionTol);
  EXPECT_NEAR(rest_position(model, body_named(model, "train_v1_w2"))[1], 0.0, kPositionTol);
}

TEST(ExpandTrain, VehiclesTakeHertzianWheelContacts) {
  const std::string train =
      std::string(kBridge) +
      "gravity: [0, -9.81]\n"
      "train:\n  speed: 10\n  front: 12.0\n  as: vehicles\n"
      "  vehicles: [{axles: [2.0, 12.0], load: 1.0e5}]\n"
      "  suspension: {wheel_mass: 800, inertia: 2.0e5, stiffness: 1.0e6, contact: {law: hertz, coefficient: 1.0e10, "
      "damping: 500}}\n";
  const Model model = parse_model_text(train, "x.yaml");
  ASSERT_EQ(model.contacts.size(), 2u);  // two wheels, one beam
  for (const Contact& c : model.contacts) {
    EXPECT_EQ(c.law, ContactLaw::kHertz) << c.name;
    EXPECT_EQ(c.coefficient, 1.0e10) << c.name;
    EXPECT_EQ(c.stiffness, 0.0) << c.name;
    EXPECT_EQ(c.damping, 500.0) << c.name;
    EXPECT_TRUE(c.unilateral) << c.name;
  }
  // Each law's constant, and not the other's.
  const auto with_contact = [&](const std::string& contact) {
    std::string text = train;
    const std::string old_contact = "contact: {law: hertz, coefficient: 1.0e10, damping: 500}";
    return error_of(text.replace(text.find(old_contact), old_contact.size(), contact));
  };
  EXPECT_NE(with_contact("contact: {law: hertz, stiffness: 1.0e9}").find("stiffness belongs to law linear"),
            std::string::npos);
  EXPECT_NE(with_contact("contact: {coefficient: 1.0e10}").find("coefficient belongs to law hertz"), std::string::npos);
  EXPECT_NE(with_contact("contact: {law: hertz}").find("coefficient"), std::string::npos);
  EXPECT_NE(with_contact("contact: {law: rigid, stiffness: 1.0e9}").find("law"), std::string::npos);
}

TEST(ExpandTrain, ErrorsPointIntoTheFile) {
  const std::string bridge = kBridge;
  EXPECT_EQ(error_of(bridge + "train: {hslm: A11, speed: 80}\n"),
            "models/x.yaml:10:15: train.hslm: expected one of A1, A2, ..., A10 (EN 1991-2 HSLM-A), got 'A11'");
  EXPECT_EQ(error_of(bridge + "train: {hslm: A1, speed: 80, on: [bridge]}\n"),
            "models/x.yaml:10:35: train.on: the model has no beam 'bridge'");
  EXPECT_EQ(error_of(bridge + "train: {hslm: A1, speed: 80, as: vehicles}\n"),
            "models/x.yaml:10:34: train.as: vehicles: an HSLM train is a load model of point forces (EN 1991-2); "
            "it expands as: forces only");
  EXPECT_NE(error_of(bridge + "train: {hslm: A1, speed: -80}\n").find("models/x.yaml:10:"), std::string::npos);
  EXPECT_NE(error_of(bridge + "train: {hslm: A1, vehicles: [], speed: 80}\n").find("give either 'hslm'"),
            std::string::npos);
  EXPECT_NE(error_of(bridge + "train: {vehicles: [{axles: [3, 1], load: 1e5}], speed: 80}\n")
                .find("models/x.yaml:10:28: train: vehicle #1: axles: expected positions"),
            std::string::npos);
  EXPECT_NE(error_of(bridge + "train: {vehicles: [{axles: [1, 3], load: 1e5}], speed: 80, as: vehicles}\n")
                .find("the model has no gravity"),
            std::string::npos);
  // A generated name the file already uses is refused at the train's name.
  const std::string taken = std::string(kBridge) +
                            "    loads: [{type: moving, name: train_a2, value: -1, speed: 1}]\n"
                            "train: {hslm: A1, speed: 80}\n";
  EXPECT_NE(error_of(taken).find("models/x.yaml:11:8: the train generates the name 'train_a2', which the file "
                                 "already uses at line 10"),
            std::string::npos)
      << error_of(taken);
}

}  // namespace
}  // namespace mbfe::frontend
