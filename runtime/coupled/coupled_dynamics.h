// The explicit dynamics of a coupled model (coupled_model.h): at one state,
// the terms of eqs (15) and the accelerations and multipliers, by the
// saddle-point system or the partitioned elimination (eqs (16)-(17)). The
// formulations that integrate it (coordinate_partitioning.h,
// augmented_system.h, split_beam_system.h) share it.
//
// A CoupledDynamics pairs the constant model (shared between runs and
// threads) with the workspace of one run (CoupledData): building one costs
// allocations, nothing more. Evaluating allocates nothing after the first call
// but for one thing: a column M_c^-1 e_k (inverse_mass_column) is allocated,
// then kept, the first time a constraint contact touches DOF k, so a slider
// pin allocates as it reaches new elements. solve_augmented (the augmented
// formulation; the implicit system's and the tangents' accelerations) forms
// its saddle-point matrix and LU in the data too; only a matrix near singular,
// whose condition Eigen's estimate then judges, allocates.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "runtime/coupled/contact_constraints.h"
#include "runtime/coupled/coupled_model.h"
#include "runtime/coupled/partition_choice.h"
#include "runtime/coupled/structure_lanes.h"
#include "runtime/linalg/small_lu.h"

namespace mbfe::runtime {

/// Contact forces and constraint residuals at one state.
struct ContactReport {
  Eigen::VectorXd lambda;   // multipliers of eq (15), stacked like the rows (N)
  Eigen::VectorXd phi;      // constraint residuals (m)
  double phi_max = 0.0;     // max |Phi| (m)
  std::vector<double> s;    // per contact: position along its beam (m)
  Eigen::VectorXd qdd;      // accelerations [q_b''; q_c''] at this state
};

/// The kept-mode coordinates of the split structures (see
/// CoupledDynamics::split_low_rank_beams) and their rates, at one state.
struct SplitState {
  const Eigen::VectorXd& e;   // per split structure [eta; zeta] (2 m entries), stacked
  const Eigen::VectorXd& ed;
};

/// What one run writes while evaluating a coupled model: one per run or
/// thread, sized when made.
struct CoupledData {
  explicit CoupledData(const CoupledModel& model);

  using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  // The rigid part at the last evaluation: M_b, F_b, Q_b plus the elements'
  // rigid forces, r_b = Q_b + f_b - F_b (driven coordinates eliminated).
  RowMajorMatrix mb_row;
  Eigen::MatrixXd mb;
  Eigen::VectorXd fb, qb_force, rb;
  // Driven joints: the motion, and the rows of M and of F - Q before they
  // were eliminated (for their reactions); the state with the motion imposed.
  DrivenCoordinates::Motion motion;
  Eigen::MatrixXd drive_m_rows;
  Eigen::VectorXd drive_bias, q_motion, qd_motion;
  // The force elements' states (one per element of the model, same order)
  // and their beam forces f_c.
  std::vector<std::unique_ptr<ForceState>> forces;
  Eigen::VectorXd fc_extra;
  // The beams: loads, free accelerations a_c0 = M_c^-1 (P + f_c - C q' - K q).
  Eigen::VectorXd rc, ac0, tmp;
  Eigen::VectorXd ldlt;  // the sparse solves' workspace (linalg/sparse_ldlt_solve.h)
  std::vector<LowRankStructure::Workspace> structures;
  // Constraints: values, W = M_c^-1 J_c^T, H = J_c W, g_c = J_c a_c0, and
  // the columns M_c^-1 e_k of the beam DOFs contacts have touched (a slider
  // visits a few elements, a pin one).
  ConstraintValues cv;
  Eigen::MatrixXd w, h;
  Eigen::VectorXd gc;
  std::vector<std::vector<Eigen::VectorXd>> minv_col;
  // solve_augmented: the saddle-point matrix, its full-pivoting LU, the
  // right-hand side, the solution and a column of scratch.
  Eigen::MatrixXd a_matrix;
  Eigen::FullPivLU<Eigen::MatrixXd> a_lu;
  Eigen::VectorXd a_rhs, a_x, a_tmp;
  // solve_partitioned.
  Eigen::MatrixXd p_jv, p_ju, p_xju, p_xh, p_dir, p_a;
  Eigen::VectorXd p_d, p_rhs, p_base, p_b, p_x, p_mu;
  SmallLu p_jv_lu, p_a_lu;
  // Split coordinates: the q_c, q_c' the forces read (beams that are not
  // split as they are, the DOFs the forces read of split ones made nodal;
  // the other DOFs of split beams hold whatever an earlier evaluation left,
  // and nothing reads them), those DOFs, eta - zeta per split structure and
  // its rate, the kept modes' loads and accelerations.
  Eigen::VectorXd split_qc, split_qcd, split_delta, split_delta_rate, split_acc;
  std::vector<int> split_read;
  // Loads the caller sets while a run goes (CoupledDynamics::set_applied_load).
  struct AppliedLoad {
    int beam = 0;
    double s = 0.0;                     // m along the beam
    int cols[4] = {-1, -1, -1, -1};     // q_c columns of the element's DOFs (-1: fixed)
    double weights[4] = {0, 0, 0, 0};   // the shape functions at s
    std::function<double(double)> value;  // N at t
  };
  std::vector<AppliedLoad> applied;
};

class CoupledDynamics {
 public:
  explicit CoupledDynamics(std::shared_ptr<const CoupledModel> model);

