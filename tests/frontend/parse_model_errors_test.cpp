// The model front end's refusals: each bad file gives its exact message,
// file:line:col: what is wrong (the good files: parse_model_test.cpp).
#include <gtest/gtest.h>

#include <string>

#include "frontend/parse_model.h"
#include "ir/identifiers.h"
#include "ir/model_error.h"
#include "tests/support/model_error.h"

namespace mbfe::frontend {
using namespace mbfe::ir;
namespace {

const char* const kTwoLinks = R"(model: m
bodies:
  - name: link1
    parent: ground
    joint: {type: revolute}
    mass: 1
    inertia: 0.1
  - name: link2
    parent: link1
    joint: {type: revolute, at: [1, 0]}
    mass: 1
    inertia: 0.1
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(ParseModelErrors, NegativeMassPointsAtTheValue) {
  std::string text = kTwoLinks;
  text.replace(text.rfind("mass: 1"), 7, "mass: -2");  // link2's mass, line 11
  EXPECT_EQ(test::model_error_of(text), "models/x.yaml:11:11: body 'link2': mass must be >= 0 (got -2)");
}

TEST(ParseModelErrors, UnknownKeyPointsAtTheKey) {
  EXPECT_EQ(test::model_error_of(replaced(kTwoLinks, "    mass: 1\n", "    mas: 1\n")),
            "models/x.yaml:6:5: unknown key 'mas' in body 'link1' (expected one of: name, "
            "parent, joint, mass, inertia, com, points)");
}

TEST(ParseModelErrors, MissingKeyPointsAtTheMap) {
  EXPECT_EQ(test::model_error_of(replaced(kTwoLinks, "    inertia: 0.1\n  - name: link2", "  - name: link2")),
            "models/x.yaml:3:5: body 'link1': missing required key 'inertia'");
}

TEST(ParseModelErrors, ParentAfterChild) {
  EXPECT_EQ(test::model_error_of(replaced(kTwoLinks, "parent: ground", "parent: link2")),
            "models/x.yaml:4:13: body 'link1': unknown parent 'link2' (a parent must be listed "
            "before its children; the root is 'ground')");
}

TEST(ParseModelErrors, KeywordAsName) {
  EXPECT_EQ(test::model_error_of(replaced(kTwoLinks, "name: link2", "name: double")),
            "models/x.yaml:8:11: body #2: name 'double' is reserved in C++");
}

TEST(ParseModelErrors, YamlSyntaxErrorAtItsMark) {
  EXPECT_EQ(test::model_error_of("model: m\nbodies: [a, b\n"),
            "models/x.yaml:3:1: invalid YAML: end of sequence flow not found");
}

TEST(ParseModelErrors, EmptyFile) {
  EXPECT_EQ(test::model_error_of(""),
            "models/x.yaml:1:1: the file holds no model (expected a YAML map starting with "
            "'model:')");
}

TEST(ParseModelErrors, NotAMap) {
  EXPECT_EQ(test::model_error_of("[1, 2]\n"),
            "models/x.yaml:1:1: the model file: expected a map of keys, got a list of 2 items");
}

TEST(ParseModelErrors, MissingFile) {
  try {
    load_model_file("/nonexistent/dir/x.yaml");
    FAIL() << "accepted a missing file";
  } catch (const ModelError& error) {
    EXPECT_STREQ(error.what(), "/nonexistent/dir/x.yaml: cannot read: No such file or directory");
    EXPECT_EQ(error.loc().line, 0);
  }
}

TEST(ParseModelErrors, ResourceLimitsSayValueAndLimit) {
  ParseLimits small;
  small.max_file_bytes = 100;
  const std::string text = kTwoLinks;
  EXPECT_EQ(test::model_error_of(text, "models/x.yaml", small),
            "models/x.yaml:1:1: the file is " + std::to_string(text.size()) +
                " bytes, more than the limit of 100 (ParseLimits::max_file_bytes)");
  ParseLimits one_body;
  one_body.max_bodies = 1;
  EXPECT_EQ(test::model_error_of(kTwoLinks, "models/x.yaml", one_body),
            "models/x.yaml:3:3: bodies: 2 entries, more than the limit of 1 "
            "(ParseLimits::max_bodies)");
  // 300,000 list items: yaml-cpp would spend ~150 MB on them; refused unread,
  // at the comma that makes value 100,001 (model: gravity: [ are 1 to 3).
  std::string many = "model: m\ngravity: [0";
  for (int i = 0; i < 300000; ++i) many += ",0";
  many += "]\n";
  EXPECT_EQ(test::model_error_of(many),
            "models/x.yaml:2:200006: the file holds about 300003 YAML values, more than the "
            "limit of 100000 (ParseLimits::max_yaml_values)");
}

TEST(ParseModelErrors, ModelErrorParts) {
  try {
    parse_model_text("model: 3x\n", "a.yaml");
    FAIL() << "accepted";
  } catch (const ModelError& error) {
    EXPECT_EQ(error.file(), "a.yaml");
    EXPECT_EQ(error.loc().line, 1);
    EXPECT_EQ(error.loc().column, 8);
    EXPECT_EQ(error.message(),
              "model '3x' is not an identifier (letters, digits and '_', not starting with a "
              "digit)");
  }
}

TEST(Identifier, Rules) {
  EXPECT_TRUE(is_identifier("link1"));
  EXPECT_TRUE(is_identifier("_x"));
  EXPECT_TRUE(is_identifier("A_b_9"));
  EXPECT_FALSE(is_identifier(""));
  EXPECT_FALSE(is_identifier("1a"));
  EXPECT_FALSE(is_identifier("a-b"));
  EXPECT_FALSE(is_identifier("a b"));
  EXPECT_FALSE(is_identifier("a.b"));
  EXPECT_FALSE(is_identifier("caf\xc3\xa9"));
  EXPECT_FALSE(is_identifier(std::string("a\0b", 3)));
}

}  // namespace
}  // namespace mbfe::frontend
