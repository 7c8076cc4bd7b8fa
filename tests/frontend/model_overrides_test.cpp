// `--set PATH=VALUE`: an overridden file is the file edited that way, and a
// bad PATH or VALUE is an error in the file that names the --set. Also the
// names of loads, which are what PATH reaches them by.
#include "frontend/model_overrides.h"

#include <gtest/gtest.h>

#include <string>

#include "frontend/parse_model.h"
#include "frontend/parse_sweep.h"
#include "frontend/sha256.h"
#include "tests/support/model_error.h"

namespace mbfe::frontend {
using namespace mbfe::ir;
namespace {

/// A small coupled model with a named body load, a named beam load and a
/// contact; `stiffness` and `inertia` spelled as given.
std::string model_text(const std::string& stiffness = "2.0e6", const std::string& inertia = "1.0e-4",
                       const std::string& contact_extra = "stiffness: 5.0e6") {
  return "model: override_check\n"                                               // 1
         "gravity: [0, -9.81]\n"                                                 // 2
         "bodies:\n"                                                             // 3
         "  - name: cart\n"                                                      // 4
         "    parent: ground\n"                                                  // 5
         "    joint: {type: prismatic, axis: [0, 1], at: [10, 0]}\n"             // 6
         "    mass: 100.0\n"                                                     // 7
         "    inertia: 0.0\n"                                                    // 8
         "    points: {contact: [0, 0]}\n"                                       // 9
         "loads:\n"                                                              // 10
         "  - {name: front_susp, type: spring_damper, joint: cart, stiffness: " +  // 11
         stiffness + ", damping: 10}\n" +
         "  - {type: force, body: cart, value: [0, -5]}\n"                       // 12
         "beams:\n"                                                              // 13
         "  - name: bridge\n"                                                    // 14
         "    origin: [0, 0]\n"                                                  // 15
         "    length: 20.0\n"                                                    // 16
         "    elements: 4\n"                                                     // 17
         "    section: {area: 0.01, inertia: " + inertia + "}\n" +                // 18
         "    material: {youngs_modulus: 2.1e11, density: 7850}\n"              // 19
         "    supports: [{at: 0.0, type: pinned}, {at: 20.0, type: pinned}]\n"  // 20
         "    loads: [{name: axle, type: moving, value: -1000, speed: 20}]\n"  // 21
         "contacts:\n"                                                           // 22
         "  - {name: tyre, type: slider_spring, body: cart, point: contact, beam: bridge, " + contact_extra +
         "}\n";                                                                   // 23
}

std::string error_of(const std::string& text, const ModelOverrides& overrides) {
  return test::model_error_of(text, "bridge.yaml", {}, overrides);
}

TEST(ModelOverrides, AnOverriddenFileIsTheEditedFile) {
  const ModelOverrides overrides = {{"loads.front_susp.stiffness", "3.5e6"},
                                    {"beams.bridge.section.inertia", "0.3"},
                                    {"beams.bridge.loads.axle.speed", "35"},
                                    {"contacts.tyre.damping", "250"}};
  const Model set = parse_model_text(model_text(), "bridge.yaml", {}, overrides);
  const Model edited =
      parse_model_text(model_text("3.5e6", "0.3", "stiffness: 5.0e6, damping: 250"), "bridge.yaml");
  EXPECT_EQ(set.loads[0].stiffness, 3.5e6);
  EXPECT_EQ(set.loads[0].stiffness, edited.loads[0].stiffness);
  EXPECT_EQ(set.beams[0].second_moment, 0.3);
  EXPECT_EQ(set.beams[0].second_moment, edited.beams[0].second_moment);
  EXPECT_EQ(set.beams[0].moving_loads[0].speed, 35.0);
  EXPECT_EQ(set.contacts[0].damping, edited.contacts[0].damping);
  EXPECT_EQ(set.loads[0].name, "front_susp");
  EXPECT_EQ(set.loads[1].name, "");
  EXPECT_EQ(set.beams[0].moving_loads[0].name, "axle");
  // A changed value is a changed model; no override, the file's own hash.
  EXPECT_NE(set.source_sha256, sha256_hex(model_text()));
  EXPECT_EQ(parse_model_text(model_text(), "bridge.yaml").source_sha256, sha256_hex(model_text()));
}

TEST(ModelOverrides, ALastKeyMayBeNewAndLaterOverridesWin) {
  const Model m = parse_model_text(model_text(), "bridge.yaml", {},
                                   {{"contacts.tyre.damping", "1"}, {"contacts.tyre.damping", "2"}});
  EXPECT_EQ(m.contacts[0].damping, 2.0);
}

TEST(ModelOverrides, ABadPathIsAnErrorInTheFileNamingTheSet) {
  EXPECT_EQ(error_of(model_text(), {{"loads.rear_susp.stiffness", "1"}}),
            "bridge.yaml:11:3: --set loads.rear_susp.stiffness=1: 'loads' has no item named 'rear_susp' (an item "
            "of a list is reached by its name: key)");
  EXPECT_EQ(error_of(model_text(), {{"beams.bridge.sektion.inertia", "1"}}),
            "bridge.yaml:14:5: --set beams.bridge.sektion.inertia=1: 'bridge' has no key 'sektion'");
  EXPECT_EQ(error_of(model_text(), {{"beams.bridge.section", "1"}}),
            "bridge.yaml:18:14: --set beams.bridge.section=1: PATH leads to a map, not to a single value: give the "
            "whole of it as VALUE in YAML's flow form ({key: value, ...}) or go on to one of its keys (PATH.key)");
  EXPECT_EQ(error_of(model_text(), {{"beams..inertia", "1"}}),
            "bridge.yaml:1:1: --set beams..inertia=1: PATH 'beams..inertia' has an empty key");
  // A misspelt last key is added, and the schema refuses it at its map.
  const std::string misspelt = error_of(model_text(), {{"loads.front_susp.stifness", "1"}});
  EXPECT_NE(misspelt.find("bridge.yaml:11:5: "), std::string::npos) << misspelt;
  EXPECT_NE(misspelt.find("'stifness'"), std::string::npos) << misspelt;
  EXPECT_NE(misspelt.find("(the value came from --set loads.front_susp.stifness=1)"), std::string::npos) << misspelt;
}

TEST(ModelOverrides, ABadValueIsAnErrorAtTheValueNamingTheSet) {
  const std::string text = model_text();
  const std::string e = error_of(text, {{"loads.front_susp.stiffness", "abc"}});
  EXPECT_EQ(e.rfind("bridge.yaml:11:69: ", 0), 0u) << e;
  EXPECT_NE(e.find("got 'abc'"), std::string::npos) << e;
  EXPECT_NE(e.find("(the value came from --set loads.front_susp.stiffness=abc)"), std::string::npos) << e;
  // An error elsewhere in the file does not blame the --set.
  const std::string elsewhere =
      error_of(model_text("-1"), {{"beams.bridge.section.inertia", "0.3"}});
  EXPECT_EQ(elsewhere.find("--set"), std::string::npos) << elsewhere;
}

TEST(LoadNames, DuplicatesAndNonIdentifiersAreRefused) {
  std::string text = model_text();
  const std::string second = "  - {type: force, body: cart, value: [0, -5]}\n";
  text.replace(text.find(second), second.size(), "  - {name: front_susp, type: force, body: cart, value: [0, -5]}\n");
  EXPECT_EQ(error_of(text, {}), "bridge.yaml:12:12: load 'front_susp': duplicate load name (first used at line 11)");
}

TEST(LoadNames, ASweepReachesANamedLoad) {
  const Sweep sweep = parse_sweep_text(
      "sweep: springs\nmodel: bridge.yaml\nvary:\n  - {path: loads.front_susp.stiffness, values: [1e6, 2e6]}\n",
      "springs.yaml");
  EXPECT_NO_THROW(check_sweep_paths(sweep, model_text()));
  const Model point = parse_model_text(point_model_text(sweep, model_text(), 1), "point");
  EXPECT_EQ(point.loads[0].stiffness, 2e6);
}

}  // namespace
}  // namespace mbfe::frontend
