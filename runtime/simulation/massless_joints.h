// Joints that move no mass: a free joint whose body and every body it carries
// have mass 0 and inertia 0 has a zero row and column in M, so its
// acceleration is not defined and no run or static start can begin.
#pragma once

#include <cstddef>
#include <string>

#include "ir/model.h"

namespace mbfe::runtime {

/// Whether `body` and every body it carries have no mass and no inertia.
bool carries_no_mass(const ir::Model& model, std::size_t body);

/// "'wheel' moves no mass: body 'wheel' and every body it carries have mass 0
/// and inertia 0, so its acceleration is not defined; give it a mass or
/// inertia, or drive its joint" (`coordinate` one of `body`'s).
std::string moves_no_mass(const ir::Model& model, const std::string& coordinate, std::size_t body);

/// Refuses a run from the given initial state of a coupled model (bodies and
/// beams) with such a joint, before its first step (which would divide by the
/// zero mass: NaN). Models without beams are left to the run, which names the
/// massless bodies when it meets the singular M(q); so are models with
/// constraint contacts (pin, slider_pin) or closed loops: a constraint may fix
/// what the mass does not.
/// @throws ir::ModelError at the body, "model '<name>': '<coordinate>' moves no mass: ...".
void refuse_massless_joints(const ir::Model& model);

}  // namespace mbfe::runtime
