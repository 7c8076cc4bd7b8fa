// The model front end: good files give the right IR (parse_model_errors_test.cpp:
// bad ones give exact messages).
#include "frontend/parse_model.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "frontend/sha256.h"
#include "tests/support/model_error.h"

namespace mbfe::frontend {
using namespace mbfe::ir;
namespace {

const std::string kModelsDir = std::string(MBFE_SOURCE_DIR) + "/models/";

// Parsing copies decimal text into doubles; arithmetic on them (a/|a|, a^4/12)
// is exact to a few ulp.
constexpr double kUlpTol = 1e-15;

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ParseModel, DoublePendulumFile) {
  const std::string path = kModelsDir + "double_pendulum.yaml";
  const Model model = load_model_file(path);
  EXPECT_EQ(model.name, "double_pendulum");
  EXPECT_EQ(model.source_path, path);
  EXPECT_EQ(model.source_sha256, sha256_hex(read_bytes(path)));
  EXPECT_EQ(model.gravity, (Vec2{0.0, -9.81}));
  ASSERT_EQ(model.bodies.size(), 2u);

  const Body& link1 = model.bodies[0];
  const Body& link2 = model.bodies[1];
  EXPECT_EQ(link1.name, "link1");
  EXPECT_EQ(link1.parent, -1);
  EXPECT_EQ(link2.parent, 0);
  EXPECT_EQ(link2.joint.type, JointType::kRevolute);
  EXPECT_EQ(link2.joint.at, (Vec2{1.0, 0.0}));
  EXPECT_EQ(link1.mass, 1.0);
  EXPECT_NEAR(link1.inertia, 1.0 / 12.0, kUlpTol);
  EXPECT_EQ(link1.com, (Vec2{0.5, 0.0}));
  ASSERT_EQ(link1.points.size(), 1u);
  EXPECT_EQ(link1.points[0].name, "tip");
  EXPECT_EQ(link1.points[0].position, (Vec2{1.0, 0.0}));
  EXPECT_EQ(link1.loc.line, 5);  // the first key of the body's map

  EXPECT_EQ(model.initial.q, (std::vector<double>{0.3, 0.0}));
  EXPECT_EQ(model.initial.qd, (std::vector<double>{0.0, 0.0}));
  EXPECT_EQ(model.simulation.integrator, "rk4");
  EXPECT_EQ(model.simulation.step, 1.0e-3);
  EXPECT_EQ(model.simulation.t_end, 2.0);
}

TEST(ParseModel, ShippedRigidModelsParse) {
  for (const char* name : {"cart_pendulum", "chain_5", "chain_10", "chain_20"}) {
    SCOPED_TRACE(name);
    const Model model = load_model_file(kModelsDir + name + ".yaml");
    EXPECT_EQ(model.name, name);
  }
  const Model chain = load_model_file(kModelsDir + "chain_20.yaml");
  ASSERT_EQ(chain.bodies.size(), 20u);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(chain.bodies[i].parent, i - 1);
  EXPECT_EQ(load_model_file(kModelsDir + "cart_pendulum.yaml").bodies[0].joint.type,
            JointType::kPrismatic);
}

TEST(ParseModel, NamesThatOnlyLookLikeOutputColumnsAreTaken) {
  // The refused clashes are in tests/malformed/output_name_*.yaml; these
  // write no column twice: a body a_dot without a body a, phi_abs and force_x
  // in a model without beams (no such columns), deck_w11 beside a beam deck
  // of 10 elements (nodes 0..10), deck_w03 (not how a node is written), time.
  const std::string beam =
      "beams:\n  - {name: deck, origin: [0, 0], length: 1.0, elements: 10, section: {shape: square, side: 0.005},\n"
      "     material: {youngs_modulus: 2.1e11, density: 7860}, supports: [{at: 0.0, type: pinned}, {at: 1.0, type: pinned}]}\n";
  auto model = [](const std::vector<std::string>& names, const std::string& rest) {
    std::string text = "model: m\nbodies:\n";
    std::string parent = "ground";
    for (const std::string& n : names) {
      text += "  - {name: " + n + ", parent: " + parent + ", joint: {type: revolute}, mass: 1, inertia: 0.1}\n";
      parent = n;
    }
    return text + rest;
  };
  EXPECT_EQ(test::model_error_of(model({"a_dot", "phi_abs", "force_x", "time", "lambda_c_1", "tension_d"}, "")), "(accepted)");
  EXPECT_EQ(test::model_error_of(model({"deck_w11", "deck_w03", "deck_dw11", "a_drive"}, beam)), "(accepted)");
  EXPECT_NE(test::model_error_of(model({"deck_w10"}, beam)).find("a coordinate of beam 'deck' (node 10)"), std::string::npos);
  EXPECT_NE(test::model_error_of(model({"deck_dw0_dot"}, beam)).find("a coordinate of beam 'deck' (node 0)"), std::string::npos);
}

TEST(ParseModel, Sha256OfKnownVector) {
  // FIPS 180-2, appendix B.1.
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(parse_model_text("model: m\nbodies: [{name: a, parent: ground, joint: {type: "
                             "revolute}, mass: 1, inertia: 1}]\n",
                             "m.yaml")
                .source_sha256.size(),
            64u);
}

TEST(ParseModel, DefaultsAndNormalisedAxis) {
  const Model model = parse_model_text(R"(model: m
bodies:
  - {name: cart, parent: ground, joint: {type: prismatic, axis: [3, 4]}, mass: 2, inertia: 0}
  - {name: arm, parent: cart, joint: {type: revolute}, mass: 0, inertia: 0}
)",
                                       "m.yaml");
  EXPECT_EQ(model.gravity, (Vec2{0.0, 0.0}));
  EXPECT_EQ(model.simulation.integrator, "rk4");
  EXPECT_EQ(model.simulation.step, 1e-3);
  EXPECT_EQ(model.simulation.t_end, 1.0);
  const Body& cart = model.bodies[0];
  EXPECT_NEAR(cart.joint.axis[0], 0.6, kUlpTol);
  EXPECT_NEAR(cart.joint.axis[1], 0.8, kUlpTol);
  EXPECT_EQ(cart.joint.at, (Vec2{0.0, 0.0}));
  EXPECT_EQ(cart.com, (Vec2{0.0, 0.0}));
  EXPECT_TRUE(cart.points.empty());
  EXPECT_EQ(model.bodies[1].mass, 0.0);  // massless bodies are allowed
  EXPECT_EQ(model.initial.q.size(), 2u);
}

