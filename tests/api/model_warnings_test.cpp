// Warnings about likely unit mistakes (api/model_warnings.h): each rule on a
// one-beam model with the value entered in the wrong unit, the exact line
// it must print, and silence on every shipped model (their values are the
// plausible ones the rules must let through).
#include "api/model_warnings.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "frontend/parse_model.h"

namespace mbfe {
namespace {

namespace fs = std::filesystem;

/// A 1 m steel cantilever, one of its values replaced by `material` or `geometry`.
ir::Model beam(const std::string& material, const std::string& geometry = "angle: 0.0, length: 1.0") {
  const std::string text = "model: w\nbeams:\n  - {name: rod, origin: [0, 0], " + geometry +
                           ", elements: 2,\n     section: {area: 1e-4, inertia: 1e-9}, material: {" + material +
                           "},\n     supports: [{at: 0.0, type: clamped}]}\n";
  return frontend::parse_model_text(text, "w.yaml");
}

TEST(ModelWarnings, APlausibleBeamHasNone) {
  EXPECT_TRUE(model_warnings(beam("youngs_modulus: 2.1e11, density: 7850")).empty());
}

TEST(ModelWarnings, YoungsModulusInGPaOrMPa) {
  EXPECT_EQ(model_warnings(beam("youngs_modulus: 210, density: 7850")),
            std::vector<std::string>{"w.yaml:3:5: warning: beam 'rod': E = 210 Pa is 1e9 times below steel's 2.1e11 "
                                     "Pa: GPa entered as Pa?"});
  EXPECT_EQ(model_warnings(beam("youngs_modulus: 2.1e5, density: 7850")),
            std::vector<std::string>{"w.yaml:3:5: warning: beam 'rod': E = 2.1e5 Pa is 1e6 times below steel's 2.1e11 "
                                     "Pa: MPa (N/mm^2) entered as Pa?"});
  // Concrete in GPa: 36 Pa, 5.83e9 times below steel's, GPa the factor that fits.
  const std::vector<std::string> concrete = model_warnings(beam("youngs_modulus: 36, density: 2500"));
  ASSERT_EQ(concrete.size(), 1u);
  EXPECT_NE(concrete[0].find("E = 36 Pa is 5.83e9 times below steel's 2.1e11 Pa: GPa entered as Pa?"),
            std::string::npos)
      << concrete[0];
}

TEST(ModelWarnings, DensityLengthAndAngle) {
  EXPECT_EQ(model_warnings(beam("youngs_modulus: 2.1e11, density: 7.85")),
            std::vector<std::string>{"w.yaml:3:5: warning: beam 'rod': density = 7.85 kg/m^3 is 1e3 times below "
                                     "steel's 7.85e3 kg/m^3: t/m^3 or g/cm^3 entered as kg/m^3?"});
  const std::vector<std::string> mm =
      model_warnings(beam("youngs_modulus: 2.1e11, density: 7850", "angle: 0.0, length: 20000"));
  ASSERT_EQ(mm.size(), 1u);
  EXPECT_NE(mm[0].find("length = 2e4 m is 1e3 times above a railway span's 20 m: mm entered as m?"), std::string::npos)
      << mm[0];
  const std::vector<std::string> degrees =
      model_warnings(beam("youngs_modulus: 2.1e11, density: 7850", "angle: 180, length: 1.0"));
  ASSERT_EQ(degrees.size(), 1u);
  EXPECT_NE(degrees[0].find("angle = 180 rad is more than a turn: degrees entered as rad?"), std::string::npos)
      << degrees[0];
}

TEST(ModelWarnings, AFreeJointThatMovesNoMass) {
  // A massless arm carrying a massless tip: nothing gives the joint inertia.
  // Driven, or carrying a mass, it is a valid fictitious body.
  const auto model = [](const std::string& tip_mass, const std::string& motion) {
    return frontend::parse_model_text(
        "model: m\nbodies:\n  - {name: arm, parent: ground, joint: {type: revolute" + motion +
            "}, mass: 0, inertia: 0}\n  - {name: tip, parent: arm, joint: {type: revolute, at: [1, 0]}, mass: " +
            tip_mass + ", inertia: 0, com: [0.5, 0]}\n",
        "m.yaml");
  };
  const std::vector<std::string> both = model_warnings(model("0", ""));
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0], "m.yaml:3:5: warning: body 'arm': its joint moves no mass (it and every body it carries have mass 0 "
                     "and inertia 0), so its acceleration is not defined: give it a mass or inertia, or drive the joint");
  EXPECT_NE(both[1].find("body 'tip': its joint moves no mass"), std::string::npos) << both[1];
  EXPECT_TRUE(model_warnings(model("1", "")).empty());
  const std::vector<std::string> driven = model_warnings(model("0", ", motion: \"t\""));
  ASSERT_EQ(driven.size(), 1u);
  EXPECT_NE(driven[0].find("body 'tip'"), std::string::npos) << driven[0];
}

TEST(ModelWarnings, NoShippedModelWarns) {
  int models = 0;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(MBFE_SOURCE_DIR) / "models")) {
    if (entry.path().extension() != ".yaml" || entry.path().parent_path().filename() == "sweeps") continue;
    const ir::Model model = frontend::load_model_file(entry.path().string());
    EXPECT_TRUE(model_warnings(model).empty()) << entry.path() << ": " << model_warnings(model).front();
    ++models;
  }
  EXPECT_GE(models, 20);
}

}  // namespace
}  // namespace mbfe
