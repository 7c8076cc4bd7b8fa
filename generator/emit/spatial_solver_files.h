// The two files of a generated spatial solver: <model>.h and <model>.cpp,
// the counterpart of solver_files.h (whose banner they share). The source
// fills every field of mbfe_model_v1, including those appended for spatial
// models and closed loops (runtime/abi/mbfe_model_abi.h).
#pragma once

#include <string>
#include <vector>

#include "generator/emit/generate_solver.h"
#include "generator/emit/solver_files.h"
#include "ir/coordinate_layout.h"
#include "ir/model.h"

namespace mbfe::gen {

/// What the source file of a spatial solver holds besides its frame.
struct SpatialSolverParts {
  std::string kernels;    // mass_matrix, inertial_forces, generalized_forces, dynamics, position_derivative
  std::string points;     // one function per named point
  std::string motion;     // the motion kernel; empty when no joint is driven
  std::string loops;      // the loop kernels; empty when the model has no constraints
  std::vector<int> parent_table;  // parent of each velocity coordinate, for M's assembly loop; empty for a chain
  std::vector<SolverParts::PointFunction> point_functions;
  std::vector<int> driven_velocities, driven_positions;  // driven coordinates: indices into v and into q
  std::vector<LoopTableEntry> loop_entries;
  int loop_rows = 0;
};

std::string spatial_solver_header(const ir::Model& model, const ir::CoordinateLayout& layout,
                                  const GeneratedSolver& solver);

std::string spatial_solver_source(const ir::Model& model, const ir::CoordinateLayout& layout,
                                  const GeneratedSolver& solver, const SpatialSolverParts& parts);

}  // namespace mbfe::gen
