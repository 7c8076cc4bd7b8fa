// Every file of tests/malformed/ must be refused with a located, named error,
// quickly, and without crashing (docs/robustness.md).
//
// Each corpus file starts with two comment lines:
//   # expect: <a substring of the error message>
//   # at: LINE:COL        (the 1-based location the error must carry)
// The files, by issue-6 category:
// - truncated YAML and broken syntax: truncated_flow_map, truncated_quoted_string,
//   truncated_mid_body, tab_indentation, undefined_alias, long_key_over_yaml_limit,
//   two_documents, only_comments (an empty model), top_is_list, top_is_scalar,
//   leading_comma and lone_comma (yaml-cpp 0.7's LoadAll loops on these, issue #1040)
// - wrong types: mass_is_map, mass_is_quoted_string, mass_is_word, mass_is_list, mass_empty,
//   bodies_not_list, gravity_three_components, gravity_scalar, com_scalar, joint_not_map,
//   elements_fraction, name_is_list, points_as_list, torque_value_vector,
//   force_value_scalar, step_quoted, hex_number, alias_bomb (9^9 aliases, never expanded)
// - NaN and infinities: mass_nan, inertia_inf, gravity_minus_inf, length_overflow (1e999),
//   joint_at_nan_word, huge_digit_string
// - negative or zero sizes: mass_negative, inertia_negative, beam_length_zero,
//   beam_length_negative, elements_zero, elements_negative, youngs_modulus_zero,
//   density_negative, section_side_zero, section_area_negative, section_inertia_missing,
//   section_shape_and_area, section_side_without_shape, rayleigh_alpha_negative,
//   step_zero, t_end_negative, omega_limit_zero, margin_negative, zeta_min_one, adjustment_unknown_policy,
//   prismatic_zero_axis, prismatic_without_axis, revolute_with_axis,
//   spring_negative_stiffness
// - unknown or duplicate names and keys: unknown_body_key, unknown_top_key,
//   unknown_joint_type, unknown_parent, unknown_load_body, unknown_load_point,
//   unknown_load_type, unknown_initial_body, unknown_integrator, unknown_support_type,
//   missing_mass, missing_model, missing_joint_type, duplicate_key, duplicate_body,
//   duplicate_point, beam_named_like_body, duplicate_contact, body_named_ground,
//   no_bodies_no_beams
// - cycles: own_parent, cycle_two_bodies
// - a support or load off the nodes: support_off_node, support_outside_beam,
//   support_twice_on_node, beam_load_off_node, beam_load_negative_position
// - contacts: contact_missing_beam, contact_at_outside_beam, slider_pin_with_at,
//   contact_unknown_point, pin_without_at
// - resource limits: elements_hundred_million, total_dofs_over_limit, and, generated
//   below, the 10,000-body chain (TenThousandBodyChain), a 201-body one
//   (ChainOverBodyLimit) and 201 named points (PointsOverLimit)
// - names that are not identifiers, C++ keywords: name_with_dash, name_starts_with_digit,
//   name_keyword_int, model_name_class, model_name_code_injection, name_unicode,
//   name_double_underscore, name_too_long, point_name_with_space, name_true
// - very long strings: long_string_as_number, long_unknown_key, name_too_long
// - deep nesting: deep_brackets, deep_braces_unclosed, deep_indentation, deep_dashes
// - output columns that would share a name: output_name_t, output_name_phi_abs,
//   output_name_rate_clash (bodies a and a_dot), output_name_drive_clash,
//   output_name_beam_coordinate (a body deck_w3 beside beam deck),
//   output_name_contact_force, output_name_pin_multiplier, output_name_link_tension,
//   output_name_loop_residual (a body so named in a model with closed loops)
// - spatial models and closed loops: spatial_zero_axis, spatial_inertia_triangle,
//   spatial_with_beam, constraint_same_body, loops_with_beam
// - expressions in t whose constant parts have no value: expression_division_by_zero,
//   expression_zero_over_zero, expression_log_of_zero, expression_log_of_negative,
//   expression_sqrt_of_negative, expression_zero_to_zero, expression_negative_power_of_zero,
//   expression_negative_base_fractional_power, expression_exp_overflow, expression_product_overflow
//   (trees too deep or too large: tests/frontend/expression_parser_test.cpp)
// - binary garbage and non-text: garbage.bin (written by make_garbage.py), nul_byte,
//   invalid_utf8, control_character
// A truly empty (0-byte) file cannot carry the header; parse_model_test covers it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/parse_model.h"

