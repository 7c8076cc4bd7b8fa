// The element of a finite-element beam, as a replaceable part.
//
// Assembly (beam_system.cpp) only asks an element for its matrices and its
// consistent load vector, so another planar element (an ANCF bending element,
// for one) can replace the Hermite element without touching the assembly.
// Contract: an element has two nodes; the first two DOFs of each node are
// [w, w'] (transverse displacement in m, slope dw/ds), in that order; supports
// fix those two.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "ir/model.h"

namespace mbfe::runtime {

class BeamElement {
 public:
  virtual ~BeamElement() = default;
  /// DOFs per node (2 for the Hermite element: [w, w']).
  virtual int node_dofs() const = 0;
  /// Element stiffness, (2 node_dofs) square, symmetric, in N/m, N, N m.
  virtual Eigen::MatrixXd stiffness() const = 0;
  /// Element mass, (2 node_dofs) square, symmetric positive definite, in kg, kg m, kg m^2.
  virtual Eigen::MatrixXd mass() const = 0;
  /// Consistent nodal loads of a uniform transverse load. @param q N/m.
  virtual Eigen::VectorXd uniform_load(double q) const = 0;
  /// A factor F of the stiffness, F^T F = stiffness() (r x 2 node_dofs),
  /// computed without forming the stiffness: its rows map nodal DOFs to
  /// scaled strain measures, so rigid motions give exactly zero. The sparse
  /// modal path factorises with it, because cond(K) of a long beam grows as
  /// ne^4 and exceeds 1/eps near 50,000 elements. An empty matrix means "none".
  virtual Eigen::MatrixXd stiffness_factor() const { return {}; }
};

/// The element the beam asks for (today: the Hermite Euler-Bernoulli element
/// with the beam's mass lumping). @throws std::invalid_argument if a property
/// of the beam is not positive (length, elements, area, inertia, E, density).
std::unique_ptr<BeamElement> make_beam_element(const ir::Beam& beam);

}  // namespace mbfe::runtime
