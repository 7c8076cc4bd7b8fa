// `--set PATH=VALUE` with lists and maps: a flow VALUE replaces a list whole,
// an index reaches one item of a list of values, a sweep takes list values,
// messages about what a --set wrote (inside an expression, an item of a list,
// one of several keys added to one map) name that --set, and a point's model
// names its files by absolute paths.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "frontend/model_overrides.h"
#include "frontend/parse_model.h"
#include "frontend/parse_sweep.h"
#include "tests/support/process.h"
#include "tests/support/model_error.h"

namespace mbfe::frontend {
using namespace mbfe::ir;
namespace {

/// A small coupled model (line numbers on the right).
std::string model_text() {
  return "model: list_check\n"                                                                                   // 1
         "gravity: [0, -9.81]\n"                                                                                 // 2
         "bodies:\n"                                                                                             // 3
         "  - name: cart\n"                                                                                      // 4
         "    parent: ground\n"                                                                                  // 5
         "    joint: {type: prismatic, axis: [0, 1], at: [10, 0]}\n"                                             // 6
         "    mass: 100.0\n"                                                                                     // 7
         "    inertia: 0.0\n"                                                                                    // 8
         "    points: {contact: [0, 0]}\n"                                                                       // 9
         "loads:\n"                                                                                              // 10
         "  - {name: uplift, type: force, body: cart, value: [0, 262.15]}\n"                                     // 11
         "beams:\n"                                                                                              // 12
         "  - name: bridge\n"                                                                                    // 13
         "    origin: [0, 0]\n"                                                                                  // 14
         "    length: 20.0\n"                                                                                    // 15
         "    elements: 4\n"                                                                                     // 16
         "    section: {area: 0.01, inertia: 1.0e-4}\n"                                                          // 17
         "    material: {youngs_modulus: 2.1e11, density: 7850}\n"                                               // 18
         "    supports: [{at: 0.0, type: pinned}, {at: 20.0, type: pinned}]\n"                                   // 19
         "    loads: [{name: axle, type: moving, value: -1000, speed: 20}]\n"                                    // 20
         "contacts:\n"                                                                                           // 21
         "  - {name: tyre, type: slider_spring, body: cart, point: contact, beam: bridge, stiffness: 5.0e6}\n";  // 22
}

std::string edited(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

std::string error_of(const std::string& text, const ModelOverrides& overrides) {
  return test::model_error_of(text, "m.yaml", {}, overrides);
}

TEST(ModelOverrideValues, AListValueReplacesAListAndAnIndexReachesOneItem) {
  const Model file = parse_model_text(edited(model_text(), "value: [0, 262.15]", "value: [0, 300]"), "m.yaml");
  const Model whole = parse_model_text(model_text(), "m.yaml", {}, {{"loads.uplift.value", "[0, 300]"}});
  const Model item = parse_model_text(model_text(), "m.yaml", {}, {{"loads.uplift.value.1", "300"}});
  EXPECT_EQ(file.loads[0].force[1].evaluate(0.0), 300.0);
  EXPECT_EQ(whole.loads[0].force[1].evaluate(0.0), 300.0);
  EXPECT_EQ(item.loads[0].force[1].evaluate(0.0), 300.0);
  EXPECT_EQ(whole.loads[0].force[0].evaluate(0.0), 0.0);
  const Model origin = parse_model_text(model_text(), "m.yaml", {}, {{"beams.bridge.origin", " [ -0.5, 1.5 ] "}});
  EXPECT_EQ(origin.beams[0].origin[0], -0.5);
  EXPECT_EQ(origin.beams[0].origin[1], 1.5);
  // A list of maps replaced whole (supports), and a map (a beam's profile).
  const Model supports = parse_model_text(
      model_text(), "m.yaml", {},
      {{"beams.bridge.supports", "[{at: 0, type: clamped}]"}, {"beams.bridge.profile", "{expression: \"0.001*s\"}"}});
  ASSERT_EQ(supports.beams[0].supports.size(), 1u);
  EXPECT_EQ(supports.beams[0].supports[0].type, SupportType::kClamped);
  EXPECT_EQ(supports.beams[0].profile.kind, ProfileKind::kExpression);
  // The hash is of the overrides as written: a list is a changed model too.
  EXPECT_NE(whole.source_sha256, parse_model_text(model_text(), "m.yaml").source_sha256);
}

TEST(ModelOverrideValues, PathsIntoListsAreCheckedAtTheList) {
  EXPECT_EQ(error_of(model_text(), {{"loads.uplift.value.2", "1"}}),
            "m.yaml:11:52: --set loads.uplift.value.2=1: 'value' is a list of 2 items, which has no item 2 (items of "
            "a list of values are reached by their index, 0 to 1)");
  // A list of maps is entered by name, not by index.
  EXPECT_EQ(error_of(model_text(), {{"loads.0.value", "1"}}),
            "m.yaml:11:3: --set loads.0.value=1: 'loads' has no item named '0' (an item of a list is reached by its "
            "name: key)");
  const std::string scalar = error_of(model_text(), {{"loads.uplift.value", "300"}});
  EXPECT_EQ(
      scalar.rfind("m.yaml:11:52: --set loads.uplift.value=300: PATH leads to a list of 2 items, not to a "
                   "single value: give the whole of it as VALUE in YAML's flow form ([a, b, ...]) or go on to one "
                   "of its items by its index (PATH.0)",
                   0),
      0u)
      << scalar;
  const std::string broken = error_of(model_text(), {{"loads.uplift.value", "[0, 300"}});
  EXPECT_EQ(broken.rfind("m.yaml:11:52: --set loads.uplift.value=[0, 300: VALUE is not a YAML flow list or map", 0), 0u)
      << broken;
}

TEST(ModelOverrideValues, MessagesAboutWhatASetWroteNameIt) {
  // An item of a list VALUE, at its own column in the file's line.
  const std::string item = error_of(model_text(), {{"loads.uplift.value", "[0, abc]"}});
  EXPECT_EQ(item.rfind("m.yaml:11:56: ", 0), 0u) << item;
  EXPECT_NE(item.find("(the value came from --set loads.uplift.value=[0, abc])"), std::string::npos) << item;
  // Inside an expression: an unknown name, a constant that does not exist,
  // t in a profile (the profile a key new to its map).
  const std::string motion = error_of(model_text(), {{"bodies.cart.joint.motion", "20*q"}});
  EXPECT_NE(motion.find("'q'"), std::string::npos) << motion;
  EXPECT_NE(motion.find("(the value came from --set bodies.cart.joint.motion=20*q)"), std::string::npos) << motion;
  const std::string log0 = error_of(model_text(), {{"beams.bridge.loads.axle.value", "-1000*log(0)"}});
  // (a long --set is shortened in the message, as every value shown is)
  EXPECT_NE(log0.find("log of 0"), std::string::npos) << log0;
  EXPECT_NE(log0.find("(the value came from --set beams.bridge.loads.axle.value=-1000*log("), std::string::npos)
      << log0;
  const std::string profile = error_of(model_text(), {{"beams.bridge.profile", "{expression: \"0.001*t\"}"}});
  EXPECT_NE(profile.find("unknown name 't'"), std::string::npos) << profile;
  EXPECT_NE(profile.find("(the value came from --set beams.bridge.profile={expression:"), std::string::npos) << profile;
  // Two keys added to one map: the message is about the first, whatever the order.
  const std::string two =
      error_of(model_text(),
               {{"contacts.tyre.coefficient", "-1"}, {"contacts.tyre.law", "hertz"}, {"contacts.tyre.stiffness", ""}});
  EXPECT_NE(two.find("coefficient"), std::string::npos) << two;
  EXPECT_NE(two.find("(the value came from --set contacts.tyre.coefficient=-1)"), std::string::npos) << two;
  // An error elsewhere on a line a --set wrote into blames no --set.
  const std::string elsewhere =
      error_of(edited(model_text(), "body: cart, value: [0, 262.15]", "body: kart, value: [0, 262.15]"),
               {{"loads.uplift.value.1", "300"}});
  EXPECT_EQ(elsewhere.find("--set"), std::string::npos) << elsewhere;
}

TEST(ModelOverrideValues, ASweepVariesListsAndItems) {
  const Sweep sweep = parse_sweep_text(
      "sweep: uplift\nmodel: m.yaml\n"
      "set: {beams.bridge.origin: [0, 0.5]}\n"
      "vary:\n"
      "  - {path: loads.uplift.value, values: [[0, 250], [0, 300]]}\n"
      "  - {path: contacts.tyre.stiffness, values: [1e6]}\n",
      "sweep.yaml");
  EXPECT_NO_THROW(check_sweep_paths(sweep, model_text()));
  const Model point = parse_model_text(point_model_text(sweep, model_text(), 1), "point.yaml");
  EXPECT_EQ(point.loads[0].force[1].evaluate(0.0), 300.0);
  EXPECT_EQ(point.beams[0].origin[1], 0.5);
  const Sweep by_index = parse_sweep_text(
      "sweep: uplift\nmodel: m.yaml\nvary:\n  - {path: loads.uplift.value.1, values: [250, 300]}\n", "sweep.yaml");
  EXPECT_NO_THROW(check_sweep_paths(by_index, model_text()));
  EXPECT_EQ(
      point_model_text(by_index, model_text(), 1),
      point_model_text(
          parse_sweep_text("sweep: uplift\nmodel: m.yaml\nvary:\n  - {path: loads.uplift.value, values: [[0, 300]]}\n",
                           "sweep.yaml"),
          model_text(), 0));
  // A list where the model has a list takes list values only.
  const Sweep scalar = parse_sweep_text(
      "sweep: uplift\nmodel: m.yaml\nvary:\n  - {path: loads.uplift.value, values: [250, 300]}\n", "sweep.yaml");
  try {
    check_sweep_paths(scalar, model_text());
    ADD_FAILURE() << "accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("sweep.yaml:4:12: path 'loads.uplift.value' leads to a list of 2 items"),
              std::string::npos)
        << e.what();
  }
}

TEST(ModelOverrideValues, APointsModelNamesItsProfileFileByAnAbsolutePath) {
  const test::TempDir dir;
  std::filesystem::create_directories(dir / "models");
  test::spit(dir / "models" / "rail.csv", "s,offset\n0,0\n10,0.001\n20,0\n");
  const std::string model =
      edited(model_text(), "    length: 20.0\n", "    length: 20.0\n    profile: {file: rail.csv}\n");
  test::spit(dir / "models" / "m.yaml", model);
  const Sweep sweep = parse_sweep_text(
      "sweep: rail\nmodel: ../models/m.yaml\nvary:\n  - {path: contacts.tyre.stiffness, values: [1e6]}\n",
      (dir / "sweeps" / "rail.yaml").string());
  const std::string point = point_model_text(sweep, model, 0);
  // Read where a point's model lives: the table is still found.
  const std::filesystem::path elsewhere = dir / "out" / "points" / "0" / "model.yaml";
  const Model parsed = parse_model_text(point, elsewhere.string());
  EXPECT_EQ(parsed.beams[0].profile.kind, ProfileKind::kTable);
  EXPECT_EQ(parsed.beams[0].profile.table_offset[1], 0.001);
  EXPECT_NE(point.find((dir / "models" / "rail.csv").string()), std::string::npos) << point;
  // The model as written, read from its folder, is the same model.
  EXPECT_EQ(parse_model_text(model, (dir / "models" / "m.yaml").string()).beams[0].profile.table_s,
            parsed.beams[0].profile.table_s);
}

}  // namespace
}  // namespace mbfe::frontend
