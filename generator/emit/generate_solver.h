// The generator's front door: a validated model in, C++ sources out.
// Deliberately free of GiNaC so that callers do not pay for its headers.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "model/model.h"

namespace mbfe::gen {

struct GeneratedFile {
  std::string name;  // e.g. "double_pendulum.cpp"
  std::string text;
};

struct GeneratedSolver {
  std::vector<GeneratedFile> files;                        // header first
  std::vector<std::pair<std::string, long>> operations;    // M, F, Q kernels, in emission order
  long fused_operations = 0;                               // the fused M+F+Q kernel
  long total_operations() const;
};

/// Version string written into every banner and cache key.
const char* generator_version();

/// Derives and emits the solver of `model` (which must have at least one
/// body). Deterministic: the same model gives byte-identical text.
GeneratedSolver generate_solver(const model::Model& model);

}  // namespace mbfe::gen
