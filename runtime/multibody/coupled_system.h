// The coupled rigid + beam model of Section 4 (eqs (14)-(17)):
//
//   M_b(q_b) q_b'' + F_b + J_b^T lambda = Q_b                  (15a)
//   M_c q_c'' + C_c q_c' + K_c q_c + J_c^T lambda = P_c        (15b)
//   Phi(q_b, q_c) = 0                                          (15c)
//
// with the contact constraints of contact_constraints.h. Two formulations, both
// OdeSystems for the integrators (docs/partitioning.md gives the formulas):
//
// - PartitionedSystem (the paper's, eqs (16)-(17)): q_b = (u, v), the m
//   dependent coordinates v chosen among q_b by the largest pivots of J_b
//   (column-pivoted QR) and chosen again when J_v becomes ill-conditioned. The
//   state is y = [u; q_c; u'; q_c']; v is closed by Newton on Phi at every
//   evaluation (|Phi| <= closure_tol, in practice ~1e-15 m), v' by the velocity
//   constraint. An ODE in (u, q_c) that explicit integrators step as is.
// - AugmentedSystem (cross-check): y = [q_b; q_c; q_b'; q_c'], accelerations
//   and multipliers from the saddle-point system
//   [[M, J^T], [J, 0]] [q''; lambda] = [Q - F; gamma]; no drift correction, so
//   |Phi| drifts with the integration error (reported).
//
// Beams enter through their mass matrix, load vector and a callback for the
// internal force C q' + K q, so that the adjusted C and K of the damping
// adjustment (sparse, dense or low-rank) plug in unchanged.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/fem/beam_system.h"
#include "runtime/integrators/ode_system.h"
#include "runtime/multibody/contact_constraints.h"
#include "runtime/multibody/rigid_system.h"
#include "runtime/multibody/small_lu.h"

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
};

/// Mesh of an assembled beam (uniform elements).
BeamMesh beam_mesh(const BeamSystem& beam);
/// The beam with its own Rayleigh C and K.
CoupledBeam coupled_beam(const BeamSystem& beam);
/// The beam with another internal force (adjusted damping): M and P from `beam`.
CoupledBeam coupled_beam(const BeamSystem& beam, BeamForceFn force);

/// Which rigid coordinates are dependent (v, m of them) and independent (u).
struct Partition {
  std::vector<int> dependent;    // ascending rigid indices
  std::vector<int> independent;  // ascending rigid indices
};

/// The best partition for the rigid Jacobian cv.jb (m x nb): the columns of
/// the first m pivots of a column-pivoted QR (largest pivots). `sigma_min`
/// receives the smallest singular value of the chosen J_v (the quality measure
/// that PartitionedSystem compares between partitions).
/// @throws SingularConstraintError (naming the contact most involved in the
///         rank loss, t and sigma_min / scale) if sigma_min(J_v) is below 1e-13
///         times constraint_scale(cv): J_b has rank < m.
Partition choose_partition(const ContactConstraints& cc, const ConstraintValues& cv, double t,
                           double* sigma_min = nullptr);

/// Scale of the constraint Jacobian, max(sigma_max(J_b), max |J_e|), against
/// which a singular J_v is judged (so that a J_b that vanishes as a whole, a
/// linkage at a dead point, is caught).
double constraint_scale(const ConstraintValues& cv);

/// Smallest singular value of a matrix (1 for an empty one).
double sigma_min(const Eigen::MatrixXd& a);

/// J_v is declared singular when sigma_min(J_v) < kSingularConstraint x
/// constraint_scale(cv) (double precision with a margin of ~1e3 ulps).
constexpr double kSingularConstraint = 1e-13;

/// A cheap sufficient test (rigorous up to the rounding of the LU) that J_v,
/// factored as `jv_lu`, passes the singularity test: a lower bound of
/// sigma_min(J_v) (the pivot bound of SmallLu, then 1 / ||J_v^-1||_F) against an upper bound of
/// constraint_scale(cv) (||J_b||_F, max |J_e|). When it returns false the
/// caller runs the exact (SVD) test; it only saves the SVDs on the common,
/// healthy path.
bool clearly_regular(SmallLu& jv_lu, const ConstraintValues& cv);

