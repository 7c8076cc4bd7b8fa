// Closed-form contact constraints between a body vertex and a beam
// (Section 4 of the paper, eqs (12)-(13)), with their Jacobians and the
// velocity-product term of their second derivative.
//
// Beam frame: origin at the beam's `origin`, x along its axis, y transverse.
// (x_P, y_P)(q): the vertex in that frame. On the element [s0, s0 + le] that
// holds s, w(s) = N((s - s0)/le) . qe with the Hermite cubics N and the
// element's DOFs qe = [w1, w1', w2, w2'].
//   pin at `at`:  Phi = [at - x_P(q);  w(at) - y_P(q)]
//   slider_pin:   Phi = w(s(q)) - y_P(q),  s(q) = x_P(q)
// J_b = dPhi/dq and J_e = dPhi/dqe are differentiated symbolically, so for a
// slider J_b carries dN/ds * ds/dq; gamma = -(dJ/dt) [q'; qe'] collects every
// velocity-quadratic term, including those of s'(q, q') (N_ss s'^2, 2 N_s s' qe').
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "ir/model.h"
#include "generator/symbolic/code_list.h"

namespace mbfe::gen {

struct ContactKernels {
  std::string name;  // the contact's name
  int type = 0;      // 0 pin, 1 slider_pin (as the ABI)
  int beam = -1;
  double at = 0.0;
  int rows = 0;
  Kernel position, phi, jacobians, gamma;
};

/// Symbols shared by every contact kernel.
struct ContactSymbols {
  std::vector<GiNaC::symbol> q, qd;  // rigid coordinates (the same objects as the rigid derivation)
  std::vector<GiNaC::symbol> qe, qed;  // 4 element DOFs and their rates
  GiNaC::symbol s0{"s0"}, le{"le"};
};

/// Derives the kernels of every contact of `model`. Intermediates go into `code`.
std::vector<ContactKernels> derive_contacts(const ir::Model& model, const ContactSymbols& symbols,
                                            CodeList& code);

}  // namespace mbfe::gen
