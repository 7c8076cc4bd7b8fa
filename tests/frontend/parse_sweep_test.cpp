// Sweep files: the points they describe (product and zip, ranges, templates,
// values set for every point), the model file of a point, and bad files
// refused at their file:line:col.
#include "frontend/parse_sweep.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "frontend/parse_model.h"

namespace mbfe::frontend {
namespace {

const std::string kModel = R"(model: m
bodies:
  - name: cart
    parent: ground
    joint: {type: prismatic, axis: [1, 0], motion: "20*t"}
    mass: 1.0
    inertia: 0
  - name: arm
    parent: cart
    joint: {type: revolute}
    mass: 2.0
    inertia: 0.1
beams:
  - name: deck
    origin: [0, 0]
    length: 10.0
    elements: 10
    section: {area: 0.01, inertia: 1.0e-4}
    material: {youngs_modulus: 2.1e11, density: 7850}
    supports: [{at: 0.0, type: pinned}, {at: 10.0, type: pinned}]
    damping: {rayleigh: {alpha: 0.0, beta: 0.0}}
)";

std::string sweep_text(const std::string& vary, const std::string& extra = "") {
  return "sweep: s\nmodel: m.yaml\nvary:\n" + vary + extra;
}

TEST(ParseSweep, ProductOfRangeAndValuesWithTemplate) {
  const ir::Sweep s = parse_sweep_text(
      sweep_text("  - {path: bodies.cart.joint.motion, range: {from: 10, to: 30, count: 3}, template: \"{}*t\"}\n"
                 "  - {path: beams.deck.damping.rayleigh.alpha, values: [0.0, 0.5]}\n"),
      "s.yaml");
  ASSERT_EQ(s.points(), 6);
  EXPECT_EQ(s.vary[0].values, (std::vector<std::string>{"10*t", "20*t", "30*t"}));
  EXPECT_EQ(s.indices(0), (std::vector<int>{0, 0}));
  EXPECT_EQ(s.indices(1), (std::vector<int>{0, 1}));  // the last variable varies fastest
  EXPECT_EQ(s.indices(5), (std::vector<int>{2, 1}));
  // Point 3: speed 20, alpha 0.5, in a model that parses to exactly that.
  const ir::Model m = parse_model_text(point_model_text(s, kModel, 3), "p.yaml");
  EXPECT_EQ(m.bodies[0].joint.motion->evaluate(2.0), 40.0);
  EXPECT_EQ(m.beams[0].rayleigh_alpha, 0.5);
  EXPECT_EQ(m.bodies[1].mass, 2.0);  // the rest as it was
  EXPECT_EQ(sweep_model_path(s), "m.yaml");
}

TEST(ParseSweep, ZipTakesTheIthValuesTogether) {
  const ir::Sweep s = parse_sweep_text(sweep_text("  - {path: bodies.arm.mass, values: [1, 2, 3]}\n"
                                                  "  - {path: bodies.arm.inertia, values: [0.1, 0.2, 0.3]}\n",
                                                  "mode: zip\n"),
                                       "s.yaml");
  ASSERT_EQ(s.points(), 3);
  const ir::Model m = parse_model_text(point_model_text(s, kModel, 2), "p.yaml");
  EXPECT_EQ(m.bodies[1].mass, 3.0);
  EXPECT_EQ(m.bodies[1].inertia, 0.3);
}

TEST(ParseSweep, SetGivesEveryPointTheSameValueBeforeItsOwn) {
  const ir::Sweep s = parse_sweep_text(sweep_text("  - {path: bodies.arm.mass, values: [1, 2]}\n",
                                                  "set: {bodies.arm.inertia: 0.7, bodies.cart.joint.motion: \"5*t\"}\n"),
                                       "s.yaml");
  ASSERT_EQ(s.points(), 2);
  ASSERT_EQ(s.set.size(), 2u);
  EXPECT_EQ(s.set[0].path, "bodies.arm.inertia");
  check_sweep_paths(s, kModel);
  for (long i = 0; i < 2; ++i) {
    const ir::Model m = parse_model_text(point_model_text(s, kModel, i), "p.yaml");
    EXPECT_EQ(m.bodies[1].mass, 1.0 + static_cast<double>(i));  // varied
    EXPECT_EQ(m.bodies[1].inertia, 0.7);                         // set
    EXPECT_EQ(m.bodies[0].joint.motion->evaluate(2.0), 10.0);
  }
}

void expect_error(const std::string& text, const std::string& where, const std::string& what, bool paths = false) {
  try {
    const ir::Sweep s = parse_sweep_text(text, "s.yaml");
    if (paths) check_sweep_paths(s, kModel);
    FAIL() << "accepted: " << text;
  } catch (const ir::ModelError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("s.yaml:" + where + ": ", 0), 0u) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  }
}