/// Contact forces and constraint residuals at one state.
struct ContactReport {
  Eigen::VectorXd lambda;   // multipliers of eq (15), stacked like the rows (N)
  Eigen::VectorXd phi;      // constraint residuals (m)
  double phi_max = 0.0;     // max |Phi| (m)
  std::vector<double> s;    // per contact: position along its beam (m)
};

/// The shared core: rigid kernels, factored beam mass matrices and the two
/// acceleration solvers. The model and this object's beams are constant; all
/// scratch lives in members (one object per simulating thread).
class CoupledDynamics {
 public:
  /// @throws std::invalid_argument for inconsistent beams / contacts,
  ///         std::runtime_error if a beam mass matrix is not positive definite.
  CoupledDynamics(const mbfe_model_v1& model, std::vector<CoupledBeam> beams,
                  std::vector<BodyInertia> bodies = {});

  int nb() const { return nb_; }
  int nc() const { return nc_; }
  int n() const { return nb_ + nc_; }
  int m() const { return cc_.num_rows(); }
  const ContactConstraints& constraints() const { return cc_; }
  const mbfe_model_v1& model() const { return model_; }
  const std::vector<CoupledBeam>& beams() const { return beams_; }

  /// Evaluates M_b, Q_b - F_b, P_c - f_c, the constraints with gamma, and the
  /// beam-side products a_c0 = M_c^-1 r_c, W = M_c^-1 J_c^T, H = J_c W.
  /// q, qd: n entries ([q_b; q_c]). `at_q`, if given, holds the constraints
  /// evaluated at this q already (without rates): only gamma is added.
  void evaluate(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const ConstraintValues* at_q = nullptr);
  const ConstraintValues& values() const { return cv_; }

  /// After evaluate(): q'' (n) and lambda (m) from the saddle-point system.
  /// @throws SingularConstraintError / SingularMassMatrixError.
  void solve_augmented(double t, Eigen::VectorXd& qdd, Eigen::VectorXd& lambda);
  /// After evaluate(): the same unknowns by the partitioned elimination
  /// (eqs (16)-(17)) with dependent coordinates p.dependent.
  /// @throws SingularConstraintError if J_v or the reduced system is singular.
  void solve_partitioned(double t, const Partition& p, Eigen::VectorXd& qdd,
                         Eigen::VectorXd& lambda);

  /// Constraint residual max |Phi| at q, and the row holding it.
  double phi_max(const ConstraintValues& cv, int* row = nullptr) const;

 private:
  const mbfe_model_v1& model_;
  std::vector<CoupledBeam> beams_;
  std::vector<BodyInertia> bodies_;
  ContactConstraints cc_;
  int nb_, nc_;
  std::vector<std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>> mc_factor_;
  // Workspace.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> mb_row_;
  Eigen::MatrixXd mb_;
  Eigen::VectorXd fb_, qb_force_, rb_, rc_, ac0_, gc_, tmp_;
  Eigen::MatrixXd w_, h_;
  ConstraintValues cv_;
  // Workspace of solve_partitioned (sized on first use, no allocation after).
  Eigen::MatrixXd p_jv_, p_ju_, p_xju_, p_xh_, p_dir_, p_a_;
  Eigen::VectorXd p_d_, p_rhs_, p_base_, p_b_, p_x_, p_mu_;
  SmallLu p_jv_lu_, p_a_lu_;
  // M_c^-1 e_k of the beam DOFs that contacts have touched, per beam
  // (computed on first use: a slider visits a few elements, a pin one).
  std::vector<std::vector<Eigen::VectorXd>> minv_col_;
};

/// Common face of the two formulations.
class CoupledSystem : public OdeSystem {
 public:
  explicit CoupledSystem(std::shared_ptr<CoupledDynamics> dyn) : dyn_(std::move(dyn)) {}
  CoupledDynamics& dynamics() { return *dyn_; }

  /// A consistent initial y from full coordinates q = [q_b; q_c], qd (n each).
  /// Partitioned: keeps u, q_c, u', q_c' and closes v, v'. Augmented: as given.
  virtual Eigen::VectorXd initial_state(double t, const Eigen::VectorXd& q,
                                        const Eigen::VectorXd& qd) = 0;
  /// Full coordinates [q_b; q_c] and rates at y.
  virtual void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q,
                          Eigen::VectorXd& qd) = 0;
  /// Multipliers, residuals and slider positions at (t, y).
  virtual ContactReport report(double t, const Eigen::VectorXd& y) = 0;

 protected:
  std::shared_ptr<CoupledDynamics> dyn_;
};

