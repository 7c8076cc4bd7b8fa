#include "generator/symbolic/driven_motion.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "generator/symbolic/time_functions.h"
#include "ir/model_error.h"

namespace mbfe::gen {

namespace {

/// q'(t) and q''(t) of a motion q(t) = f. GiNaC may find a derivative
/// undefined where the motion is not (d/dt 0^t = 0^t log 0): an error at the motion.
std::pair<GiNaC::ex, GiNaC::ex> motion_derivatives(const ir::Expression& motion, const GiNaC::ex& f,
                                                   const GiNaC::symbol& t) {
  try {
    const GiNaC::ex df = f.diff(t);
    return {df, df.diff(t)};
  } catch (const std::domain_error& e) {  // GiNaC's pole_error
    const ir::ExpressionSource& s = motion.source();
    throw ir::ModelError(s.file, s.loc,
                         s.what + ": its derivative is undefined for every t (GiNaC: " + e.what() +
                             "); expected a motion differentiable twice in expression \"" + s.text + "\"");
  }
}

}  // namespace

Kernel derive_motion_kernel(const ir::Model& model, const GiNaC::symbol& t, CodeList& code, std::vector<int>& driven) {
  Kernel motion{"motion", "double t, double* q, double* qd, double* qdd",
                "Driven joints, in the order of kDrivenCoordinates: q(t), q'(t), q''(t).", {}, {}};
  driven.clear();
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const auto& m = model.bodies[i].joint.motion;
    if (!m) continue;
    const std::string k = std::to_string(driven.size());
    const GiNaC::ex f = to_ginac(*m, t);
    const auto [df, ddf] = motion_derivatives(*m, f, t);
    motion.outputs.push_back({"q[" + k + "]", code.define(f)});
    motion.outputs.push_back({"qd[" + k + "]", code.define(df)});
    motion.outputs.push_back({"qdd[" + k + "]", code.define(ddf)});
    driven.push_back(static_cast<int>(i));
  }
  if (!driven.empty()) motion.statements = code.closure(motion.outputs);
  return motion;
}

}  // namespace mbfe::gen
