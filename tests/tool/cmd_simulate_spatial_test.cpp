// `mbfe simulate` and `mbfe stability` on spatial models and closed loops from
// the command line: an implicit integrator keeps the loops closed, and a
// formulation asked of a tree is refused with a message (exit 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "tests/support/cli.h"
#include "tests/support/process.h"

namespace mbfe {
namespace {

TEST(SimulateSpatial, ImplicitIntegratorsKeepTheLoopsClosed) {
  // Newton closes the loops at every evaluation, whatever the integrator.
  constexpr double kRoundOffResidual = 1e-12;  // m
  const test::TempDir dir;
  for (const char* integrator : {"trapezoid", "bdf2"}) {
    SCOPED_TRACE(integrator);
    const std::string out = (dir / (std::string(integrator) + ".csv")).string();
    const test::CliRun r =
        test::run_cli(std::string("simulate models/four_bar.yaml --integrator ") + integrator + " --t-end 0.5 --out " + out);
    ASSERT_EQ(r.status, 0) << r.all();
    EXPECT_NE(r.err.find("(partitioned formulation)"), std::string::npos) << r.err;
    const test::Csv csv = test::read_csv(out);
    const int residual = csv.column("loop_residual");
    ASSERT_GE(residual, 0);
    double worst = 0.0;
    for (const auto& row : csv.rows) worst = std::max(worst, row[static_cast<std::size_t>(residual)]);
    EXPECT_LT(worst, kRoundOffResidual);
  }
}

TEST(SimulateSpatial, AFormulationForATreeIsRefused) {
  struct Case {
    std::string command, message;
  };
  const Case cases[] = {
      {"simulate models/double_pendulum_3d.yaml --formulation augmented --out /dev/null",
       "--formulation applies to coupled models (bodies, beams and contacts) and models with closed loops"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.command);
    const test::CliRun r = test::run_cli(c.command);
    EXPECT_EQ(r.status, 2) << r.all();
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
  }
}

TEST(SimulateSpatial, AnInitialQuaternionOffUnitLengthIsScaledAndSaidSo) {
  // A ball-jointed pendulum whose initial quaternion is written (2, 0, 0, 0):
  // the identity, twice too long. It is scaled (a run as from the unit one)
  // and said on stderr; --strict refuses it at the list (line 6, column 20).
  const test::TempDir dir;
  const std::string path = (dir / "ball.yaml").string();
  std::ofstream(path) << "model: ball\ndimension: 3\ngravity: [0, 0, -9.81]\nbodies:\n"
                         "  - {name: bob, parent: ground, joint: {type: spherical}, mass: 1, "
                         "inertia: [0.01, 0.01, 0.01, 0, 0, 0], com: [0, 0, -0.5]}\n"
                         "initial: {q: {bob: [2, 0, 0, 0]}}\n";
  const test::CliRun r = test::run_cli("simulate " + path + " --t-end 0.01 --out /dev/null");
  ASSERT_EQ(r.status, 0) << r.all();
  EXPECT_NE(r.err.find("initial.q.bob: the quaternion has norm 2, not 1, and was scaled to unit length"),
            std::string::npos)
      << r.err;
  const test::CliRun strict = test::run_cli("simulate " + path + " --t-end 0.01 --strict --out /dev/null");
  EXPECT_EQ(strict.status, 2) << strict.all();
  EXPECT_NE(strict.err.find("ball.yaml:6:20: initial.q.bob: the quaternion has norm 2, not 1, and was scaled to unit "
                            "length (strict: write a unit quaternion"),
            std::string::npos)
      << strict.err;
}

}  // namespace
}  // namespace mbfe
