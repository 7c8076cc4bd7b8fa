// The coupled rigid + beam model of Section 4 (eqs (14)-(17)):
//
//   M_b(q_b) q_b'' + F_b + J_b^T lambda = Q_b                  (15a)
//   M_c q_c'' + C_c q_c' + K_c q_c + J_c^T lambda = P_c        (15b)
//   Phi(q_b, q_c) = 0                                          (15c)
//
// CoupledDynamics evaluates the terms at one state and solves for the
// accelerations and multipliers, by the saddle-point system or by the
// partitioned elimination; the two formulations that integrate it
// (coordinate_partitioning.h, augmented_system.h) share it.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/structure/beam_links.h"
#include "runtime/coupled/contact_constraints.h"
#include "runtime/coupled/contact_springs.h"
#include "runtime/structure/coupled_beam.h"
#include "runtime/coupled/partition_choice.h"
#include "runtime/multibody/rigid_system.h"
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

/// The kept-mode coordinates of the beams in split coordinates (see
/// CoupledDynamics::split_low_rank_beams) and their rates, at one state.
struct SplitState {
  const Eigen::VectorXd& e;   // per split beam [eta; zeta] (2 m entries), stacked
  const Eigen::VectorXd& ed;
};

/// The shared core: rigid kernels, factored beam mass matrices and the two
/// acceleration solvers. The model and this object's beams are constant; all
/// scratch lives in members (one object per simulating thread).
class CoupledDynamics {
 public:
  /// `joined`: the low-rank parts of joined structures (coupled_beam.h); their
  /// member beams carry only their own part, their links are marked inside.
  /// @throws std::invalid_argument for inconsistent beams / contacts / joined
  ///         structures, std::runtime_error if a beam mass matrix is not positive definite.
  CoupledDynamics(const mbfe_model_v1& model, std::vector<CoupledBeam> beams,
                  std::vector<BodyInertia> bodies = {}, const std::vector<ir::Link>& links = {},
                  std::vector<std::shared_ptr<const JoinedLowRank>> joined = {});

  int nb() const { return nb_; }
  int nc() const { return nc_; }
  int n() const { return nb_ + nc_; }
  int m() const { return cc_.num_rows(); }
  const ContactConstraints& constraints() const { return cc_; }
  const mbfe_model_v1& model() const { return model_; }
  const std::vector<CoupledBeam>& beams() const { return beams_; }
  const std::vector<std::shared_ptr<const JoinedLowRank>>& joined() const { return joined_; }

  /// Evaluates M_b, Q_b - F_b, P_c - f_c, the constraints with gamma, and the
  /// beam-side products a_c0 = M_c^-1 r_c, W = M_c^-1 J_c^T, H = J_c W.
  /// q, qd: n entries ([q_b; q_c]). `at_q`, if given, holds the constraints
  /// evaluated at this q already (without rates): only gamma is added.
  /// `split`: the kept-mode coordinates of a state in split coordinates, whose
  /// q_c, q_c' then hold each split beam's uniform part s, s' (see
  /// split_low_rank_beams); without it the state is nodal, split beams or not.
  void evaluate(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                const ConstraintValues* at_q = nullptr, const SplitState* split = nullptr);

  /// Split coordinates for the low-rank adjusted beams (docs/damping-adjustment.md,
  /// "Split coordinates"): such a beam's q = s + Phi_L (eta - zeta), where the
  /// uniform part s moves as if every mode had the cap,
  ///   s'' = M^-1 f - c* s' - k* s,
  /// eta are its kept modes and zeta the kept modes of s,
  ///   eta''  = Phi_L^T f - (c* + d_C) .* eta' - (k* + d_K) .* eta,
  ///   zeta'' = Phi_L^T f - c* zeta' - k* zeta,
  /// f its loads. The forces read q at a few DOFs (contacts, links) and load a
  /// few, so a right-hand side reads a few rows of Phi_L instead of every
  /// entry of U and Phi_L; the same ODE, exactly (it keeps zeta = Phi_L^T M s).
  /// Returns false, changing nothing, for a model with constraint contacts or
  /// joined structures, or without low-rank beams.
  bool split_low_rank_beams();
  /// The split beams (indices into beams()), and where each one's [eta; zeta]
  /// starts in the stacked kept-mode coordinates.
  const std::vector<int>& split_beams() const { return split_beam_; }
  const std::vector<int>& split_offsets() const { return split_offset_; }
  /// Entries of the stacked kept-mode coordinates (sum of 2 m).
  int num_split_coordinates() const { return split_size_; }
  /// After evaluate() with split beams: the kept-mode accelerations [eta''; zeta''], stacked.
  const Eigen::VectorXd& split_accelerations() const { return split_acc_; }
  /// The beam coordinates of split beam k (index into split_beams()) at a
  /// state: q = s + Phi_L (eta - zeta), for rates likewise. Every DOF, or one.
  void split_to_nodal(int k, const Eigen::Ref<const Eigen::VectorXd>& s, const Eigen::VectorXd& e,
                      Eigen::Ref<Eigen::VectorXd> q) const;
  double split_to_nodal(int k, int dof, double s, const Eigen::VectorXd& e) const;
  /// The stacked kept-mode coordinates [eta; zeta] = [Phi_L^T M q; Phi_L^T M q]
  /// of nodal beam coordinates q_c (the same for rates).
  void split_from_nodal(const Eigen::Ref<const Eigen::VectorXd>& qc, Eigen::VectorXd& e) const;
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