TEST(ParseModel, Loads) {
  const Model model = parse_model_text(R"(model: m
bodies:
  - {name: a, parent: ground, joint: {type: revolute}, mass: 1, inertia: 1, points: {p: [1, 0], q: [2, 0]}}
loads:
  - {type: force, body: a, point: q, value: [0, -10]}
  - {type: force, body: a, value: [1, 2]}
  - {type: torque, body: a, value: 0.5}
  - {type: spring_damper, joint: a, stiffness: 10, damping: 0.1, rest: 0.2}
)",
                                       "m.yaml");
  ASSERT_EQ(model.loads.size(), 4u);
  EXPECT_EQ(model.loads[0].type, LoadType::kForce);
  EXPECT_EQ(model.loads[0].point, 1);
  EXPECT_EQ(model.loads[0].force[0].evaluate(0.0), 0.0);
  EXPECT_EQ(model.loads[0].force[1].evaluate(0.0), -10.0);
  EXPECT_EQ(model.loads[1].point, -1);  // the body-frame origin
  EXPECT_EQ(model.loads[2].type, LoadType::kTorque);
  EXPECT_EQ(model.loads[2].torque.evaluate(0.0), 0.5);
  EXPECT_EQ(model.loads[3].type, LoadType::kSpringDamper);
  EXPECT_EQ(model.loads[3].body, 0);
  EXPECT_EQ(model.loads[3].stiffness, 10.0);
  EXPECT_EQ(model.loads[3].damping, 0.1);
  EXPECT_EQ(model.loads[3].rest, 0.2);
}

