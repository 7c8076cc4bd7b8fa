// A beam's `profile:` and `camber:`: each form into the IR, and bad input
// refused at the file, line and column where it is written (the model file's,
// or the profile table's own).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "frontend/parse_model.h"

namespace mbfe::frontend {
using namespace mbfe::ir;
namespace {

/// A 30 m beam whose line 8 is `    <profile_line>` (column 5 is its first character).
std::string beam_model(const std::string& profile_line) {
  return "model: rail\n"
         "gravity: [0, -9.81]\n"
         "beams:\n"
         "  - name: rail\n"
         "    origin: [0.0, 0.0]\n"
         "    length: 30.0\n"
         "    elements: 30\n"
         "    " + profile_line + "\n"
         "    section: {area: 0.01, inertia: 1.0e-4}\n"
         "    material: {youngs_modulus: 2.1e11, density: 7850}\n"
         "    supports: [{at: 0.0, type: pinned}, {at: 30.0, type: pinned}]\n";
}

class ParseProfile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::path(::testing::TempDir()) / "mbfe_parse_profile";
    std::filesystem::create_directories(dir_);
  }
  std::string model_path() const { return (dir_ / "rail.yaml").string(); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  Model parse(const std::string& profile_line) const {
    return parse_model_text(beam_model(profile_line), model_path());
  }
  std::string error_of(const std::string& profile_line) const {
    try {
      parse(profile_line);
    } catch (const ModelError& error) {
      return error.what();
    }
    return "(accepted)";
  }
  std::filesystem::path dir_;
};

TEST_F(ParseProfile, ExpressionInS) {
  const Model m = parse("profile: {expression: \"0.002*sin(2*pi*s/25)\"}");
  const BeamProfile& p = m.beams[0].profile;
  EXPECT_EQ(p.kind, ProfileKind::kExpression);
  EXPECT_FALSE(p.camber_static);
  EXPECT_DOUBLE_EQ(p.expression.evaluate(6.25), 0.002);
}

TEST_F(ParseProfile, ExpressionErrorsPointIntoTheText) {
  // t is not the variable of a profile: column 5 + len("profile: {expression: \"0.001*") = 34.
  EXPECT_EQ(error_of("profile: {expression: \"0.001*t\"}"),
            model_path() + ":8:34: beam 'rail': profile.expression: unknown name 't' (allowed: s, pi, sin, cos, tan, "
                           "exp, log, sqrt, abs, min, max, step) in expression \"0.001*t\"");
  // Not finite on the beam: log(s - 10) at s < 10.
  const std::string log_error = error_of("profile: {expression: \"0.001*log(s - 10)\"}");
  EXPECT_NE(log_error.find(model_path() + ":8:34: "), std::string::npos) << log_error;
  EXPECT_NE(log_error.find("at s = 0 m"), std::string::npos) << log_error;
}

TEST_F(ParseProfile, APoleBetweenTheSamplesIsRefusedAtItsOperator) {
  // The 4001 samples of [0, 30] are 7.5 mm apart; s = 10.0003 is none of them,
  // and 1/(s - 10.0003) is finite (if large) at every one.
  const std::string division = error_of("profile: {expression: \"0.001/(s - 10.0003)\"}");
  EXPECT_EQ(division.rfind(model_path() + ":8:33: beam 'rail': profile.expression \"0.001/(s - 10.0003)\" has a "
                                          "pole at s = 10.0003 m: a division by a part that is 0 there",
                           0),
            0u)
      << division;
  const std::string power = error_of("profile: {expression: \"0.001*(s - 10.0003)^(-1)\"}");
  EXPECT_NE(power.find(":8:47: "), std::string::npos) << power;  // the ^
  EXPECT_NE(power.find("a negative power of a part that is 0"), std::string::npos) << power;
  const std::string tangent = error_of("profile: {expression: \"0.001*tan(s/10)\"}");  // pole at 5 pi = 15.708 m
  EXPECT_NE(tangent.find("has a pole at s = 15.70796"), std::string::npos) << tangent;
  // No pole: a sign change by a jump, a part that keeps its sign, a positive power.
  EXPECT_EQ(error_of("profile: {expression: \"0.001/(step(s - 5) - 0.5)\"}"), "(accepted)");
  EXPECT_EQ(error_of("profile: {expression: \"0.001/(s + 1)\"}"), "(accepted)");
  EXPECT_EQ(error_of("profile: {expression: \"0.001*(s - 10.0003)^3\"}"), "(accepted)");
}

TEST_F(ParseProfile, TableRelativeToTheModelFile) {
  write("rail.csv", "# measured\ns, offset\n0, 0\n10, 0.001\n30.5, -0.002\n");
  const Model m = parse("profile: {file: rail.csv}");
  const BeamProfile& p = m.beams[0].profile;
  EXPECT_EQ(p.kind, ProfileKind::kTable);
  EXPECT_EQ(p.table_s, (std::vector<double>{0.0, 10.0, 30.5}));
  EXPECT_EQ(p.table_offset, (std::vector<double>{0.0, 0.001, -0.002}));
}

TEST_F(ParseProfile, TableWithoutHeaderHasSThenOffset) {
  write("bare.csv", "0,0.001\n15,-0.001\n30,0\n");
  const Model m = parse("profile: {file: bare.csv}");
  EXPECT_EQ(m.beams[0].profile.table_s, (std::vector<double>{0.0, 15.0, 30.0}));
  EXPECT_EQ(m.beams[0].profile.table_offset, (std::vector<double>{0.001, -0.001, 0.0}));
}

TEST_F(ParseProfile, BadTablesAreRefusedWhereTheyAreWrong) {
  const std::string table = (dir_ / "bad.csv").lexically_normal().string();
  write("bad.csv", "s,offset\n0,0\n5,0.001\n5,0.002\n30,0\n");
  EXPECT_EQ(error_of("profile: {file: bad.csv}"),
            table + ":4:1: profile table: s must increase strictly from row to row: got 5 m after 5 m");
  write("bad.csv", "s,offset\n0,0\n5,1e-3x\n");
  EXPECT_EQ(error_of("profile: {file: bad.csv}"),
            table + ":3:3: profile table: offset: expected a finite number, got \"1e-3x\"");
  write("bad.csv", "position,height\n0,0\n");
  EXPECT_NE(error_of("profile: {file: bad.csv}").find(table + ":1:1: profile table: expected a header naming the columns s and offset"),
            std::string::npos);
  write("bad.csv", "s,offset\n0,0\n20,0\n");
  EXPECT_EQ(error_of("profile: {file: bad.csv}"),
            model_path() + ":8:21: beam 'rail': profile.file: \"bad.csv\" covers s in [0, 20] m; expected it to cover the "
                           "beam's [0, 30] m");
  EXPECT_NE(error_of("profile: {file: missing.csv}").find(model_path() + ":8:21: beam 'rail': profile.file: cannot read \"missing.csv\""),
            std::string::npos);
}

TEST_F(ParseProfile, SpectrumWithClassBandAndSeed) {
  const Model m = parse("profile: {psd: fra, class: 5, wavelengths: [1, 80], seed: 7}\n    camber: static");
  const BeamProfile& p = m.beams[0].profile;
  EXPECT_EQ(p.kind, ProfileKind::kSpectrum);
  EXPECT_EQ(p.spectrum, TrackSpectrum::kFra);
  EXPECT_EQ(p.spectrum_class, 5);
  EXPECT_EQ(p.wavelength_min, 1.0);
  EXPECT_EQ(p.wavelength_max, 80.0);
  EXPECT_EQ(p.seed, 7u);
  EXPECT_TRUE(p.camber_static);
  const Model g = parse("profile: {psd: german, class: high, wavelengths: [2, 50]}");
  EXPECT_EQ(g.beams[0].profile.spectrum, TrackSpectrum::kGerman);
  EXPECT_EQ(g.beams[0].profile.spectrum_class, 1);
}

TEST_F(ParseProfile, SpectrumErrors) {
  EXPECT_EQ(error_of("profile: {psd: fra, class: 7, wavelengths: [1, 80]}"),
            model_path() + ":8:32: beam 'rail': profile.class: the FRA spectrum has track classes 1 to 6, got 7");
  EXPECT_NE(error_of("profile: {psd: fra, class: 3, wavelengths: [80, 1]}").find("0 < shortest < longest"),
            std::string::npos);
  EXPECT_NE(error_of("profile: {psd: fra, class: 3, wavelengths: [1e-4, 1]}").find("harmonic evaluations"),
            std::string::npos);
  EXPECT_NE(error_of("profile: {psd: usa, class: 3, wavelengths: [1, 80]}").find("fra"), std::string::npos);
  EXPECT_NE(error_of("profile: {expression: \"0\", file: rail.csv}").find("exactly one of expression, file or psd"),
            std::string::npos);
  EXPECT_NE(error_of("profile: {expression: \"0.001*s\", seed: 3}").find("profile.seed belongs to a psd profile"),
            std::string::npos);
  EXPECT_NE(error_of("camber: dead").find("static"), std::string::npos);
}

}  // namespace
}  // namespace mbfe::frontend
