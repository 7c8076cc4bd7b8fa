// The rigid part of a model alone, M(q) v' + F(q, v) = Q(q, v, t) (eq (6)),
// as a first-order system y = [q; v] for the integrators: q' = v for planar
// models and spatial ones of revolute and prismatic joints, q' = G(q) v (the
// kernel position_derivative) where a joint has a quaternion, renormalised
// after every accepted step.
//
//   const mbfe_model_v1& model = *mbfe_model_double_pendulum();
//   runtime::RigidSystem system(model, runtime::body_inertias(ir));
//   auto stepper = runtime::make_stepper(runtime::parse_integrator("rk4"), system);
//
// The generated kernels write M, F, Q; the runtime factors M numerically
// (LLT) at every evaluation. Nothing is allocated per rhs() call.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/integrators/ode_system.h"
#include "runtime/multibody/rigid_coordinates.h"
#include "ir/model.h"

namespace mbfe::runtime {

/// Mass properties of one body, for diagnostics (which bodies carry no inertia).
struct BodyInertia {
  std::string name;
  double mass = 0.0;     // kg
  double inertia = 0.0;  // kg m^2 about the centre of mass (spatial: the trace of the tensor)
};

/// One entry per body of `model`, in model (= coordinate) order.
std::vector<BodyInertia> body_inertias(const ir::Model& model);

/// M, F, Q of the rigid part at one state (Eigen, column-major).
struct RigidTerms {
  Eigen::MatrixXd M;  // nq x nq, kg / kg m / kg m^2 by coordinate type
  Eigen::VectorXd F;  // nq, velocity-dependent inertial terms (N or N m)
  Eigen::VectorXd Q;  // nq, gravity, loads, springs (N or N m)
};

/// M (row-major nq x nq), F and Q of `model` at (q, qd, t), each nq entries
/// (M nq^2): by the fused `dynamics` kernel when the solver has one (it shares
/// the kinematics), else by the three kernels.
void evaluate_dynamics(const mbfe_model_v1& model, const double* q, const double* qd, double t,
                       double* M_row_major, double* F, double* Q);

/// Evaluates the kernels of `model` at (q, qd, t) into `out` (resized if needed).
/// @throws std::invalid_argument if q or qd does not have num_coordinates entries.
void evaluate_rigid_terms(const mbfe_model_v1& model, const Eigen::VectorXd& q,
                          const Eigen::VectorXd& qd, double t, RigidTerms& out);

/// Message and exception for a mass matrix that is not positive definite at
/// (t, M). A coordinate with M_ii = 0 moves no mass: the message names those
/// and the bodies of `bodies` with no mass and no inertia, and asks for mass.
/// A null direction whose coordinates all have M_ii > 0 is singular only
/// numerically (a state grown far beyond the model's range, usually by a step
/// beyond the stable limit): the message says so and points to `mbfe advise`.
/// Used by RigidSystem and the coupled systems.
[[noreturn]] void throw_singular_mass_matrix(const mbfe_model_v1& model,
                                             const std::vector<BodyInertia>& bodies,
                                             const Eigen::MatrixXd& M, double t);

/// y = [q; v] (nq + nv entries); y' = [G(q) v; M^-1 (Q - F)].
class RigidSystem : public OdeSystem {
 public:
  /// @param model the generated solver; must outlive this object.
  /// @param bodies mass properties in coordinate order, for the message of a
  ///        singular mass matrix; empty = unknown (the message then names only
  ///        the coordinates). @throws std::invalid_argument if `bodies` is not
  ///        empty and has a size other than the model's bodies, or the ABI
  ///        version differs from MBFE_MODEL_ABI_VERSION.
  /// @param coordinates the layout of q and v (rigid_coordinates of the IR);
  ///        empty (nq = 0) = one of each per coordinate of the solver, which
  ///        must then have nv = nq.
  explicit RigidSystem(const mbfe_model_v1& model, std::vector<BodyInertia> bodies = {},
                       RigidCoordinates coordinates = {});

  int size() const override { return nq_ + nv_; }
  /// nq, the position coordinates.
  int num_coordinates() const { return nq_; }
  /// nv, the velocity coordinates (= nq without quaternions).
  int num_velocities() const { return nv_; }
  const RigidCoordinates& coordinates() const { return coordinates_; }

  /// Renormalises the quaternions of y (none: nothing).
  void after_step(double t, Eigen::VectorXd& y) override;

  /// @throws std::invalid_argument if y has the wrong size.
  /// @throws SingularMassMatrixError if M(q) is not positive definite
  ///         (reciprocal condition estimate below kMassRcondFloor).
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;

  /// "<coordinate>" for q, "<coordinate>_dot" for q' (and the layout's
  /// names of the velocities of spherical and free joints).
  std::string name(int i) const override;

  /// Total mechanical energy is not defined by the ABI (no potential kernel);
  /// kinetic energy 1/2 v^T M(q) v in J at y.
  double kinetic_energy(const Eigen::VectorXd& y);

  /// Driven joints (`motion:`): their coordinates, model order. rhs() takes
  /// their q and q' from the motion at t, not from y, and gives their
  /// q'' = motion''(t): the free coordinates follow
  /// M_ff q''_f = Q_f - F_f - M_fd q''_d.
  const std::vector<int>& driven() const { return driven_; }
  /// Overwrites the driven entries of y = [q; q'] with the motion at t.
  void impose_motion(double t, Eigen::VectorXd& y) const;
  /// The generalized force (N or N m) each driven joint exerts at (t, y) to
  /// follow its motion: (M q'' + F - Q)_d.
  void drive_reactions(double t, const Eigen::VectorXd& y, Eigen::VectorXd& out);

  /// M is declared singular below this reciprocal condition estimate.
  static constexpr double kMassRcondFloor = 1e-13;

 private:
  const mbfe_model_v1& model_;
  std::vector<BodyInertia> bodies_;
  RigidCoordinates coordinates_;
  int nq_, nv_;
  // Per driven joint: its entry of q (driven_ indexes v).
  std::vector<int> driven_positions_;
  // Workspace, sized once.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m_row_;
  Eigen::MatrixXd m_;
  Eigen::VectorXd f_, q_force_, rhs_, qdd_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  std::vector<int> driven_;
  mutable Eigen::VectorXd drive_q_, drive_qd_, drive_qdd_;
  Eigen::VectorXd y_motion_;
};

}  // namespace mbfe::runtime
