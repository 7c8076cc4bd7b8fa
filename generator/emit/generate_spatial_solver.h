// The generator's pipeline for spatial models (dimension: 3), beside the
// planar one of generate_solver.cpp, which calls it: derive
// (symbolic/spatial_dynamics.h, symbolic/loop_constraints.h), remove common
// subexpressions, print, lay out the two files (spatial_solver_files.h).
#pragma once

#include "generator/emit/generate_solver.h"
#include "ir/model.h"

namespace mbfe::gen {

/// The solver of a spatial `model` with at least one body.
GeneratedSolver generate_spatial_solver(const ir::Model& model);

}  // namespace mbfe::gen