  const CoupledModel& model() const { return *model_; }
  const std::shared_ptr<const CoupledModel>& shared_model() const { return model_; }
  CoupledData& data() { return data_; }
  const CoupledData& data() const { return data_; }
  int nb() const { return model_->nb(); }
  int nc() const { return model_->nc(); }
  int n() const { return model_->n(); }
  int m() const { return model_->m(); }
  const ContactConstraints& constraints() const { return model_->constraints(); }
  const mbfe_model_v1& kernels() const { return model_->kernels(); }

  /// Evaluates M_b, Q_b - F_b, the forces, the constraints with gamma, and
  /// the beam-side products a_c0, W = M_c^-1 J_c^T, H = J_c W.
  /// q, qd: n entries ([q_b; q_c]). `at_q`, if given, holds the constraints
  /// evaluated at this q already (without rates): only gamma is added.
  /// `split`: the kept-mode coordinates of a state in split coordinates, whose
  /// q_c, q_c' then hold each split structure's uniform part s, s' (see
  /// split_low_rank_beams); without it the state is nodal, split beams or not.
  /// @throws std::invalid_argument for vectors of the wrong size.
  void evaluate(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const ConstraintValues* at_q = nullptr, const SplitState* split = nullptr);

  /// After evaluate(): q'' (n) and lambda (m) from the saddle-point system.
  /// @throws SingularConstraintError / SingularMassMatrixError.
  void solve_augmented(double t, Eigen::VectorXd& qdd, Eigen::VectorXd& lambda);
  /// After evaluate(): the same unknowns by the partitioned elimination
  /// (eqs (16)-(17)) with dependent coordinates p.dependent.
  /// @throws SingularConstraintError if J_v or the reduced system is singular.
  void solve_partitioned(double t, const Partition& p, Eigen::VectorXd& qdd, Eigen::VectorXd& lambda);

  /// Split coordinates for the adjusted beams in the low-rank form
  /// (docs/damping-adjustment.md, "Split coordinates"): such a beam's
  /// q = s + Phi_L (eta - zeta), where the uniform part s moves as every
  /// capped mode does,
  ///   s'' = B^-1 f / mu_M - (mu_C s' + mu_K s) / mu_M,
  /// eta are its kept modes and zeta the kept modes of s,
  ///   (mu_M b + d_M) eta'' = g - (mu_C b + d_C) eta' - (mu_K b + d_K) eta,
  ///   zeta'' = g / (mu_M b) - (mu_C zeta' + mu_K zeta) / mu_M,
  /// g = Phi_L^T f, f its loads (low_rank_structure.h for B, mu, d and b).
  /// The forces read q at a few DOFs and load a few, so a right-hand side
  /// reads a few rows of Phi_L; the same ODE, exactly (it keeps
  /// zeta = Phi_L^T M s). Returns false, changing nothing, when the model is
  /// not splittable (CoupledModel::splittable).
  bool split_low_rank_beams();
  /// The split structures (indices into model().structures()), and where each
  /// one's [eta; zeta] starts in the stacked kept-mode coordinates.
  const std::vector<int>& split_structures() const { return split_structure_; }
  const std::vector<int>& split_offsets() const { return split_offset_; }
  /// Entries of the stacked kept-mode coordinates (sum of 2 m).
  int num_split_coordinates() const { return split_size_; }
  /// After split_low_rank_beams: whether the split structures' work of an
  /// evaluation runs on two threads (chosen by their size; the same bits
  /// either way), and a choice other than the default's.
  bool threaded_structures() const { return lanes_ != nullptr && lanes_->threaded(); }
  void set_threaded_structures(bool threaded) { lanes_ = std::make_unique<StructureLanes>(threaded); }
  /// After evaluate() with split structures: the kept-mode accelerations [eta''; zeta''], stacked.
  const Eigen::VectorXd& split_accelerations() const { return data_.split_acc; }
  /// The beam coordinates of split structure k (index into split_structures())
  /// at a state: q = s + Phi_L (eta - zeta), for rates likewise. Every DOF
  /// (s and q over its range), or one (its index within the range).
  void split_to_nodal(int k, const Eigen::Ref<const Eigen::VectorXd>& s, const Eigen::VectorXd& e,
                      Eigen::Ref<Eigen::VectorXd> q) const;
  double split_to_nodal(int k, int dof, double s, const Eigen::VectorXd& e) const;
  /// The stacked kept-mode coordinates [eta; zeta] = [U^T q; U^T q] of nodal
  /// beam coordinates q_c (the same for rates).
  void split_from_nodal(const Eigen::Ref<const Eigen::VectorXd>& qc, Eigen::VectorXd& e) const;

