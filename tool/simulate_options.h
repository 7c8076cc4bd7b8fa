// What `mbfe simulate` was asked to do, after flags override the model's
// `simulation:` block. Shared by the rigid, beam and coupled drivers.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ir/model.h"

namespace mbfe::tool {

struct SimulateOptions {
  std::string integrator;              // e.g. "rk4", "forward_euler"
  double step = 0.0;                   // s
  double t_end = 0.0;                  // s
  std::optional<std::string> out;      // CSV path; stdout when absent
  bool quiet = false;                  // no progress on stderr
  std::optional<bool> adjust;          // --adjust on|off; absent = model decides
  std::vector<std::string> probes;     // --probe beam1@0.5 (beam models)
  std::optional<double> rho_inf;       // generalized-alpha spectral radius
  long long every = 0;                 // write every N-th step; 0 = automatic
};

/// Beam-only models (no bodies). Returns the exit status (0, 2 or 3).
int simulate_beams(const ir::Model& model, const SimulateOptions& options);

}  // namespace mbfe::tool
