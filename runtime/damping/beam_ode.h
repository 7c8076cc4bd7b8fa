// A beam M q'' + C q' + K q = P (original or modally adjusted) as an OdeSystem
// the integrators step, in mass-normalised modal coordinates: q = Phi eta,
// every mode decoupled, m_j eta_j'' + c_j eta_j' + k_j eta_j = phi_j^T P
// (m_j = 1 unless the policy mass raised it). O(n) per right-hand side. Needs
// a complete basis (every mode): the same model as the nodal one
// (runtime/structure/nodal_beam_ode.h), only expressed in other coordinates,
// and every integrator here is linear and commutes with that change of
// variables.
//
// The load is P (constant) plus, when set, a time-dependent part given as
// sparse nodal forces at t (runtime/fem/beam_loads.h).
//
// Damping: c_j per mode, plus, when set, the damping of the beam's discrete
// parts that a Rayleigh c_j = alpha + beta omega_j^2 leaves out
// (BeamSystem::damping_remainder: r diagonal entries R on a few DOFs), as
// Phi_r^T R Phi_r with Phi_r those r rows of Phi: a rank-r coupling, solved
// by Woodbury in the implicit steps (r x r).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "runtime/fem/beam_loads.h"
#include "runtime/integrators/integrator.h"
#include "runtime/modal/modal_basis.h"
#include "runtime/modal/state_spectrum.h"

namespace mbfe::runtime {

class ModalBeamOde final : public LinearSecondOrderSystem {
 public:
  /// @param basis complete, mass-normalised (n modes). @param modes m_j, c_j,
  /// k_j per mode (size n). @param M, P the nodal mass matrix and load (N).
  /// @throws std::invalid_argument on size mismatches, a partial basis or a
  /// modal mass that is not > 0.
  ModalBeamOde(const ModalBasis& basis, const std::vector<ModalDynamics>& modes,
               const Eigen::SparseMatrix<double>& M, const Eigen::VectorXd& P);

  int dof() const override { return static_cast<int>(k_.size()); }
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;
  void solve_shifted(double t, const Eigen::VectorXd& y, double c, const Eigen::VectorXd& b,
                     Eigen::VectorXd& x) override;
  void load(double t, Eigen::VectorXd& out) override;
  void mult_m(const Eigen::VectorXd& x, Eigen::VectorXd& out) override { out = m_.cwiseProduct(x); }
  void mult_c(const Eigen::VectorXd& x, Eigen::VectorXd& out) override;
  void mult_k(const Eigen::VectorXd& x, Eigen::VectorXd& out) override { out = k_.cwiseProduct(x); }
  void solve_combination(double a, double b, double c, const Eigen::VectorXd& r, Eigen::VectorXd& x) override;
  std::string name(int i) const override;

  /// Nodal state [q; q'] of size 2n -> modal [eta; eta'] (eta = Phi^T M q).
  Eigen::VectorXd from_nodal(const Eigen::VectorXd& y_nodal) const;
  /// Modal state -> nodal positions q = Phi eta (n).
  void positions(const Eigen::VectorXd& y, Eigen::VectorXd& q) const;
  const Eigen::MatrixXd& phi() const { return phi_; }
  const Eigen::VectorXd& modal_load() const { return p_; }  // Phi^T P (N)
  /// Adds a time-dependent load (empty function: none).
  void set_time_loads(TimeLoadFn loads) { time_loads_ = std::move(loads); }
  /// Adds nodal damping on a few DOFs (DOF index, N s/m), on top of the modes'
  /// own c_j. @throws std::invalid_argument for a DOF outside the beam.
  void set_damping_remainder(const std::vector<std::pair<int, double>>& remainder);
  /// Phi^T (P + P_t(t)) (N).
  void modal_load_at(double t, Eigen::VectorXd& out);

 private:
  /// x with (diag(d) + s Phi_r^T R Phi_r) x = rhs.
  void solve_damped(const Eigen::VectorXd& d, double s, const Eigen::VectorXd& rhs, Eigen::VectorXd& x) const;

  Eigen::MatrixXd phi_, mphi_;  // Phi, M Phi
  Eigen::VectorXd k_, c_, m_, p_;  // per mode; p = Phi^T P
  Eigen::MatrixXd phi_r_;          // the remainder's rows of Phi (r x n)
  Eigen::VectorXd remainder_;      // R (r), N s/m
  Eigen::VectorXd v_r_;            // scratch: Phi_r eta' (r)
  bool unit_mass_ = true;          // every m_j == 1: the right-hand side skips the division
  TimeLoadFn time_loads_;
  std::vector<NodalForce> forces_;  // scratch
  Eigen::VectorXd pt_;              // scratch
};

}  // namespace mbfe::runtime