  /// The slider_spring contacts; states() are those of the last evaluate().
  const ContactSprings& springs() const { return springs_; }
  /// The links between beams (droppers); states() are those of the last evaluate().
  const BeamLinks& links() const { return links_; }
  BeamLinks& links() { return links_; }

  /// Driven joints (`motion:`): their rigid coordinates, model order. In
  /// evaluate() their q and q' are those of the motion at t, whatever the
  /// state says, and the solvers return their q'' = motion''(t).
  const std::vector<int>& driven() const { return driven_; }
  /// Overwrites the driven coordinates of q and qd (n entries) with the motion at t.
  void impose_motion(double t, Eigen::VectorXd& q, Eigen::VectorXd& qd) const;
  /// After evaluate() and a solve: the generalized force (N or N m) each
  /// driven joint exerts to follow its motion, (M q'' + F - Q)_d.
  void drive_reactions(const Eigen::VectorXd& qdd, Eigen::VectorXd& out) const;

 private:
  // a (the beam's q_c'' slot) = s'' and the kept-mode accelerations of
  // split beam `beam` (index into beams_); f: its loads beyond P (s.size()
  // entries), or null.
  void split_accelerations(int beam, const Eigen::Ref<const Eigen::VectorXd>& s,
                           const Eigen::Ref<const Eigen::VectorXd>& sd, const double* f,
                           const SplitState& split, Eigen::Ref<Eigen::VectorXd> a);

  const mbfe_model_v1& model_;
  std::vector<CoupledBeam> beams_;
  std::vector<BodyInertia> bodies_;
  ContactConstraints cc_;
  ContactSprings springs_;
  BeamLinks links_;
  std::vector<std::shared_ptr<const JoinedLowRank>> joined_;
  int nb_, nc_;
  std::vector<int> driven_;
  // Driven joints at the last evaluate(): the motion, and the rows of M and of
  // F - Q before the driven coordinates were eliminated.
  mutable Eigen::VectorXd drive_q_, drive_qd_, drive_qdd_;
  Eigen::MatrixXd drive_m_rows_;
  Eigen::VectorXd drive_bias_;
  Eigen::VectorXd q_motion_, qd_motion_;  // the state with the motion imposed
  // Beam forces that change with time (loads, springs), and their scratch.
  Eigen::VectorXd fc_extra_;
  std::vector<NodalForce> nodal_;
  std::vector<std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>> mc_factor_;
  // Workspace.
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> mb_row_;
  Eigen::MatrixXd mb_;
  Eigen::VectorXd fb_, qb_force_, rb_, rc_, ac0_, gc_, tmp_;
  Eigen::VectorXd joined_x_, joined_v_, joined_r_, joined_rk_;  // a joined structure's stacked q, q', modal forces
  Eigen::MatrixXd w_, h_;
  ConstraintValues cv_;
  // Workspace of solve_partitioned (sized on first use, no allocation after).
  Eigen::MatrixXd p_jv_, p_ju_, p_xju_, p_xh_, p_dir_, p_a_;
  Eigen::VectorXd p_d_, p_rhs_, p_base_, p_b_, p_x_, p_mu_;
  SmallLu p_jv_lu_, p_a_lu_;
  // Split coordinates (split_low_rank_beams): per beam its index in
  // split_beam_ or -1, M^-1 P and Phi_L^T P per split beam, the q_c and q_c'
  // with the DOFs the forces read made nodal, and the columns they read.
  std::vector<int> split_beam_, split_offset_, split_index_;
  std::vector<Eigen::VectorXd> split_minv_p_, split_phi_p_;
  int split_size_ = 0;
  Eigen::VectorXd split_acc_, split_qc_, split_qcd_, split_g_;
  Eigen::VectorXd split_delta_, split_delta_rate_;  // eta - zeta per split beam (m each, stacked), and its rate
  std::vector<int> split_read_;
  // M_c^-1 e_k of the beam DOFs that contacts have touched, per beam
  // (computed on first use: a slider visits a few elements, a pin one).
  std::vector<std::vector<Eigen::VectorXd>> minv_col_;
};

/// Names of the full coordinates [q_b; q_c]: rigid coordinate names, then
/// "<beam>_w<node>" / "<beam>_dw<node>" for the free beam DOFs.
std::vector<std::string> coupled_coordinate_names(const CoupledDynamics& dyn);

}  // namespace mbfe::runtime
