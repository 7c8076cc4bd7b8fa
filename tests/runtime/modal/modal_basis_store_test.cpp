// sliced_modes_inputs: what the modes cache keys on. Equal beams give equal
// inputs; any change to what decides the sliced modes (a material constant,
// the mesh, the tension, the bound, the run size) gives other inputs.
#include <gtest/gtest.h>

#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_analysis.h"
#include "runtime/modal/modal_basis_store.h"

namespace mbfe::runtime {
namespace {

ir::Beam wire() {
  ir::Beam b;
  b.name = "wire";
  b.length = 20.0;
  b.elements = 40;
  b.youngs_modulus = 1.2e11;
  b.density = 8900.0;
  b.area = 1.5e-4;
  b.second_moment = 1.6e-9;
  b.tension = 20000.0;
  b.supports.push_back({0.0, ir::SupportType::kPinned, -1, 0.0, 0.0, 0.0, {}});
  b.supports.push_back({20.0, ir::SupportType::kPinned, -1, 0.0, 0.0, 0.0, {}});
  return b;
}

std::string inputs_of(const ir::Beam& beam, double up_to = 800.0, int slice = 10) {
  ModalOptions options;
  options.up_to_omega = up_to;
  options.slice_modes = slice;
  return sliced_modes_inputs(assemble_beam(beam, {0.0, -9.81}), options);
}

TEST(SlicedModesInputs, EqualBeamsGiveEqualInputs) { EXPECT_EQ(inputs_of(wire()), inputs_of(wire())); }

TEST(SlicedModesInputs, AnyChangeToTheBeamOrTheOptionsChangesThem) {
  const std::string base = inputs_of(wire());
  ir::Beam stiffer = wire();
  stiffer.youngs_modulus *= 1.0 + 1e-15 * 8;  // a few ulps
  EXPECT_NE(inputs_of(stiffer), base);
  ir::Beam finer = wire();
  finer.elements = 41;
  EXPECT_NE(inputs_of(finer), base);
  ir::Beam tighter = wire();
  tighter.tension = 20001.0;
  EXPECT_NE(inputs_of(tighter), base);
  ir::Beam heavier = wire();
  heavier.density = 8901.0;
  EXPECT_NE(inputs_of(heavier), base);
  EXPECT_NE(inputs_of(wire(), 801.0), base);
  EXPECT_NE(inputs_of(wire(), 800.0, 11), base);
}

}  // namespace
}  // namespace mbfe::runtime
