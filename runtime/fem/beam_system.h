// One beam's assembled finite-element system, supports applied:
//   M q'' + C q' + K q = P          (eq (11a) of the paper)
// q = the beam's free DOFs in contract order: nodes from s = 0 to s = L,
// [w, w'] per node, DOFs fixed by supports removed.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ir/model.h"

namespace mbfe::runtime {

/// A point load that changes with time, on free DOF `free_index`.
struct TimedNodalLoad {
  int free_index = -1;
  ir::Expression value;  // N
  ir::TimeWindow window;
};

class RunningSurface;

struct BeamSystem {
  std::string name;
  int num_nodes = 0;                 // elements + 1
  double element_length = 0.0;       // m
  Eigen::SparseMatrix<double> M;     // kg (consistent or lumped), n x n
  Eigen::SparseMatrix<double> K;     // N/m
  Eigen::SparseMatrix<double> C;     // alpha M_e + beta K_e of the elements, plus the supports' dampers
  Eigen::VectorXd P;                 // N: gravity (own weight) + constant point loads
  /// Loads that change with time (runtime/fem/beam_loads.h adds them up at t):
  /// point loads with an expression in t or a time window, moving loads.
  std::vector<TimedNodalLoad> timed_loads;
  std::vector<ir::BeamMovingLoad> moving_loads;
  bool has_time_loads() const { return !timed_loads.empty() || !moving_loads.empty(); }
  /// free_dof[k] = index into the full 2 * num_nodes vector of free DOF k.
  std::vector<int> free_dof;
  /// full_to_free[i] = free index of full DOF i, or -1 if fixed by a support.
  std::vector<int> full_to_free;
  double length = 0.0;               // m
  double rayleigh_alpha = 0.0;       // 1/s (C = alpha M + beta K)
  double rayleigh_beta = 0.0;        // s
  /// C - (alpha M + beta K) over the whole beam: Rayleigh damping is the
  /// elements', while M and K also hold the discrete parts (point masses,
  /// spring supports with their masses), whose dampers C holds as they are.
  /// So the remainder is, per free DOF of a discrete part (sorted, each once),
  /// its dampers' c - alpha m - beta k (N s/m). A modal form that damps every
  /// mode by alpha + beta omega_j^2 adds it to keep the original C
  /// (docs/damping-adjustment.md, "The discrete parts' damping").
  std::vector<std::pair<int, double>> damping_remainder;
  /// S with S^T S = K (r x n, r = 2 per element for the Hermite element), or
  /// empty when the element offers no factor. Used by the sparse modal path.
  Eigen::SparseMatrix<double> stiffness_factor;
  /// What slider contacts ride on beyond w (`profile:`, `camber:`;
  /// runtime/fem/running_surface.h); null for the bare axis.
  std::shared_ptr<const RunningSurface> surface;
};

/// Assembles one beam. @param gravity ground-frame gravity (m/s^2); its
/// transverse component loads the beam with its own weight.
/// The transverse unit vector is the axis rotated by +90 deg,
/// n = (-sin angle, cos angle); positive w and positive point loads point
/// along n. Own weight: uniform q = rho A (g . n) N/m with consistent nodal
/// loads (forces and moments); point loads act on the node's w. Loads on DOFs
/// fixed by a support go to the support (dropped from P).
/// Supports and point loads use their resolved `node` when >= 0, else `at`
/// must fall on a node (within 1e-9 L).
/// @throws std::invalid_argument on a non-positive property, a support or load
/// off the nodes or outside [0, L] (message names the beam).
BeamSystem assemble_beam(const ir::Beam& beam, const ir::Vec2& gravity);

/// Node index of position `s` (m) along `beam`. @throws std::invalid_argument
/// if s is outside [0, L] or not at a node (within 1e-9 L); `what` names the
/// item in the message ("support", "load").
int node_at(const ir::Beam& beam, double s, const char* what);

/// Where position s (m) lies on an assembled beam: its element (0-based; the
/// last element for s = L) and xi = (s - s_e) / le in [0, 1].
struct BeamPoint {
  int element = 0;
  double xi = 0.0;
};
/// @throws std::invalid_argument if s is outside [0, L] (1e-12 L slack).
BeamPoint locate_on_beam(const BeamSystem& beam, double s);

/// w(s), w'(s) and w''(s) as linear maps of the free coordinates q:
/// w(s) = sum_i w[i] q[free_index[i]] over the i with free_index[i] >= 0
/// (-1 marks an element DOF fixed by a support). Hermite element only.
struct BeamPointWeights {
  std::array<int, 4> free_index{-1, -1, -1, -1};
  Eigen::Vector4d w = Eigen::Vector4d::Zero();        // 1
  Eigen::Vector4d dw_ds = Eigen::Vector4d::Zero();    // 1/m
  Eigen::Vector4d d2w_ds2 = Eigen::Vector4d::Zero();  // 1/m^2
};
BeamPointWeights point_weights(const BeamSystem& beam, double s);

/// Transverse displacement w(s) in m for free coordinates q (size = dof).
/// @throws std::invalid_argument if q has the wrong size or s is off the beam.
double deflection_at(const BeamSystem& beam, const Eigen::VectorXd& q, double s);

}  // namespace mbfe::runtime
