// Expressions in t that are hostile or undefined, through the real `mbfe`
// binary: a sum too deep to walk recursively, constants without a value,
// values that are not finite where a run first uses them (exit status 2,
// located, nothing written) and loads that become infinite during a run (exit
// status 3, the load named, the rows so far kept whole).
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

#include "tests/support/process.h"

namespace mbfe::test {
namespace {

/// One body turned by a torque `value`, 0.1 s of RK4 at 1 ms.
std::string rigid_model(const std::string& value) {
  return "model: m\n"
         "bodies:\n"
         "  - name: wheel\n"
         "    parent: ground\n"
         "    joint: {type: revolute, at: [0, 0]}\n"
         "    mass: 1\n"
         "    inertia: 1\n"
         "loads:\n"
         "  - {type: torque, body: wheel, value: \"" + value + "\"}\n"
         "simulation: {integrator: rk4, step: 1.0e-3, t_end: 0.1}\n";
}

/// A pinned beam with a point load `value` at midspan; RK4 at 10 us (its stable limit is 0.11 ms).
std::string beam_model(const std::string& value) {
  return "model: m\n"
         "beams:\n"
         "  - name: deck\n"
         "    origin: [0, 0]\n"
         "    length: 10.0\n"
         "    elements: 10\n"
         "    section: {area: 0.01, inertia: 1.0e-4}\n"
         "    material: {youngs_modulus: 2.1e11, density: 7850}\n"
         "    supports: [{at: 0.0, type: pinned}, {at: 10.0, type: pinned}]\n"
         "    loads:\n"
         "      - {type: point, at: 5.0, value: \"" + value + "\"}\n"
         "simulation: {integrator: rk4, step: 1.0e-5, t_end: 0.06}\n";
}

// Where the value's text starts in the two models (after the quote).
constexpr const char* kRigidValueAt = ":9:41: ";
constexpr const char* kBeamValueAt = ":11:40: ";

/// "file:9:NN: " for the character `offset` of a value that starts at `start` (":9:40: ").
std::string at_offset(const std::string& file, const std::string& start, int offset) {
  std::smatch m;
  static const std::regex re(":(\\d+):(\\d+): ");
  std::regex_search(start, m, re);
  return file + ":" + m[1].str() + ":" + std::to_string(std::stoi(m[2].str()) + offset) + ": ";
}

long rows_in_message(const std::string& err) {
  std::smatch m;
  static const std::regex re("(\\d+) rows written");
  return std::regex_search(err, m, re) ? std::stol(m[1]) : -1;
}

class CliExpressionFaults : public ::testing::Test {
 protected:
  std::string env() const { return "MBFE_CACHE_DIR=" + quote((tmp_ / "cache").string()); }
  RunResult mbfe(const std::string& args) { return run_mbfe(tmp_, args, env()); }
  fs::path model(const std::string& name, const std::string& text) {
    const fs::path path = tmp_ / name;
    spit(path, text);
    return path;
  }
  TempDir tmp_;
};

// The reproducers: 60,000 terms on a body (120 KB) made `mbfe generate` exit
// with status 139, 100,000 on a beam crashed `mbfe simulate`.
TEST_F(CliExpressionFaults, FlatSumsDeeperThanTheLimitExit2AtTheOperator) {
  std::string sum = "t";
  for (int i = 1; i < 100000; ++i) sum += "+t";
  const fs::path rigid = model("rigid.yaml", rigid_model(sum.substr(0, 2 * 60000 - 1)));
  const RunResult g = mbfe("generate " + quote(rigid.string()) + " -o " + quote((tmp_ / "gen").string()));
  EXPECT_EQ(g.status, 2) << g.err;
  // The 1000th '+' (offset 1999) makes the tree 1001 deep.
  EXPECT_EQ(g.err.rfind(at_offset(rigid.string(), kRigidValueAt, 1999) + "load #1: value: a tree deeper than 1000", 0),
            0u)
      << g.err.substr(0, 300);
  const fs::path beam = model("beam.yaml", beam_model(sum));
  const RunResult s = mbfe("simulate " + quote(beam.string()) + " --out " + quote((tmp_ / "beam.csv").string()));
  EXPECT_EQ(s.status, 2) << s.err.substr(0, 300);
  EXPECT_EQ(s.err.rfind(at_offset(beam.string(), kBeamValueAt, 1999) + "beam 'deck': load #1: value: a tree deeper",
                        0),
            0u)
      << s.err.substr(0, 300);
  EXPECT_FALSE(fs::exists(tmp_ / "beam.csv"));
}

// Exit status 1 with GiNaC's "power::eval(): division by zero" and no position
// for a body; a run that diverged to NaN (exit 3) or ran with 0^0 = 1 for a beam.
TEST_F(CliExpressionFaults, ConstantsWithoutAValueExit2AtTheirOperator) {
  struct Case {
    std::string value;
    int offset;  // of the operator or function in the value
    std::string reason;
  };
  const std::vector<Case> cases = {{"1/0", 1, "division by zero"},
                                   {"0/0", 1, "division by zero"},
                                   {"log(0)", 0, "log of 0"},
                                   {"sqrt(-1)", 0, "sqrt of a negative number (-1)"},
                                   {"0^0", 1, "0^0 is undefined"},
                                   {"exp(1000)", 0, "overflows a double"}};
  for (const Case& c : cases) {
    const fs::path rigid = model("rigid.yaml", rigid_model(c.value));
    const RunResult g = mbfe("generate " + quote(rigid.string()) + " -o " + quote((tmp_ / "gen").string()));
    EXPECT_EQ(g.status, 2) << c.value << ": " << g.err;
    EXPECT_EQ(g.err.rfind(at_offset(rigid.string(), kRigidValueAt, c.offset) + "load #1: value: " + c.reason, 0), 0u)
        << c.value << ": " << g.err;
    const fs::path beam = model("beam.yaml", beam_model(c.value));
    const RunResult s = mbfe("simulate " + quote(beam.string()) + " --out " + quote((tmp_ / "b.csv").string()));
    EXPECT_EQ(s.status, 2) << c.value << ": " << s.err;
    EXPECT_EQ(s.err.rfind(at_offset(beam.string(), kBeamValueAt, c.offset) + "beam 'deck': load #1: value: " + c.reason,
                          0),
              0u)
        << c.value << ": " << s.err;
    EXPECT_FALSE(fs::exists(tmp_ / "b.csv"));
  }
}

// GiNaC finds 1/(t-t) undefined while generating: status 1, no position, before.
TEST_F(CliExpressionFaults, UndefinedForEveryTExits2AtTheOperator) {
  const fs::path rigid = model("rigid.yaml", rigid_model("1/(t-t)"));
  const RunResult g = mbfe("generate " + quote(rigid.string()) + " -o " + quote((tmp_ / "gen").string()));
  EXPECT_EQ(g.status, 2) << g.err;
  EXPECT_EQ(g.err.rfind(at_offset(rigid.string(), kRigidValueAt, 1) +
                            "load #1: value: a division by zero for every t (GiNaC: power::eval(): division by zero)",
                        0),
            0u)
      << g.err;
}

// 100/t at t = 0: the run's first evaluation. Before, a divergence (exit 3).
TEST_F(CliExpressionFaults, NotFiniteWhereTheRunStartsExits2AndWritesNothing) {
  const fs::path rigid = model("rigid.yaml", rigid_model("100/t"));
  const RunResult r = mbfe("simulate " + quote(rigid.string()) + " --out " + quote((tmp_ / "r.csv").string()));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(at_offset(rigid.string(), kRigidValueAt, 3) +
                       "load #1: value \"100/t\" is inf at t = 0 s: division by zero; expected a finite value where "
                       "the run first uses it"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(tmp_ / "r.csv"));

  const fs::path beam = model("beam.yaml", beam_model("1000/t"));
  const RunResult b = mbfe("simulate " + quote(beam.string()) + " --out " + quote((tmp_ / "b.csv").string()));
  EXPECT_EQ(b.status, 2) << b.err;
  EXPECT_EQ(b.err, at_offset(beam.string(), kBeamValueAt, 4) +
                       "beam 'deck': load #1: value \"1000/t\" is inf at t = 0 s: division by zero; expected a finite "
                       "value where the run first uses it\n");
  EXPECT_FALSE(fs::exists(tmp_ / "b.csv"));

  // A motion is differentiated: sqrt(t) is 0 at t = 0, its velocity is not finite.
  const fs::path driven = model("driven.yaml",
                                "model: m\n"
                                "bodies:\n"
                                "  - name: slider\n"
                                "    parent: ground\n"
                                "    joint: {type: prismatic, axis: [1, 0], motion: \"sqrt(t)\"}\n"
                                "    mass: 1\n"
                                "    inertia: 0\n"
                                "  - {name: arm, parent: slider, joint: {type: revolute}, mass: 1, inertia: 1}\n"
                                "simulation: {integrator: rk4, step: 1.0e-3, t_end: 0.1}\n");
  const RunResult d = mbfe("simulate " + quote(driven.string()) + " --out " + quote((tmp_ / "d.csv").string()));
  EXPECT_EQ(d.status, 2) << d.err;
  EXPECT_NE(d.err.find(driven.string() + ":5:53: body 'slider': joint.motion \"sqrt(t)\": its first derivative is "
                                         "inf at t = 0 s"),
            std::string::npos)
      << d.err;
}

// 1/(t - 0.05) is finite where the run starts and infinite at t = 0.05: a
// fault of the run. Before, "diverged ... |y| = inf", no load named.
TEST_F(CliExpressionFaults, LoadBecomingInfiniteDuringTheRunIsNamedAndTheRowsKept) {
  struct Case {
    std::string name, text, location, message;
    double step;  // s, the model's
  };
  const fs::path rigid = model("rigid.yaml", rigid_model("100/(t-0.05)"));
  const fs::path beam = model("beam.yaml", beam_model("1000/(t-0.05)"));
  // At rest until the load jumps to inf: the driver's bound is still inf
  // then, and the run went on writing rows of inf with exit status 0.
  const fs::path rest = model("rest.yaml", rigid_model("step(t - 0.05)/(t - 0.05)"));
  const std::vector<Case> cases = {
      {"rest", rest.string(), at_offset(rest.string(), kRigidValueAt, 14),
       "load #1: value \"step(t - 0.05)/(t - 0.05)\" is inf at t = 0.05 s: division by zero", 1e-3},
      {"rigid", rigid.string(), at_offset(rigid.string(), kRigidValueAt, 3),
       "load #1: value \"100/(t-0.05)\" is inf at t = 0.05 s: division by zero", 1e-3},
      {"beam", beam.string(), at_offset(beam.string(), kBeamValueAt, 4),
       "beam 'deck': load #1: value \"1000/(t-0.05)\" is inf at t = 0.05 s: division by zero", 1e-5}};
  for (const Case& c : cases) {
    const fs::path csv = tmp_ / (c.name + ".csv");
    const RunResult r = mbfe("simulate " + quote(c.text) + " --every 1 --out " + quote(csv.string()));
    EXPECT_EQ(r.status, 3) << c.name << ": " << r.err;
    // "... (file:line:col); N rows written ...": the position without its trailing ": ".
    const std::string where = c.location.substr(0, c.location.size() - 2);
    EXPECT_NE(r.err.find(c.message + " (" + where + ")"), std::string::npos) << c.name << ": " << r.err;
    const std::string text = slurp(csv);
    const std::size_t rows = check_complete_csv(text);
    EXPECT_EQ(static_cast<long>(rows), rows_in_message(r.err)) << r.err;
    // Every step before t = 0.05 is there and finite (the last one is the
    // step that ends at 0.05, whose stages meet the load); none from 0.05 on.
    const auto lines = lines_of(text);
    ASSERT_GE(lines.size(), 2u);
    EXPECT_LT(std::stod(lines.back()), 0.05) << lines.back();
    // The last row's time as printed, against 0.05 - step: well inside a
    // step (a row one step off misses by 1000 times this).
    constexpr double kLastRowRel = 1e-3;
    EXPECT_NEAR(std::stod(lines.back()), 0.05 - c.step, kLastRowRel * c.step) << lines.back();
    EXPECT_EQ(rows, static_cast<std::size_t>(std::llround((0.05 - c.step) / c.step)) + 1) << c.name;
    for (std::size_t i = 1; i < lines.size(); ++i) {
      EXPECT_EQ(lines[i].find("inf"), std::string::npos) << lines[i];
      EXPECT_EQ(lines[i].find("nan"), std::string::npos) << lines[i];
    }
  }
}

}  // namespace
}  // namespace mbfe::test