const char* const kBeamModel = R"(model: m
description: a pinned-pinned beam with a body pinned to it
gravity: [0, -9.81]
bodies:
  - {name: arm, parent: ground, joint: {type: revolute}, mass: 1, inertia: 0.1, points: {tip: [1, 0]}}
beams:
  - name: beam1
    origin: [0, -1]
    length: 1.0
    elements: 10
    section: {shape: square, side: 0.005}
    material: {youngs_modulus: 2.1e11, density: 7860}
    supports: [{at: 0.0, type: pinned}, {at: 0.3, type: clamped}, {at: 1.0, type: pinned}]
    damping: {rayleigh: {alpha: 3.0e-3, beta: 1.5e-4}}
    loads: [{type: point, at: 0.7, value: -10.0}]
    adjustment: {omega_limit: 1.0e5, margin: 0.2, zeta_min: 0.05, policy: keep_slow}
    mass: lumped
  - name: beam2
    origin: [0, 0]
    angle: 0.5
    length: 2.0
    elements: 4
    section: {area: 1.0e-4, inertia: 2.0e-9}
    material: {youngs_modulus: 7.0e10, density: 2700}
contacts:
  - {name: c1, type: pin, body: arm, point: tip, beam: beam1, at: 0.5}
  - {name: c2, type: slider_pin, body: arm, point: tip, beam: beam2}
initial: {q: {arm: -0.1}, qd: {arm: 2}}
)";

TEST(ParseModel, BeamsSectionsNodesAndAdjustment) {
  const Model model = parse_model_text(kBeamModel, "m.yaml");
  ASSERT_EQ(model.beams.size(), 2u);
  const Beam& beam1 = model.beams[0];
  EXPECT_EQ(beam1.origin, (Vec2{0.0, -1.0}));
  EXPECT_EQ(beam1.angle, 0.0);
  EXPECT_EQ(beam1.elements, 10);
  EXPECT_NEAR(beam1.area, 0.005 * 0.005, kUlpTol * 2.5e-5);
  EXPECT_NEAR(beam1.second_moment, 0.005 * 0.005 * 0.005 * 0.005 / 12.0, kUlpTol * 5.2e-11);
  EXPECT_EQ(beam1.youngs_modulus, 2.1e11);
  EXPECT_EQ(beam1.density, 7860.0);
  ASSERT_EQ(beam1.supports.size(), 3u);
  // 0.3 / 0.1 is 2.9999999999999996 in doubles: resolved to node 3 anyway.
  EXPECT_EQ(beam1.supports[0].node, 0);
  EXPECT_EQ(beam1.supports[1].node, 3);
  EXPECT_EQ(beam1.supports[1].type, SupportType::kClamped);
  EXPECT_EQ(beam1.supports[2].node, 10);
  ASSERT_EQ(beam1.loads.size(), 1u);
  EXPECT_EQ(beam1.loads[0].node, 7);
  EXPECT_EQ(beam1.loads[0].value.evaluate(0.0), -10.0);
  EXPECT_EQ(beam1.rayleigh_alpha, 3.0e-3);
  EXPECT_EQ(beam1.rayleigh_beta, 1.5e-4);
  EXPECT_TRUE(beam1.adjustment.present);
  EXPECT_EQ(beam1.adjustment.omega_limit, 1.0e5);
  EXPECT_EQ(beam1.adjustment.margin, 0.2);
  EXPECT_EQ(beam1.adjustment.zeta_min, 0.05);
  EXPECT_EQ(beam1.adjustment.policy, AdjustmentPolicy::kKeepSlow);
  EXPECT_EQ(beam1.mass, MassLumping::kLumped);

  const Beam& beam2 = model.beams[1];
  EXPECT_EQ(beam2.angle, 0.5);
  EXPECT_EQ(beam2.area, 1.0e-4);
  EXPECT_EQ(beam2.second_moment, 2.0e-9);
  EXPECT_TRUE(beam2.supports.empty());
  EXPECT_EQ(beam2.rayleigh_alpha, 0.0);
  EXPECT_FALSE(beam2.adjustment.present);
  EXPECT_EQ(beam2.mass, MassLumping::kConsistent);

  ASSERT_EQ(model.contacts.size(), 2u);
  EXPECT_EQ(model.contacts[0].type, ContactType::kPin);
  EXPECT_EQ(model.contacts[0].body, 0);
  EXPECT_EQ(model.contacts[0].point, 0);
  EXPECT_EQ(model.contacts[0].beam, 0);
  EXPECT_EQ(model.contacts[0].at, 0.5);
  EXPECT_EQ(model.contacts[1].type, ContactType::kSliderPin);
  EXPECT_EQ(model.contacts[1].beam, 1);
  EXPECT_EQ(model.initial.q, (std::vector<double>{-0.1}));
  EXPECT_EQ(model.initial.qd, (std::vector<double>{2.0}));
}

