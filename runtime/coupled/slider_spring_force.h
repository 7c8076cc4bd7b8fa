// A slider_spring contact (docs/contacts.md) as a force element: a penalty
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
// Law hertz (a wheel on a rail, docs/contacts.md): N = C_H delta^1.5 +
// c delta' while delta > 0, and N = 0 when delta <= 0 whatever `unilateral`
// says (a Hertzian contact has no tension branch); C_H in N/m^1.5 comes from
// the model (the generated kernels carry the linear stiffness only).
//
// Unilateral: N = 0 when delta <= 0 (apart) or k delta + c delta' < 0 (the
// damper would pull): the contact never pulls. Off the beam (s outside
// [0, L]) the contact is inactive: vehicles drive on and off.
//
// Tangent: k g g^T and c g g^T while it presses, g = d delta / dq; Hertz's
// k is dN/d delta = 1.5 C_H delta^0.5, in closed form. The change
// of g itself is left out, N dg/dq and the damper's c (dg/dq) q' (g's rigid
// part holds the beam's slope under the point, so a point moving along the
// beam makes delta' depend on q_c): a Newton matrix, not an exact Jacobian.
// It is exact along q' everywhere, and along q_c in the beam's rows when the
// bodies are at rest.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"
#include "runtime/coupled/force_element.h"
#include "runtime/structure/beam_mesh.h"

namespace mbfe::runtime {

/// The force law of a slider_spring (ir::ContactLaw): the linear law takes
/// the generated kernels' stiffness; Hertz's takes its coefficient here.
struct SpringLaw {
  bool hertz = false;
  double coefficient = 0.0;  // N/m^1.5 (hertz)
};

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
/// columns, -1 for a DOF fixed by a support).
struct SpringGradient {
  std::vector<double> jb;
  double je[4] = {0, 0, 0, 0};
  int cols[4] = {-1, -1, -1, -1};
  bool pressing = false;  // on the beam and N > 0 (or bilateral)
};

class SliderSpringForce final : public ForceElement {
 public:
  struct State final : ForceState {
    SpringContactState contact;
    SpringGradient gradient;
    mutable std::vector<std::pair<int, double>> entries;  // add_tangent's scratch
  };

  /// Contact `index` of `model` (type 2), on the beam `mesh` whose free DOFs
  /// start at `offset` in q_c, with force law `law`. @throws
  /// std::invalid_argument if it is not a slider_spring, or a Hertz law has a
  /// coefficient that is not positive.
  SliderSpringForce(const mbfe_model_v1& model, int index, BeamMesh mesh, int offset, SpringLaw law = {});

  const std::string& name() const override { return name_; }
  /// Model contact index.
  int contact() const { return index_; }
  double stiffness() const { return kernels_.stiffness; }  // N/m (linear law)
  const SpringLaw& law() const { return law_; }
  /// N(delta, delta') of its law, compression positive, before the
  /// unilateral clip (N); and dN/d delta (N/m) at delta.
  double law_force(double delta, double rate) const;
  double law_stiffness(double delta) const;
  double damping() const { return kernels_.damping; }      // N s/m
  /// The running surface's offset from the beam's deflection at s (m, along
  /// +w: profile minus camber; 0 on a beam without either), and the side the
  /// point presses from (+1 a wheel on a deck, -1 `side: below`): delta
  /// without the offset is delta - side() * surface_offset(s).
  double surface_offset(double s) const;
  double side() const { return kernels_.from_below ? -1.0 : 1.0; }

  std::unique_ptr<ForceState> make_state() const override;
  void add_force(const ForceArgs& x, ForceState& state, ForceSink& out) const override;
  void add_tangent(const ForceArgs& x, const ForceState& state, double c_q, double c_v,
                   TangentSink& out) const override;
  void beam_dofs_read(const double* qb, std::vector<int>& out) const override;

 private:
  const mbfe_contact_kernels_v1& kernels_;
  int index_, nb_, offset_;
  BeamMesh mesh_;
  SpringLaw law_;
  std::string name_;
};

}  // namespace mbfe::runtime
