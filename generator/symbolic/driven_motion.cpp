#include "generator/symbolic/driven_motion.h"

#include <string>

#include "generator/symbolic/time_functions.h"

namespace mbfe::gen {

Kernel derive_motion_kernel(const ir::Model& model, const GiNaC::symbol& t, CodeList& code, std::vector<int>& driven) {
  Kernel motion{"motion", "double t, double* q, double* qd, double* qdd",
                "Driven joints, in the order of kDrivenCoordinates: q(t), q'(t), q''(t).", {}, {}};
  driven.clear();
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const auto& m = model.bodies[i].joint.motion;
    if (!m) continue;
    const std::string k = std::to_string(driven.size());
    const GiNaC::ex f = to_ginac(*m, t);
    const GiNaC::ex df = f.diff(t);
    motion.outputs.push_back({"q[" + k + "]", code.define(f)});
    motion.outputs.push_back({"qd[" + k + "]", code.define(df)});
    motion.outputs.push_back({"qdd[" + k + "]", code.define(df.diff(t))});
    driven.push_back(static_cast<int>(i));
  }
  if (!driven.empty()) motion.statements = code.closure(motion.outputs);
  return motion;
}

}  // namespace mbfe::gen