TEST(ParseModel, BeamOnlyModel) {
  const Model model = parse_model_text(R"(model: b
beams:
  - {name: b, origin: [0, 0], length: 1, elements: 2, section: {area: 1, inertia: 1}, material: {youngs_modulus: 1, density: 1}}
)",
                                       "b.yaml");
  EXPECT_TRUE(model.bodies.empty());
  EXPECT_TRUE(model.initial.q.empty());
  EXPECT_EQ(model.beams.size(), 1u);
}

TEST(ParseModel, AdjustmentPolicyMass) {
  const Model model = parse_model_text(R"(model: b
beams:
  - {name: b, origin: [0, 0], length: 1, elements: 2, section: {area: 1, inertia: 1}, material: {youngs_modulus: 1, density: 1},
     adjustment: {omega_limit: 2000, policy: mass}}
)",
                                       "b.yaml");
  EXPECT_EQ(model.beams.at(0).adjustment.policy, AdjustmentPolicy::kMass);
  EXPECT_TRUE(model.beams.at(0).adjustment.active());
}

TEST(ParseModel, AdjustmentWithoutPolicyIsMassAndJoinedScopeCap) {
  // The default policy is mass (docs/damping-adjustment.md, "Which policy is
  // the default, and why"); a joined structure takes only the cap, so there
  // the cap is the default. Named policies stay as named.
  const auto policy_of = [](const std::string& block) {
    const Model model = parse_model_text(R"(model: b
beams:
  - {name: b, origin: [0, 0], length: 1, elements: 2, section: {area: 1, inertia: 1}, material: {youngs_modulus: 1, density: 1},
     adjustment: )" + block + R"(}
)",
                                         "b.yaml");
    return model.beams.at(0).adjustment.policy;
  };
  EXPECT_EQ(policy_of("{omega_limit: 2000}"), AdjustmentPolicy::kMass);
  EXPECT_EQ(policy_of("{omega_limit: 2000, scope: beam}"), AdjustmentPolicy::kMass);
  // Scope joined needs linked beams: the two-span catenary with joined wires.
  std::ifstream joined_file(std::string(MBFE_SOURCE_DIR) + "/tests/reference_outputs/models/two_span_joined.yaml");
  const std::string joined((std::istreambuf_iterator<char>(joined_file)), std::istreambuf_iterator<char>());
  ASSERT_NE(joined.find("margin: 0.1, scope: joined}"), std::string::npos);
  for (const auto& beam : parse_model_text(joined, "two_span_joined.yaml").beams) {
    if (beam.adjustment.present) EXPECT_EQ(beam.adjustment.policy, AdjustmentPolicy::kCap) << beam.name;
  }
  EXPECT_EQ(policy_of("{omega_limit: 2000, policy: cap}"), AdjustmentPolicy::kCap);
  EXPECT_EQ(policy_of("{omega_limit: 2000, policy: keep_slow}"), AdjustmentPolicy::kKeepSlow);
  EXPECT_EQ(policy_of("{omega_limit: 2000, policy: paper_eq25}"), AdjustmentPolicy::kPaperEq25);
  EXPECT_EQ(policy_of("{omega_limit: 2000, policy: none}"), AdjustmentPolicy::kNone);
  EXPECT_EQ(policy_of("{omega_limit: 2000, policy: truncate}"), AdjustmentPolicy::kTruncate);
}

}  // namespace
}  // namespace mbfe::frontend