  const ConstraintValues& values() const { return data_.cv; }
  /// Constraint residual max |Phi| at q, and the row holding it.
  double phi_max(const ConstraintValues& cv, int* row = nullptr) const;

  /// The states the force elements found at the last evaluate(): the slider
  /// springs' and the links' (model order).
  const SpringContactState& spring_state(int k) const;
  const LinkState& link_state(int k) const;
  const ForceState& force_state(int element) const { return *data_.forces[static_cast<std::size_t>(element)]; }

  /// A point load on beam `beam` at s m, value(t) in N along the beam's
  /// transverse direction, from now on: an input the caller sets between
  /// steps, not part of the model (it replaces one set before at the same
  /// beam and point). @throws std::invalid_argument for a beam index out of
  /// range or s off the beam.
  void set_applied_load(int beam, double s, std::function<double(double)> value);
  /// Adds the applied loads at t to f_c (nc entries); true if there are any.
  bool add_applied_loads(double t, double* fc) const;
  /// Whether loads set from outside act: then two evaluations at the same
  /// t and state may differ (their values can change between the calls).
  bool has_applied_loads() const { return !data_.applied.empty(); }

  /// Driven joints (`motion:`): their rigid coordinates, model order. In
  /// evaluate() their q and q' are those of the motion at t, whatever the
  /// state says, and the solvers return their q'' = motion''(t).
  const std::vector<int>& driven() const { return model_->driven().indices(); }
  /// Overwrites the driven coordinates of q and qd (n entries) with the motion at t.
  void impose_motion(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd);
  /// After evaluate() and a solve: the generalized force (N or N m) each
  /// driven joint exerts to follow its motion, (M q'' + F - Q)_d.
  void drive_reactions(const Eigen::VectorXd& qdd, Eigen::VectorXd& out) const;

 private:
  // A split structure's s'' (into a, its range of the beams' accelerations)
  // and kept-mode accelerations; f: its loads beyond P, or null.
  void split_accelerations(int k, const Eigen::Ref<const Eigen::VectorXd>& s,
                           const Eigen::Ref<const Eigen::VectorXd>& sd, const double* f,
                           const SplitState& split, Eigen::Ref<Eigen::VectorXd> a);
  // data_.split_qc, split_qcd: the beam coordinates the forces read made
  // nodal (split coordinates), for the rigid coordinates qb.
  void split_read_dofs_nodal(const double* qb, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                             const SplitState& split);
  // y = M_c^-1 e_c for beam DOF c (cached per DOF).
  const Eigen::VectorXd& inverse_mass_column(int beam, int c);

  std::shared_ptr<const CoupledModel> model_;
  CoupledData data_;
  // Split coordinates (split_low_rank_beams): the split structures, where
  // their [eta; zeta] start, and per structure its place among them or -1.
  std::vector<int> split_structure_, split_offset_, split_of_structure_;
  int split_size_ = 0;
  // The q_c ranges of beams that are not split (offset, size): an evaluation
  // in split coordinates copies these whole and only the read DOFs of the rest.
  std::vector<std::pair<int, int>> unsplit_ranges_;
  // The split structures' work of an evaluation on two threads, when they
  // are large enough for it to pay (split_low_rank_beams).
  std::unique_ptr<StructureLanes> lanes_;
};

}  // namespace mbfe::runtime
