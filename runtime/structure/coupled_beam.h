// One beam as the coupled system sees it: its mesh, mass matrix, load and
// internal force C q' + K q as a callback, so that the adjusted C and K of the
// damping adjustment (sparse, dense or low-rank) plug in unchanged.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <vector>

#include "runtime/fem/beam_loads.h"
#include "runtime/fem/beam_system.h"
#include "runtime/structure/beam_mesh.h"

namespace mbfe::runtime {

/// f = C qd + K q (N) for one beam; q, qd, f have the beam's free-DOF count.
using BeamForceFn = std::function<void(const Eigen::Ref<const Eigen::VectorXd>& q,
                                       const Eigen::Ref<const Eigen::VectorXd>& qd,
                                       Eigen::Ref<Eigen::VectorXd> f)>;

/// f = C qd + K q with sparse C, K (copied into the callback).
BeamForceFn sparse_beam_force(Eigen::SparseMatrix<double> C, Eigen::SparseMatrix<double> K);
/// f = C qd + K q with dense C, K (e.g. eq (27) adjusted matrices).
BeamForceFn dense_beam_force(Eigen::MatrixXd C, Eigen::MatrixXd K);

/// The low-rank part of a beam's C and K (the low-rank adjusted beam,
/// docs/damping-adjustment.md): C q' + K q gains U (d_C .* U^T q' + d_K .* U^T q).
struct BeamLowRank {
  Eigen::MatrixXd U;         // n x m, M Phi_L (the kept modes)
  Eigen::VectorXd d_C, d_K;  // m
  /// Phi_L = M^-1 U by rows (the split coordinates read a few rows at a
  /// time: coupled_dynamics.h), and the cap's modal damping and stiffness,
  /// the beam's C = c* M and K = k* M.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> phi_rows;
  double c_star = 0.0, k_star = 0.0;
};

/// The low-rank part shared by the beams of a joined structure (beams joined
/// by links, adjusted together; docs/catenary.md): over the stacked
/// coordinates x of its beams, C x' + K x gains U (d_C .* U^T x' + d_K .* U^T x),
/// and each member beam's own part is c* M, k* M. The links inside act as
/// forces only by what departs from their linear part (beam_links.h).
struct JoinedLowRank {
  std::vector<int> beams;    // member beams (model order); U's rows stack their free DOFs in this order
  std::vector<int> links;    // the links inside (model order)
  Eigen::MatrixXd U;         // n_s x m, M_s Phi_L
  Eigen::MatrixXd phi;       // n_s x m, Phi_L = M_s^-1 U
  Eigen::VectorXd d_C, d_K;  // m
};

/// One beam as the coupled system sees it.
struct CoupledBeam {
  BeamMesh mesh;
  Eigen::SparseMatrix<double> M;  // kg, free DOFs, symmetric positive definite
  Eigen::VectorXd P;              // N, constant load vector (own weight, point loads)
  BeamForceFn force;              // internal force C qd + K q
  /// Optional: the free acceleration a = M^-1 (P - C qd - K q) written into
  /// the third argument, for operators that give it without a solve with M
  /// (the low-rank adjusted beam: M^-1 U = Phi_L). Empty: force, then a
  /// sparse M solve. Must agree with M, P and force.
  BeamForceFn acceleration;
  /// Optional: the loads that change with time (runtime/fem/beam_loads.h), on
  /// this beam's free DOFs.
  TimeLoadFn time_loads;
  /// The sparse C and K of `force`, which is C q' + K q, plus the low-rank
  /// part when `low_rank` is set: the original Rayleigh beam's own C and K;
  /// for the low-rank adjusted beam c* M and k* M with the kept modes'
  /// corrections in `low_rank`; empty for eq (27) over every mode. The Newton
  /// matrix of the implicit steppers is built from them.
  Eigen::SparseMatrix<double> C, K;
  std::shared_ptr<const BeamLowRank> low_rank;
};

/// Mesh of an assembled beam (uniform elements).
BeamMesh beam_mesh(const BeamSystem& beam);
/// The beam with its own Rayleigh C and K.
CoupledBeam coupled_beam(const BeamSystem& beam);
/// The beam with another internal force (adjusted damping): M and P from `beam`.
CoupledBeam coupled_beam(const BeamSystem& beam, BeamForceFn force);

}  // namespace mbfe::runtime
