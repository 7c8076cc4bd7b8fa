// What acts on a coupled model beside the bodies' own dynamics (the generated
// kernels) and the beams' own (their M, C, K or adjusted structure): forces
// between bodies and beams, between beams, and loads. Each element gives its
// generalized force at a state, its tangent for the Newton matrix and the
// beam coordinates it reads; the explicit evaluation, the implicit residual
// and the Newton matrix all go over one list of them (coupled_model.h). Adding
// a kind of force is one new element and one line where the model's list is
// built (docs/architecture.md, "Adding a force element").
//
// Constraint contacts (pin, slider_pin) are not elements: they are equations
// Phi = 0 with multipliers, eliminated by the explicit formulations and
// bordering the implicit system's matrix (contact_constraints.h). Driven
// joints replace equations rather than add to them (driven_coordinates.h).
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

namespace mbfe::runtime {

/// The state an element is evaluated at: the rigid coordinates and rates
/// (nb entries, driven ones following their motion) and the beam coordinates
/// and rates (nc entries, nodal at least where the element reads them).
struct ForceArgs {
  double t = 0.0;  // s
  const double* qb = nullptr;
  const double* vb = nullptr;
  const double* qc = nullptr;
  const double* vc = nullptr;
};

/// Where generalized forces go (N or N m): the rigid part f_b (nb) and the
/// beams f_c (nc), both added to.
struct ForceSink {
  double* fb = nullptr;
  double* fc = nullptr;
};

/// Entries of a Newton matrix over [q_b; q_c] (row, column, value), summed
/// where repeated. Rows listed in `skip` (driven coordinates, whose equation
/// is their motion's) take nothing.
class TangentSink {
 public:
  TangentSink(std::vector<Eigen::Triplet<double>>& out, const std::vector<bool>* skip = nullptr)
      : out_(out), skip_(skip) {}
  void add(int row, int col, double value) {
    if (value == 0.0 || (skip_ != nullptr && row < static_cast<int>(skip_->size()) && (*skip_)[row])) return;
    out_.emplace_back(row, col, value);
  }

 private:
  std::vector<Eigen::Triplet<double>>& out_;
  const std::vector<bool>* skip_;
};

/// What an element found at its last evaluation (outputs and tallies read
/// it), and its scratch: one per element and run.
class ForceState {
 public:
  virtual ~ForceState() = default;
};

class ForceElement {
 public:
  virtual ~ForceElement() = default;

  /// Its name in messages and output columns: the contact's or link's name.
  virtual const std::string& name() const = 0;
  /// A fresh state for one run (or thread).
  virtual std::unique_ptr<ForceState> make_state() const = 0;
  /// Adds its generalized force at `x` to `out` and remembers what it found
  /// in `state`.
  virtual void add_force(const ForceArgs& x, ForceState& state, ForceSink& out) const = 0;
  /// Adds c_q (-df/dq) + c_v (-df/dv) at the state of its last add_force,
  /// over [q_b; q_c]; what an element leaves out of its exact Jacobian is said
  /// in its own header.
  virtual void add_tangent(const ForceArgs& x, const ForceState& state, double c_q, double c_v,
                           TangentSink& out) const = 0;
  /// Appends the q_c indices add_force reads at the rigid coordinates qb.
  virtual void beam_dofs_read(const double* qb, std::vector<int>& out) const = 0;
};

}  // namespace mbfe::runtime