struct PartitionOptions {
  double closure_tol = 1e-10;   // m: Newton must bring max |Phi| below this
  int max_newton = 30;          // iterations per closure
  /// Choose the partition again when sigma_min of the current J_v falls below
  /// this fraction of the best partition's (hysteresis: 0.1 avoids flip-flop).
  double repartition_ratio = 0.1;
  /// Dependent coordinates to start with (rigid indices, m of them); empty =
  /// chosen automatically. Checked by initial_state().
  std::vector<int> initial_dependent;
};

/// Coordinate partitioning, eqs (16)-(17). y = [u; q_c; u'; q_c'].
class PartitionedSystem : public CoupledSystem {
 public:
  PartitionedSystem(std::shared_ptr<CoupledDynamics> dyn, PartitionOptions opt = {});

  int size() const override { return 2 * nz_; }
  /// @throws NewtonClosureError, SingularConstraintError, SliderOffBeamError.
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;
  /// Closes v at the accepted y, keeps it as the next Newton start and chooses
  /// the partition again if J_v has become ill-conditioned (then y is rewritten
  /// in the new independent coordinates: size unchanged, meaning changed).
  void after_step(double t, Eigen::VectorXd& y) override;
  std::string name(int i) const override;

  Eigen::VectorXd initial_state(double t, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& qd) override;
  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q,
                  Eigen::VectorXd& qd) override;
  ContactReport report(double t, const Eigen::VectorXd& y) override;

  const Partition& partition() const { return part_; }
  /// How many times the partition was chosen again since construction.
  int repartitions() const { return repartitions_; }
  /// Newton iterations of the last closure.
  int last_newton_iterations() const { return last_iters_; }

 private:
  // Fills q_, qd_ (full) from y with v closed and v' projected.
  void close(double t, const Eigen::VectorXd& y);
  void set_partition(const Partition& p);

  PartitionOptions opt_;
  Partition part_;
  int nu_ = 0, nz_ = 0;
  int repartitions_ = 0, last_iters_ = 0;
  // Newton's start for v: the v and v' of the last accepted state (after_step)
  // at time t, extrapolated to the time asked for (error O(h^2) instead of
  // O(h): one Newton iteration fewer per step) when that time is within a few
  // accepted steps h of t.
  struct Guess {
    Eigen::VectorXd v, vd;
    double t = 0.0, h = 0.0;  // h: the last accepted step (0: none yet)
    bool valid = false;       // v, vd, t describe an accepted state
  };
  // The accepted, closed state q_, qd_ at t becomes the next Newton start.
  void remember_start(double t);
  Guess guess_;
  Eigen::VectorXd q_, qd_, qdd_, lambda_;
  Eigen::MatrixXd jv_;
  SmallLu jv_lu_;  // of jv_ at the last closed state
  ConstraintValues cv_close_;  // of close(), at the last closed state (after_step reads it)
  Eigen::VectorXd dv_, r_, vd_;   // workspace of close()
  // The y of the last successful closure: an integrator evaluates f at the
  // state after_step() has just closed, which need not be closed again.
  Eigen::VectorXd closed_y_;
  bool closed_valid_ = false;
};

/// The augmented (multiplier) formulation. y = [q_b; q_c; q_b'; q_c'].
class AugmentedSystem : public CoupledSystem {
 public:
  explicit AugmentedSystem(std::shared_ptr<CoupledDynamics> dyn);
  int size() const override { return 2 * dyn_->n(); }
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;
  std::string name(int i) const override;
  Eigen::VectorXd initial_state(double t, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& qd) override;
  void full_state(double t, const Eigen::VectorXd& y, Eigen::VectorXd& q,
                  Eigen::VectorXd& qd) override;
  ContactReport report(double t, const Eigen::VectorXd& y) override;

 private:
  Eigen::VectorXd q_, qd_, qdd_, lambda_;
};

/// Names of the full coordinates [q_b; q_c]: rigid coordinate names, then
/// "<beam>_w<node>" / "<beam>_dw<node>" for the free beam DOFs.
std::vector<std::string> coupled_coordinate_names(const CoupledDynamics& dyn);

}  // namespace mbfe::runtime
