// The units of a coupled run's columns come from what each coordinate is (a
// joint angle, a beam displacement w, a beam slope w'), not from its name: a
// beam whose name holds "_dw" (my_dwire) still has its displacements in m.
// The oracle is the mesh: every node has w (m) then w' (1), supports removing
// some, so a column named <beam>_w<k> is a length and <beam>_dw<k> a slope.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "frontend/parse_model.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/simulation/simulator.h"

extern "C" const mbfe_model_v1* mbfe_model_double_pendulum_beam(void);

namespace mbfe::runtime {
namespace {

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// models/double_pendulum_beam.yaml with its beam named `beam`.
ir::Model pendulum_on_beam_named(const std::string& beam) {
  std::string text = read(std::string(MBFE_SOURCE_DIR) + "/models/double_pendulum_beam.yaml");
  for (std::size_t at = text.find("beam1"); at != std::string::npos; at = text.find("beam1", at + beam.size()))
    text.replace(at, 5, beam);
  return frontend::parse_model_text(text, beam + ".yaml");
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

class BeamNamedLikeASlope : public testing::TestWithParam<std::string> {};

TEST_P(BeamNamedLikeASlope, DisplacementsInMetresSlopesInOne) {
  const std::string beam = GetParam();
  const AssembledModel model(pendulum_on_beam_named(beam), mbfe_model_double_pendulum_beam());
  SimulationRequest request;
  request.integrator = parse_integrator("rk4");
  request.step = 1e-5;
  request.t_end = 1e-5;
  const Simulator sim(model, request);
  const OutputLayout& layout = sim.layout();
  ASSERT_EQ(layout.columns.size(), layout.units.size());
  int displacements = 0, slopes = 0;
  for (std::size_t c = 0; c < layout.columns.size(); ++c) {
    const std::string& name = layout.columns[c];
    const std::string& unit = layout.units[c];
    const bool rate = name.size() > 4 && name.compare(name.size() - 4, 4, "_dot") == 0;
    if (starts_with(name, beam + "_w")) {
      EXPECT_EQ(unit, rate ? "m/s" : "m") << name;
      ++displacements;
    } else if (starts_with(name, beam + "_dw")) {
      EXPECT_EQ(unit, rate ? "1/s" : "1") << name;
      ++slopes;
    } else if (starts_with(name, "link")) {
      EXPECT_EQ(unit, rate ? "rad/s" : "rad") << name;
    }
  }
  // 51 nodes, w fixed at both pins: 49 displacements and 51 slopes, each with its rate.
  EXPECT_EQ(displacements, 2 * 49);
  EXPECT_EQ(slopes, 2 * 51);
}

INSTANTIATE_TEST_SUITE_P(Names, BeamNamedLikeASlope, testing::Values("beam1", "my_dwire"));

}  // namespace
}  // namespace mbfe::runtime
