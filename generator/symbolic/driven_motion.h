// The motion kernel of driven joints (`motion:`): q, q' and q'' of each
// driven coordinate at time t, differentiated in closed form.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "generator/symbolic/code_list.h"
#include "ir/model.h"

namespace mbfe::gen {

/// `motion(t, q, qd, qdd)`, one output of each per driven body in model
/// order, and the indices of those bodies in `driven` (empty: no kernel).
/// Intermediates go into `code`; the kernel's statements are filled.
Kernel derive_motion_kernel(const ir::Model& model, const GiNaC::symbol& t, CodeList& code, std::vector<int>& driven);

}  // namespace mbfe::gen