TEST(ParseSweep, BadFilesAreRefusedWhereTheyAreWrong) {
  expect_error(sweep_text("  - {path: bodies.carts.joint.motion, values: [\"1*t\"]}\n"), "4:12",
               "path 'bodies.carts.joint.motion': 'bodies' has no item named 'carts'", true);
  expect_error(sweep_text("  - {path: beams.deck.damping.rayleigh.alpah, values: [1]}\n"), "4:12",
               "'rayleigh' has no key 'alpah'", true);
  expect_error(sweep_text("  - {path: beams.deck.supports, values: [1]}\n"), "4:12", "not to a single value", true);
  expect_error(sweep_text("  - {path: bodies.arm.mass, values: [1, 2]}\n  - {path: bodies.arm.inertia, values: [1]}\n",
                          "mode: zip\n"),
               "5:12", "mode zip: path 'bodies.arm.inertia' has 1 values, the first has 2");
  expect_error(sweep_text("  - {path: bodies.arm.mass, values: []}\n"), "4:37", "values: the list is empty");
  expect_error(sweep_text("  - {path: bodies.arm.mass, range: {from: 1, to: 2, count: 0}}\n"), "4:60",
               "range.count must be in 1..");
  expect_error(sweep_text("  - {path: bodies.arm.mass, values: [1], range: {from: 1, to: 2, count: 2}}\n"), "4:5",
               "give either 'values: [...]' or 'range: {from, to, count}'");
  expect_error(sweep_text("  - {path: bodies.arm.mass, values: [1], template: \"t\"}\n"), "4:52",
               "template: expected '{}' where each value goes");
  expect_error(sweep_text("  - {path: bodies.arm.mass, values: [1]}\n", "collect:\n  - {name: a, column: x, stat: median}\n"),
               "6:32", "expected one of max, min, absmax, mean, rms, initial, final");
  expect_error(sweep_text("  - {path: bodies.arm.mass, values: [1]}\n", "speed: 3\n"), "5:1", "speed");
  expect_error(sweep_text("  - {path: bodies.arm.mass, values: [1]}\n", "set: {bodies.arm.mas: 3}\n"), "5:7",
               "path 'bodies.arm.mas': 'arm' has no key 'mas'", true);
  expect_error(sweep_text("  - {path: bodies.arm.mass, values: [1]}\n", "set: {bodies.arm.mass: 3}\n"), "5:7",
               "set: path 'bodies.arm.mass' is also varied");
  // A list or map is a value (it replaces what the path leads to whole); nothing is not.
  expect_error(sweep_text("  - {path: bodies.arm.mass, values: [1]}\n", "set: {bodies.arm.inertia: ~}\n"), "5:7",
               "set: bodies.arm.inertia: expected a number, a string, a list or a map, got");
  // Two probes of one label would be two columns of one name.
  expect_error(sweep_text("  - {path: bodies.arm.mass, values: [1]}\n", "simulate: {probes: [deck@5, deck@2, deck@5]}\n"),
               "5:37", "probes: 'deck@5' is given twice");
}

// Every sweep the project ships parses, its paths exist in its model, and
// every point's model is a valid model (the points' values written in).
TEST(ParseSweep, EveryShippedSweepGivesValidModelsAtEveryPoint) {
  const std::filesystem::path folder = std::filesystem::path(MBFE_SOURCE_DIR) / "models" / "sweeps";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    SCOPED_TRACE(entry.path().string());
    const ir::Sweep sweep = load_sweep_file(entry.path().string());
    const std::string model = read_sweep_model(sweep);
    check_sweep_paths(sweep, model);
    ASSERT_GT(sweep.points(), 0);
    for (long i = 0; i < sweep.points(); ++i) {
      const ir::Model m = parse_model_text(point_model_text(sweep, model, i), "point " + std::to_string(i));
      EXPECT_FALSE(m.name.empty());
    }
  }
  EXPECT_GE(files, 3) << "the shipped sweeps were not found";
}

}  // namespace
}  // namespace mbfe::frontend
