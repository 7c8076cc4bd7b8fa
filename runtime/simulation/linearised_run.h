// The linearised moving-contact run: the numerics of the accuracy estimate of
// an adjusted run (docs/damping-adjustment.md, "The accuracy estimate").
//
// The beams in modal coordinates with all their modes, each mode on its own,
//
//   m_j eta_j'' + c_j eta_j' + k_j eta_j = phi_j^T f_c(t) - phi_j^T sum_e g_e F_e,
//
// the bodies linear about a reference motion (y: the free rigid coordinates
// less the reference's),
//
//   M_r y'' + C_r y' + K_r y = f_r(t) - sum_e r_e F_e,
//
// and a few scalar force elements between them: contacts that move along
// their beam (their DOFs and weights change with t), links and dashpots on
// fixed DOFs. An element's elongation (a contact's compression, a link's
// extension) is x_e = offset_e + g_e^T q_c + r_e^T y with q_c = Phi eta, and
// its force F_e = law(x_e) + c_e x_e', zero where the law says so (a contact
// apart, a slack link). Newmark's average-acceleration rule steps every mode
// and the bodies; the forces of one step are the unknowns of a small system
// (bodies and elements), solved by Newton over the laws' pieces, so a step
// costs a few passes over the modes for each DOF the elements touch.
//
// A mode may be quasi-static (its mass and damping left out: eta_j =
// p_j / k_j each step), the treatment of modes far above what the step
// resolves, or absent (a mode policy truncate removed: eta_j = 0). Everything
// that depends on time and on the bodies' kernels (where each contact is, the
// loads) is given on the step grid beforehand (LinearisedExcitation), so one
// excitation serves several runs (original and adjusted modes, the limits a
// search tries) and a run touches no shared state.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace mbfe::runtime {

/// A force law F(x, x') of one element, x its elongation (m): positive F
/// (N) pushes x back (a compressed contact, a stretched link).
struct ElementLaw {
  double stiffness = 0.0;         // N/m: F = stiffness x (when hertz is 0)
  double hertz = 0.0;             // N/m^1.5: F = hertz x^1.5 for x > 0, no spring for x <= 0
  double damping = 0.0;           // N s/m: + damping x'
  bool compression_only = false;  // F = 0 for x <= 0 (a unilateral contact apart)
  bool no_pull = false;           // F = 0 when the law gives F < 0 (a unilateral contact, a slack link)
};

/// One element on fixed beam DOFs (a link, a dashpot of the discrete parts).
struct FixedElement {
  std::string name;
  std::vector<std::pair<int, double>> dofs;  // (q_c index, weight): x = offset + sum weight q_c[index]
  double offset = 0.0;                       // m
  ElementLaw law;
};

/// Where a moving contact acts at one time.
struct ContactGeometry {
  bool active = false;             // on its beam
  int dofs[4] = {-1, -1, -1, -1};  // q_c indices of the element under the point (-1: none)
  double weights[4] = {0, 0, 0, 0};
  double offset = 0.0;  // m: x at q_c = 0 and y = 0
};

/// A linear structure (every beam's modes) and linear bodies, without the
/// dynamics of the modes (ModalDynamicsSet holds those).
struct LinearisedStructure {
  /// One beam: its modes Phi (n_b x m_b, mass-normalised; held, not copied:
  /// it must outlive the structure), where its DOFs start in q_c and where
  /// its modes start in the modal vector.
  struct Block {
    const Eigen::MatrixXd* phi = nullptr;
    int dof_offset = 0;
    int mode_offset = 0;
  };
  std::vector<Block> blocks;
  int modes = 0;                             // n_s, every block's modes
  int dofs = 0;                              // n_c
  Eigen::MatrixXd mass, damping, stiffness;  // n_r x n_r: the bodies' M_r, C_r, K_r (kg, N s/m, N/m by coordinate)
  std::vector<FixedElement> fixed;
  std::vector<std::string> contact_names;
  std::vector<ElementLaw> contact_laws;
};

/// The time-dependent inputs of a run on the grid t_k = k step, k = 0..steps.
struct LinearisedExcitation {
  double step = 0.0;  // s
  int steps = 0;
  Eigen::VectorXd constant_load;  // n_c: the beams' constant loads P (N)
  /// [k * contacts + i]: contact i at t_k.
  std::vector<ContactGeometry> geometry;
  /// n_r x contacts per step, stacked: column k * contacts + i is r_i at t_k
  /// (dx_i / dy, m per unit of each rigid coordinate).
  Eigen::MatrixXd rigid_gradients;
  Eigen::MatrixXd rigid_loads;  // n_r x (steps + 1): f_r(t_k)
  /// The beams' loads beyond P at t_k, (q_c index, N), one list per step
  /// (empty when there are none).
  std::vector<std::vector<std::pair<int, double>>> timed_loads;
};

/// The modes' dynamics of one model.
struct ModalDynamicsSet {
  Eigen::VectorXd m, c, k;  // n_s: modal mass (1), damping (1/s), stiffness (1/s^2)
  /// Per mode: 0 dynamic, 1 quasi-static, 2 absent.
  std::vector<unsigned char> kind;
  static constexpr unsigned char kDynamic = 0, kQuasiStatic = 1, kAbsent = 2;
};

/// Where a run starts: at its own static equilibrium under the loads at t =
/// 0, or at a given state (modal coordinates and rigid deviations).
struct LinearisedStart {
  bool static_start = true;
  Eigen::VectorXd eta, eta_dot;  // n_s (given start)
  Eigen::VectorXd y, y_dot;      // n_r (given start)
};

/// What a run gives: each contact's force (N, compression positive) and
/// compression (m) at every t_k.
struct LinearisedHistory {
  std::vector<std::vector<double>> force, compression;  // [contact][k]
  int unconverged_steps = 0;  // steps whose element forces did not settle within the Newton iterations
};

/// Runs the structure with the modes `modes` from `start` over the grid of
/// `excitation`. @throws std::invalid_argument when sizes do not fit;
/// std::runtime_error when the static equilibrium or a step's system is
/// singular (a body held by nothing: no contact on a beam at t = 0).
LinearisedHistory run_linearised(const LinearisedStructure& structure, const ModalDynamicsSet& modes,
                                 const LinearisedExcitation& excitation, const LinearisedStart& start);

}  // namespace mbfe::runtime
