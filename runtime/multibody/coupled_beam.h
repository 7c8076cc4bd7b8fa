// One beam as the coupled system sees it: its mesh, mass matrix, load and
// internal force C q' + K q as a callback, so that the adjusted C and K of the
// damping adjustment (sparse, dense or low-rank) plug in unchanged.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>

#include "runtime/fem/beam_loads.h"
#include "runtime/fem/beam_system.h"
#include "runtime/multibody/contact_constraints.h"

namespace mbfe::runtime {

/// f = C qd + K q (N) for one beam; q, qd, f have the beam's free-DOF count.
using BeamForceFn = std::function<void(const Eigen::Ref<const Eigen::VectorXd>& q,
                                       const Eigen::Ref<const Eigen::VectorXd>& qd,
                                       Eigen::Ref<Eigen::VectorXd> f)>;

/// f = C qd + K q with sparse C, K (copied into the callback).
BeamForceFn sparse_beam_force(Eigen::SparseMatrix<double> C, Eigen::SparseMatrix<double> K);
/// f = C qd + K q with dense C, K (e.g. eq (27) adjusted matrices).
BeamForceFn dense_beam_force(Eigen::MatrixXd C, Eigen::MatrixXd K);

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
  /// The sparse C and K of `force` when it is C q' + K q with sparse matrices
  /// (the original Rayleigh beam); empty for the adjusted operators. The
  /// Newton matrix of the implicit steppers is built from them.
  Eigen::SparseMatrix<double> C, K;
};

/// Mesh of an assembled beam (uniform elements).
BeamMesh beam_mesh(const BeamSystem& beam);
/// The beam with its own Rayleigh C and K.
CoupledBeam coupled_beam(const BeamSystem& beam);
/// The beam with another internal force (adjusted damping): M and P from `beam`.
CoupledBeam coupled_beam(const BeamSystem& beam, BeamForceFn force);

}  // namespace mbfe::runtime
