// One beam as a coupled model sees it: its mesh and place among the model's
// beam coordinates q_c, its mass matrix and constant load, and either its own
// sparse C and K (the original Rayleigh beam) or the adjusted structure that
// holds it (low_rank_structure.h: a beam of its own, or one of several joined
// by links).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <utility>
#include <vector>

#include "runtime/fem/beam_system.h"
#include "runtime/structure/beam_mesh.h"
#include "runtime/structure/low_rank_structure.h"

namespace mbfe::runtime {

struct CoupledBeam {
  BeamMesh mesh;
  int offset = 0;                  // its first index in q_c
  Eigen::SparseMatrix<double> M;   // kg, free DOFs, symmetric positive definite
  Eigen::VectorXd P;               // N, constant load vector (own weight, point loads)
  /// Its own C and K (N s/m, N/m) when no adjusted structure holds it.
  Eigen::SparseMatrix<double> C, K;
  /// The loads that change with time (runtime/fem/beam_loads.h); null when it has none.
  std::shared_ptr<const BeamSystem> time_loads;
  /// The adjusted structure that holds it (an index into CoupledBeams::structures), -1 for none.
  int structure = -1;
  /// Held by a structure of its own, whose modal form damps each mode by
  /// Rayleigh's alpha + beta omega_j^2: the damping of its discrete parts
  /// that form leaves out (BeamSystem::damping_remainder: free DOF, N s/m),
  /// which the coupled model adds back as a force; empty otherwise.
  std::vector<std::pair<int, double>> damping_remainder;
};

/// The beams of a coupled model and the adjusted structures over them.
struct CoupledBeams {
  std::vector<CoupledBeam> beams;
  std::vector<std::shared_ptr<const LowRankStructure>> structures;
};

/// Mesh of an assembled beam (uniform elements).
BeamMesh beam_mesh(const BeamSystem& beam);
/// The beam with its own Rayleigh C and K, at `offset` in q_c.
CoupledBeam coupled_beam(const BeamSystem& beam, int offset);

}  // namespace mbfe::runtime
