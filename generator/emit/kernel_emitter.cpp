#include "generator/emit/kernel_emitter.h"

#include <sstream>

namespace mbfe::gen {

namespace {

bool declares(const std::string& signature, const std::string& param) {
  for (const std::string& decl : {"const double* " + param + ",", "const double* " + param + ")",
                                  "double " + param + ",", "double " + param + ")"})
    if (signature.find(decl) != std::string::npos) return true;
  return false;
}

}  // namespace

std::string count_of(long n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

namespace {

// The assembly loop of the composite-rigid-body algorithm (see
// AncestorPairAssembly): a loop rather than one statement per entry, so the
// emitted code stays O(N) while M has N(N+1)/2 entries.
std::string emit_assembly(const AncestorPairAssembly& a) {
  std::ostringstream out;
  const std::string& n = a.size_name;
  out << "  // Composite-rigid-body algorithm (CRBA), assembly: " << a.target << "_jk = " << a.target
      << "_kj = S_j . U_k for every j on the\n"
      << "  // path from k to the ground. A loop, not one statement per entry, keeps the code O(N); "
      << count_of(a.pairs(), "pass", "passes") << ".\n";
  if (a.has_unrelated_pairs())
    out << "  for (int i = 0; i < " << n << " * " << n << "; ++i) " << a.target
        << "[i] = 0.0;  // bodies on different branches\n";
  // In an unbranched chain the parent of j is j - 1: a plain countdown, which
  // the compiler unrolls, instead of a table lookup per step (measured 18 %
  // faster for M of the 20-link chain).
  out << "  for (int k = 0; k < " << n << "; ++k) {\n"
      << "    const double* U = " << a.right << "[k];\n"
      << "    for (int j = k; j >= 0; "
      << (a.is_chain() ? std::string("--j) {  // an unbranched chain: the parent of j is j - 1")
                       : "j = " + std::string(kParentTable) + "[j]) {")
      << "\n"
      << "      const double* S = " << a.left << "[j];\n"
      << "      const double m_jk = ";
  for (int c = 0; c < a.width; ++c) out << (c ? " + " : "") << "S[" << c << "]*U[" << c << "]";
  out << ";\n"
      << "      " << a.target << "[j*" << n << " + k] = m_jk;\n"
      << "      " << a.target << "[k*" << n << " + j] = m_jk;\n"
      << "    }\n  }\n";
  return out.str();
}

}  // namespace

EmittedKernel emit_kernel(const Kernel& kernel, const SymbolNames& inputs, const KernelParams& params,
                          const std::string& storage) {
  SymbolNames names = inputs;
  std::ostringstream body;
  long ops = 0;
  int next = 0;
  CppPrinter printer(names);
  for (const Assignment& s : kernel.statements) {
    const std::string name = "t" + std::to_string(next++);
    body << "  const double " << name << " = " << printer.print(s.rhs) << ";\n";
    ops += CppPrinter::count_operations(s.rhs);
    names.emplace(s.lhs, name);
  }
  for (const KernelOutput& o : kernel.outputs) {
    body << "  " << o.target << " = " << printer.print(o.value) << ";\n";
    ops += CppPrinter::count_operations(o.value);
  }
  EmittedKernel result;
  result.emitted = result.executed = ops;
  std::ostringstream text;
  text << "// " << kernel.doc << " ";
  if (kernel.assembly) {
    const AncestorPairAssembly& a = *kernel.assembly;
    result.emitted = ops + a.operations_per_pass();
    result.executed = ops + a.operations_per_pass() * a.pairs();
    text << result.emitted << " operations emitted (" << ops << " straight-line + " << a.operations_per_pass()
         << " in the\n// assembly loop, which makes " << count_of(a.pairs(), "pass", "passes") << "): "
         << result.executed << " per call.\n";
  } else {
    text << ops << " operations.\n";
  }
  text << storage << "void " << kernel.name << "(" << kernel.signature << ") {\n";
  // Parameters a kernel never reads (no springs: no qd; no time-dependent loads: no t).
  for (const KernelParam& param : params) {
    if (!declares(kernel.signature, param.name)) continue;
    bool used = false;
    for (const auto& sym : param.symbols) {
      for (const Assignment& s : kernel.statements) used = used || s.rhs.has(sym);
      for (const KernelOutput& o : kernel.outputs) used = used || o.value.has(sym);
    }
    if (!used) text << "  (void)" << param.name << ";\n";
  }
  if (kernel.assembly) {
    const AncestorPairAssembly& a = *kernel.assembly;
    text << "  double " << a.left << "[" << a.size_name << "][" << a.width << "];  // " << a.left_doc << "\n"
         << "  double " << a.right << "[" << a.size_name << "][" << a.width << "];  // " << a.right_doc << "\n";
  }
  text << body.str();
  if (kernel.assembly) text << emit_assembly(*kernel.assembly);
  text << "}\n";
  result.text = text.str();
  return result;
}

}  // namespace mbfe::gen
