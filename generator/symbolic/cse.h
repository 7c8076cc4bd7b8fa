// Common-subexpression elimination over one kernel.
//
// GiNaC has no CSE of its own; this pass counts every compound subexpression
// of the kernel's statements and outputs in a hash map keyed by GiNaC's
// structural hash and equality, and hoists those met more than once into new
// named temporaries, placed just before their first use. Operands are visited
// in a structural order, so the result does not depend on memory addresses.
#pragma once

#include "generator/symbolic/code_list.h"

namespace mbfe::gen {

/// Rewrites `kernel` in place. Returns how many temporaries were added.
int eliminate_common_subexpressions(Kernel& kernel);

}  // namespace mbfe::gen
