// Beams for the FE and modal tests, built straight from the model IR (no
// parser), so these tests check the runtime alone.
#pragma once

#include <cmath>
#include <string>

#include "ir/model.h"

namespace mbfe::test {

constexpr double kPi = 3.141592653589793238462643383279502884;

/// The beam of the paper's Section 7: L = 1 m, square side a, E = 2.1e11 Pa,
/// rho = 7860 kg/m^3, pinned at both ends, Rayleigh alpha = 3e-3, beta = 1.5e-4.
inline ir::Beam paper_beam(double side = 0.005, int elements = 50) {
  ir::Beam b;
  b.name = "beam1";
  b.length = 1.0;
  b.elements = elements;
  b.area = side * side;
  b.second_moment = side * side * side * side / 12.0;
  b.youngs_modulus = 2.1e11;
  b.density = 7860.0;
  b.rayleigh_alpha = 3.0e-3;
  b.rayleigh_beta = 1.5e-4;
  b.supports = {{0.0, ir::SupportType::kPinned, -1, {}},
                {1.0, ir::SupportType::kPinned, -1, {}}};
  return b;
}

/// The same section and material, clamped at s = 0, free at s = L.
inline ir::Beam cantilever_beam(int elements = 50) {
  ir::Beam b = paper_beam(0.005, elements);
  b.name = "cantilever";
  b.supports = {{0.0, ir::SupportType::kClamped, -1, {}}};
  return b;
}

inline double bending_stiffness(const ir::Beam& b) { return b.youngs_modulus * b.second_moment; }
inline double mass_per_length(const ir::Beam& b) { return b.density * b.area; }

}  // namespace mbfe::test
