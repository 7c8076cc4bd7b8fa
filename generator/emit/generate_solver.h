// The generator's front door: a validated model in, C++ sources out.
// Deliberately free of GiNaC so that callers do not pay for its headers.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "ir/model.h"

namespace mbfe::gen {

struct GeneratedFile {
  std::string name;  // e.g. "double_pendulum.cpp"
  std::string text;
};

/// Arithmetic operations of one kernel (+ - * / and math calls on doubles; a
/// unary minus is free, loop and index arithmetic are not counted).
struct KernelOperations {
  std::string kernel;
  long emitted = 0;   // written in the source: a loop body counts once
  long executed = 0;  // performed per call: a loop body counts once per pass
};

struct GeneratedSolver {
  std::vector<GeneratedFile> files;          // header first
  std::vector<KernelOperations> operations;  // M, F, Q, then contact kernels, in emission order
  KernelOperations fused;                    // the fused M+F+Q kernel (not in the totals)
  /// M's assembly loop (composite-rigid-body algorithm): passes per call (one
  /// per (ancestor, descendant) pair of bodies, N(N+1)/2 for a chain) and
  /// operations per pass. mass_matrix and dynamics both run it.
  long assembly_pairs = 0;
  long assembly_operations_per_pass = 0;
  long total_emitted() const;
  long total_executed() const;
};

/// Version string written into every banner and cache key.
const char* generator_version();

/// Derives and emits the solver of `model` (which must have at least one
/// body). Deterministic: the same model gives byte-identical text.
GeneratedSolver generate_solver(const ir::Model& model);

}  // namespace mbfe::gen
