// A link between two beams (ir::Link, docs/catenary.md: a catenary's
// dropper) as a force element: an axial spring and damper acting on the
// beams' transverse displacements,
//
//   e = g q - rest                      extension (m; structure/beam_links.h)
//   T = k e + c e'                      tension (N); a slack link: T = max(T, 0)
//   f = -T g                            nodal forces through the Hermite shape functions
//
// Tangent: k g g^T and c g g^T while taut, nothing while slack (exact away
// from the switch).
//
// A link inside a joined structure (docs/catenary.md, "The joined
// structure") has its spring's linear part k g g^T q in the structure's
// adjusted K already; as a force it adds only what departs from that:
// + k rest g - c e' g while taut (the damper acts in full), + k e_q g while
// slack (e_q = g q, the extension without the rest offset). Its tangent is
// then c g g^T while taut and -k g g^T while slack.
#pragma once

#include <string>

#include "runtime/coupled/force_element.h"
#include "runtime/structure/beam_links.h"

namespace mbfe::runtime {

/// One link at one state.
struct LinkState {
  double extension = 0.0;  // m
  double rate = 0.0;       // m/s
  double tension = 0.0;    // N (0 when slack)
  bool slack = false;      // a slack link with k e + c e' <= 0
};

class LinkForce final : public ForceElement {
 public:
  struct State final : ForceState {
    LinkState link;
  };

  /// `link` with its rest offset (the IR's `rest`, or the one form finding
  /// found for `hold`) and gradient g over q_c, in a model with nb rigid
  /// coordinates; `inside`: its spring is in a joined structure's K.
  LinkForce(const ir::Link& link, double rest, const LinkGradient& g, bool inside, int nb);

  const std::string& name() const override { return name_; }
  double stiffness() const { return k_; }  // N/m
  double damping() const { return c_; }    // N s/m
  double rest() const { return rest_; }    // m
  bool can_go_slack() const { return slack_; }
  bool inside_structure() const { return inside_; }
  const LinkGradient& gradient() const { return g_; }

  std::unique_ptr<ForceState> make_state() const override { return std::make_unique<State>(); }
  void add_force(const ForceArgs& x, ForceState& state, ForceSink& out) const override;
  void add_tangent(const ForceArgs& x, const ForceState& state, double c_q, double c_v,
                   TangentSink& out) const override;
  void beam_dofs_read(const double* qb, std::vector<int>& out) const override;

 private:
  std::string name_;
  double k_, c_, rest_;
  bool slack_, inside_;
  LinkGradient g_;
  int nb_;  // where q_c starts in [q_b; q_c]
};

}  // namespace mbfe::runtime