namespace mbfe::frontend {
using namespace mbfe::ir;
namespace {

namespace fs = std::filesystem;

// Each file is refused in well under 10 ms of CPU; 2 s leaves room for
// sanitizer builds while still catching a hang or a super-linear blow-up.
// CPU time, not wall time: four builds may share the CI machine's 2 cores.
constexpr double kMaxParseSeconds = 2.0;

// A 10,000-body chain read with raised limits: yaml-cpp alone spends about
// 0.6 s of CPU on its 120,000 values in a Release build, 3x that under ASan.
constexpr double kMaxLargeModelSeconds = 5.0;

// The corpus holds at least 60 malformed files (docs/robustness.md); fewer means files were lost.
constexpr std::size_t kMinCorpusSize = 60;

const fs::path kCorpusDir = fs::path(MBFE_SOURCE_DIR) / "tests" / "malformed";

std::vector<std::string> corpus_files() {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(kCorpusDir)) {
    const std::string extension = entry.path().extension().string();
    if (extension == ".yaml" || extension == ".bin") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

struct Expectation {
  std::string substring;  // from `# expect: ...`
  std::string location;   // from `# at: LINE:COL`
};

/// Reads the two header lines; empty fields when a header is missing.
Expectation read_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string expect_line, at_line;
  std::getline(in, expect_line);
  std::getline(in, at_line);
  const std::string expect_tag = "# expect: ", at_tag = "# at: ";
  Expectation expectation;
  if (expect_line.rfind(expect_tag, 0) == 0)
    expectation.substring = expect_line.substr(expect_tag.size());
  if (at_line.rfind(at_tag, 0) == 0) expectation.location = at_line.substr(at_tag.size());
  return expectation;
}

double cpu_seconds_since(std::clock_t start) {
  return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
}

/// Parses `path`, expecting a ModelError; returns its what() and the time taken.
std::string refusal_of(const std::string& path, double& seconds, const ParseLimits& limits = {}) {
  const std::clock_t start = std::clock();
  std::string what;
  try {
    load_model_file(path, limits);
    what = "(accepted)";
  } catch (const ModelError& error) {
    what = error.what();
  }
  seconds = cpu_seconds_since(start);
  return what;
}

class MalformedCorpus : public ::testing::TestWithParam<std::string> {};

TEST_P(MalformedCorpus, RefusedWithLocatedMessageInBoundedTime) {
  const std::string& path = GetParam();
  const Expectation expected = read_header(path);
  ASSERT_FALSE(expected.substring.empty()) << path << ": no '# expect: ' first line";
  ASSERT_FALSE(expected.location.empty()) << path << ": no '# at: LINE:COL' second line";

  double seconds = 0.0;
  const std::string what = refusal_of(path, seconds);
  const std::string prefix = path + ":" + expected.location + ": ";
  EXPECT_EQ(what.substr(0, prefix.size()), prefix) << "full message: " << what;
  EXPECT_NE(what.find(expected.substring), std::string::npos)
      << "expected to contain: " << expected.substring << "\nfull message: " << what;
  EXPECT_LT(seconds, kMaxParseSeconds);
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = fs::path(info.param).filename().string();
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Files, MalformedCorpus, ::testing::ValuesIn(corpus_files()), test_name);

TEST(MalformedCorpusSize, HoldsAtLeastSixtyFiles) {
  EXPECT_GE(corpus_files().size(), kMinCorpusSize);
}

std::string escaped_for_regex(const std::string& text) {
  static const std::regex kSpecial(R"([.^$|()\[\]{}*+?\\])");
  return std::regex_replace(text, kSpecial, R"(\$&)");
}

/// A chain of `n` links, written like models/chain_N.yaml.
std::string chain_text(int n) {
  std::ostringstream out;
  out << "model: chain_" << n << "\nbodies:\n";
  for (int i = 1; i <= n; ++i) {
    out << "  - name: link" << i << "\n"
        << "    parent: " << (i == 1 ? std::string("ground") : "link" + std::to_string(i - 1))
        << "\n    joint: {type: revolute, at: [" << (i == 1 ? 0.0 : 0.5) << ", 0]}\n"
        << "    mass: 1\n    inertia: 0.0208\n";
  }
  return out.str();
}

// Generated at test time: 10,000 bodies make a 1 MB file, too big to commit.
// Its 120,000 YAML values are refused before yaml-cpp builds a tree.
TEST(MalformedCorpusGenerated, TenThousandBodyChain) {
  const std::string path = ::testing::TempDir() + "/chain_10000.yaml";
  std::ofstream(path, std::ios::binary) << chain_text(10000);
  double seconds = 0.0;
  const std::string what = refusal_of(path, seconds);
  EXPECT_TRUE(std::regex_search(
      what, std::regex("^" + escaped_for_regex(path) +
                       ":[0-9]+:[0-9]+: the file holds about [0-9]+ YAML values, more than "
                       "the limit of 100000 \\(ParseLimits::max_yaml_values\\)$")))
      << what;
  EXPECT_LT(seconds, kMaxParseSeconds);
}

// One body over the limit on bodies: refused, pointing at the list.
TEST(MalformedCorpusGenerated, ChainOverBodyLimit) {
  const std::string path = ::testing::TempDir() + "/chain_201.yaml";
  std::ofstream(path, std::ios::binary) << chain_text(201);
  double seconds = 0.0;
  EXPECT_EQ(refusal_of(path, seconds),
            path +
                ":3:3: bodies: 201 entries, more than the limit of 200 "
                "(ParseLimits::max_bodies)");
  EXPECT_LT(seconds, kMaxParseSeconds);
}

// 200 bodies with a point each are within the limits; a second point on the last one is not.
TEST(MalformedCorpusGenerated, PointsOverLimit) {
  const std::string text = chain_text(200);
  std::string with_points;
  std::istringstream lines(text);
  std::string line;
  int bodies = 0;
  while (std::getline(lines, line)) {
    with_points += line + "\n";
    if (line.rfind("    inertia:", 0) == 0)
      with_points += ++bodies < 200 ? "    points: {tip: [0.5, 0]}\n" : "    points: {tip: [0.5, 0], mid: [0.25, 0]}\n";
  }
  const std::string path = ::testing::TempDir() + "/points_201.yaml";
  std::ofstream(path, std::ios::binary) << with_points;
  double seconds = 0.0;
  // The last body's points are on line 2 + 6 * 200 = 1202 (six lines per body); 'mid' at column 29.
  EXPECT_EQ(refusal_of(path, seconds),
            path + ":1202:29: body 'link200': point 'mid': the bodies hold 201 named points up to here, more than "
                   "the limit of 200 (ParseLimits::max_points)");
  EXPECT_LT(seconds, kMaxParseSeconds);
  ParseLimits more;
  more.max_points = 201;
  EXPECT_EQ(parse_model_text(with_points, "points.yaml", more).bodies.back().points.size(), 2u);
}

// With the limits raised, the 10,000-body chain is read, in bounded time:
// nothing in the parser is quadratic in the number of bodies.
TEST(MalformedCorpusGenerated, TenThousandBodyChainWithinRaisedLimits) {
  ParseLimits limits;
  limits.max_bodies = 10000;
  limits.max_yaml_values = 1000000;
  const std::clock_t start = std::clock();
  const Model model = parse_model_text(chain_text(10000), "chain_10000.yaml", limits);
  const double seconds = cpu_seconds_since(start);
  ASSERT_EQ(model.bodies.size(), 10000u);
  EXPECT_EQ(model.bodies.back().parent, 9998);
  EXPECT_LT(seconds, kMaxLargeModelSeconds);
}

}  // namespace
}  // namespace mbfe::frontend
