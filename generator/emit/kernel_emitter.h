// One kernel (a straight-line program of GiNaC expressions, plus the
// assembly loop of M) printed as a C++ function, with its operation counts.
#pragma once

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "generator/emit/cpp_printer.h"
#include "generator/symbolic/code_list.h"

namespace mbfe::gen {

struct EmittedKernel {
  std::string text;
  long emitted = 0;   // operations written: straight-line code + one pass of a loop body
  long executed = 0;  // operations per call: straight-line code + every pass
};

// An input parameter of the kernels: its C++ name and the symbols it carries.
struct KernelParam {
  std::string name;
  std::vector<GiNaC::ex> symbols;
};
using KernelParams = std::vector<KernelParam>;

/// Name of the parent table the assembly loop of a branched tree reads.
constexpr const char* kParentTable = "kParent";

/// "1 pass" / "3 passes".
std::string count_of(long n, const char* one, const char* many);

/// Prints `kernel` as a C++ function; temporaries are renumbered t0, t1, ...
/// in the order they are defined. `inputs` names the input symbols (q[0],
/// ...), `params` says which parameter carries which symbols (a parameter the
/// kernel never reads is marked (void)), `storage` prefixes the function
/// ("static " or "").
EmittedKernel emit_kernel(const Kernel& kernel, const SymbolNames& inputs, const KernelParams& params,
                          const std::string& storage);

}  // namespace mbfe::gen
