// The slider_spring contacts of a coupled model (docs/contacts.md): a penalty
// force between a body point and a beam instead of a constraint,
//
//   delta = w(s) - y_P            penetration of the point into the beam (m)
//   N     = k delta + c delta'    contact force, positive in compression (N)
//
// with s(q_b) and w(s) the same closed-form kernels as a slider_pin's
// (delta is that kernel's Phi, its Jacobians dPhi/dq_b and dPhi/dq_e). The
// force enters both sides as generalized forces, the gradient of the penalty
// energy with N in place of k delta:
//
//   Q_b += -(d delta / d q_b)^T N,   P_c += -(d delta / d q_c)^T N.
//
// A contact pressed from the +w side (`side: below`, a pantograph under a
// contact wire) uses delta = y_P - w(s) and the opposite gradient.
//
// Unilateral: N = 0 when delta <= 0 (apart) or k delta + c delta' < 0 (the
// damper would pull): the contact never pulls. Off the beam (s outside
// [0, L]) the contact is inactive: vehicles drive on and off.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/coupled/contact_constraints.h"

namespace mbfe::runtime {

/// One spring contact at one state.
struct SpringContactState {
  double s = 0.0;       // m along the beam
  bool on_beam = false; // s in [0, L]
  double delta = 0.0;   // m, penetration (0 off the beam)
  double rate = 0.0;    // m/s, delta'
  double force = 0.0;   // N, compression positive (0 off the beam or lifted off)
  double w = 0.0;       // m, the beam's deflection under the point (0 off the beam)
};

/// The gradient g = d delta / dq of one spring at its last evaluation: the
/// rigid part and the 4 beam DOFs of the element under the point (global q_c
/// columns, -1 for a DOF fixed by a support). The spring's generalized force
/// is -g N, so its tangent stiffness is k g g^T and its damping c g g^T while
/// it presses (the change of g itself is left out: a Newton matrix, not an
/// exact Jacobian).
struct SpringGradient {
  std::vector<double> jb;
  double je[4] = {0, 0, 0, 0};
  int cols[4] = {-1, -1, -1, -1};
  bool pressing = false;  // on the beam and N > 0 (or bilateral)
};

class ContactSprings {
 public:
  /// The model's slider_spring contacts (type 2), on `beams` numbered as in
  /// ContactConstraints (beam offsets in q_c).
  ContactSprings(const mbfe_model_v1& model, const ContactConstraints& constraints);

  int count() const { return static_cast<int>(contacts_.size()); }
  /// Model contact index of spring k.
  int contact(int k) const { return contacts_[k]; }
  std::string name(int k) const;

  /// Evaluates every spring at (q_b, q_c) with rates and adds its generalized
  /// forces to q_force (nb entries, the rigid Q) and beam_force (nc entries).
  void apply(const double* qb, const double* qc, const double* qbd, const double* qcd,
             Eigen::Ref<Eigen::VectorXd> q_force, Eigen::Ref<Eigen::VectorXd> beam_force);
  /// Appends the q_c columns apply() reads at q_b: the free DOFs of the
  /// element under each spring that is on its beam.
  void columns_read(const double* qb, std::vector<int>& out) const;
  /// The states of the last apply().
  const std::vector<SpringContactState>& states() const { return states_; }
  /// The gradients of the last apply().
  const SpringGradient& gradient(int k) const { return gradients_[k]; }
  /// Stiffness and damping of spring k (N/m, N s/m).
  double stiffness(int k) const { return model_.contacts[contacts_[k]].stiffness; }
  double damping(int k) const { return model_.contacts[contacts_[k]].damping; }

 private:
  const mbfe_model_v1& model_;
  const ContactConstraints& cc_;
  std::vector<int> contacts_;
  std::vector<SpringContactState> states_;
  std::vector<SpringGradient> gradients_;
};

/// Lift-offs and time off contact of the spring contacts over a run, counted
/// on accepted steps while the contact point is over its beam. In contact
/// means delta > 0 (a unilateral damper may still hold N at 0 there for a
/// moment as the surfaces part; that is not a lift-off).
struct SpringContactTally {
  std::string name;
  int lift_offs = 0;        // transitions from delta > 0 to delta <= 0
  double time_off = 0.0;    // s with delta <= 0 while over the beam
  bool in_contact = false;  // at the last accepted step
  bool seen = false;
};

}  // namespace mbfe::runtime
