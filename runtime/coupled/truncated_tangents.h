// The linearisation of a coupled model whose beams are truncated (policy
// truncate, docs/damping-adjustment.md): each beam moves in its kept modes
// alone, q_c = Phi_L eta, so the ODE that is integrated lives in
// z_r = [the free rigid coordinates; every structure's eta]. Its tangents are
// the coupled model's (coupled_tangents.h) projected on that basis,
//
//   M_r = T^T M T,  C_r = T^T C_t T,  K_r = T^T K_t T,   T = diag(I, Phi_L, ...),
//
// a Galerkin projection that is the truncated system's own linearisation:
// on a truncated structure each term mu B + U diag(d) U^T projects to
// diag(mu b_j + d_j), the modal mass, damping and stiffness the run steps
// with (CoupledDynamics::split_accelerations); the rigid block and the force
// elements' tangents (contacts, droppers, links) are projected entry by entry
// from the rows of Phi_L they touch. Dense: a truncation keeps hundreds to a
// few thousand modes. tangent_spectrum.h takes the result as it takes the
// nodal tangents.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <vector>

#include "runtime/coupled/coupled_tangents.h"
#include "runtime/coupled/state_operator.h"

namespace mbfe::runtime {

class TruncatedTangents final : public StateOperator {
 public:
  /// @throws std::invalid_argument unless every beam of the tangents' model
  ///         is in a truncated structure.
  explicit TruncatedTangents(const CoupledTangents& tangents);

  int size() const override { return static_cast<int>(m_.rows()); }
  int num_driven() const override { return num_driven_; }
  void apply_state_matrix(const double* in, double* out) const override;
  void factorize_shifted(double sigma) override;
  double shift() const override { return sigma_; }
  void solve_shifted(const double* in, double* out) const override;
  Eigen::MatrixXd dense_state_matrix() const override;

  /// The kept modes' amplitudes: the last modal_size() reduced coordinates.
  int modal_size() const { return static_cast<int>(modal_mass_.size()); }
  /// The reduced matrices.
  const Eigen::MatrixXd& mass() const { return m_; }
  const Eigen::MatrixXd& damping() const { return c_; }
  const Eigen::MatrixXd& stiffness() const { return k_; }

 private:
  // x = M_r^-1 r: the rigid block by its LU, the modal masses by division
  // (M_r is block diagonal: no force element has mass).
  void solve_mass(const Eigen::VectorXd& r, Eigen::VectorXd& x) const;

  int rigid_ = 0, num_driven_ = 0;
  Eigen::MatrixXd m_, c_, k_;
  Eigen::PartialPivLU<Eigen::MatrixXd> rigid_mass_lu_;
  Eigen::VectorXd modal_mass_;
  double sigma_ = 0.0;
  bool factored_ = false;
  Eigen::PartialPivLU<Eigen::MatrixXd> shifted_lu_;
  mutable Eigen::VectorXd tmp_, rhs_, sol_;
};

}  // namespace mbfe::runtime
