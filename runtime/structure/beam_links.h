// The links of a coupled model (ir::Link, docs/catenary.md): axial springs and
// dampers between points of two parallel beams, acting on their transverse
// displacements, as forces on the beams (a catenary's droppers).
//
//   e = w_b(s_b) - w_a(s_a) - rest      extension (m)
//   T = k e + c e'                      tension (N); a slack link: T = max(T, 0)
//   f_a = +T N_a^T,  f_b = -T N_b^T     nodal forces through the Hermite shape functions
//
// With g = de/dq (-N_a on a's element, +N_b on b's), f = -T g: the tangent
// stiffness is k g g^T and the damping c g g^T while the link is taut.
//
// A link inside a joined structure (docs/catenary.md, "The joined
// structure") has its spring's linear part k g g^T q in the structure's
// adjusted K already; as a force it adds only what departs from that:
// + k rest g - c e' g while taut (the damper acts in full), + k e_q g while
// slack (e_q = g q, the extension without the rest offset).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/structure/beam_mesh.h"

namespace mbfe::runtime {

/// One link at one state.
struct LinkState {
  double extension = 0.0;  // m
  double rate = 0.0;       // m/s
  double tension = 0.0;    // N (0 when slack)
  bool slack = false;      // a slack link with k e + c e' <= 0
};

class BeamLinks {
 public:
  /// `links` of the model, on the beams `meshes` whose free DOFs start at
  /// `offsets` in q_c. rest is the IR's; form finding sets it with set_rest().
  BeamLinks(const std::vector<ir::Link>& links, const std::vector<BeamMesh>& meshes, const std::vector<int>& offsets);

  int count() const { return static_cast<int>(ends_.size()); }
  const std::string& name(int k) const { return ends_[k].name; }
  double stiffness(int k) const { return ends_[k].k; }
  double damping(int k) const { return ends_[k].c; }
  bool can_go_slack(int k) const { return ends_[k].slack; }
  double rest(int k) const { return ends_[k].rest; }
  void set_rest(int k, double rest) { ends_[k].rest = rest; }
  /// Link k's spring is in a joined structure's K (see above).
  bool inside_structure(int k) const { return ends_[k].inside; }
  void set_inside_structure(int k, bool inside) { ends_[k].inside = inside; }

  /// Adds every link's forces to beam_force (nc entries) at (q_c, q_c').
  void apply(const double* qc, const double* qcd, Eigen::Ref<Eigen::VectorXd> beam_force);
  const std::vector<LinkState>& states() const { return states_; }

  /// g = de/dq_c of link k: up to 8 entries (q_c index, value).
  struct Gradient {
    int cols[8];
    double values[8];
    int size = 0;
  };
  const Gradient& gradient(int k) const { return ends_[k].g; }

 private:
  struct End {
    std::string name;
    double k = 0.0, c = 0.0, rest = 0.0;
    bool slack = false;
    bool inside = false;
    Gradient g;  // constant: the ends do not move along their beams
  };
  std::vector<End> ends_;
  std::vector<LinkState> states_;
};

/// g = de/dq of `link` on the beams `meshes`, whose free DOFs start at
/// `offsets` in the vector g indexes (q_c, or a joined structure's coordinates).
BeamLinks::Gradient link_gradient(const ir::Link& link, const std::vector<BeamMesh>& meshes,
                                  const std::vector<int>& offsets);

/// Slack events and time slack of the links over a run, counted on accepted
/// steps (like SpringContactTally for contacts).
struct LinkSlackTally {
  std::string name;
  int slackenings = 0;   // transitions from taut to slack
  double time_slack = 0.0;  // s
  bool slack = false;    // at the last accepted step
  bool seen = false;     // a step has been counted (a link slack from the start has not slackened)
};

}  // namespace mbfe::runtime
