#include "generator/emit/generate_solver.h"

#include <sstream>
#include <stdexcept>

#include "generator/emit/cpp_printer.h"
#include "ir/model_error.h"
#include "generator/symbolic/contact_kinematics.h"
#include "generator/symbolic/cse.h"
#include "generator/symbolic/rigid_dynamics.h"

namespace mbfe::gen {

namespace {

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

bool declares(const std::string& signature, const std::string& param) {
  for (const std::string& decl : {"const double* " + param + ",", "const double* " + param + ")",
                                  "double " + param + ",", "double " + param + ")"})
    if (signature.find(decl) != std::string::npos) return true;
  return false;
}

constexpr const char* kParentTable = "kParent";

std::string count_of(long n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// The assembly loop of the composite-rigid-body algorithm (see
// AncestorPairAssembly): a loop rather than one statement per entry, so the
// emitted code stays O(N) while M has N(N+1)/2 entries.
std::string emit_assembly(const AncestorPairAssembly& a) {
  std::ostringstream out;
  const std::string n = "kNumCoordinates";
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

// Prints one kernel as a C++ function; temporaries are renumbered t0, t1, ...
// in the order they are defined.
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
    text << "  double " << a.left << "[kNumCoordinates][" << a.width << "];  // " << a.left_doc << "\n"
         << "  double " << a.right << "[kNumCoordinates][" << a.width << "];  // " << a.right_doc << "\n";
  }
  text << body.str();
  if (kernel.assembly) text << emit_assembly(*kernel.assembly);
  text << "}\n";
  result.text = text.str();
  return result;
}

std::string banner(const ir::Model& model, const std::string& file, const GeneratedSolver& solver) {
  std::ostringstream b;
  b << "// " << file << ": generated by mbfe " << generator_version() << " from model '" << model.name
    << "'.\n"
    << "// Model file sha256: " << model.source_sha256 << "\n"
    << "// Generated, do not edit. Regenerate with: mbfe generate <model file> -o <folder>\n";
  if (!solver.operations.empty()) {
    // Emitted, and executed per call where a loop makes the two differ.
    auto count = [](long emitted, long executed) {
      return std::to_string(emitted) + (executed != emitted ? " (" + std::to_string(executed) + " per call)" : "");
    };
    b << "// Operations per kernel (+ - * / and calls) as emitted, and executed per call where a loop differs:";
    for (const KernelOperations& k : solver.operations) b << " " << k.kernel << " " << count(k.emitted, k.executed) << ";";
    b << " total " << count(solver.total_emitted(), solver.total_executed()) << "; fused dynamics "
      << count(solver.fused.emitted, solver.fused.executed) << ".\n";
    if (solver.assembly_pairs > 0)
      b << "// M is assembled by a loop with one pass per (ancestor, descendant) pair of bodies: "
        << count_of(solver.assembly_pairs, "pass", "passes") << ", " << solver.assembly_operations_per_pass
        << " operations each.\n";
  }
  return b.str();
}

}  // namespace

long GeneratedSolver::total_emitted() const {
  long total = 0;
  for (const KernelOperations& k : operations) total += k.emitted;
  return total;
}

long GeneratedSolver::total_executed() const {
  long total = 0;
  for (const KernelOperations& k : operations) total += k.executed;
  return total;
}

const char* generator_version() { return MBFE_GENERATOR_VERSION; }

namespace {
GeneratedSolver generate_solver_unchecked(const ir::Model& model);
}  // namespace

GeneratedSolver generate_solver(const ir::Model& model) {
  if (model.bodies.empty())
    throw std::invalid_argument("model '" + model.name + "' has no bodies: nothing to generate");
  try {
    return generate_solver_unchecked(model);
  } catch (const std::overflow_error& e) {
    // Every number of the file is finite, but products of huge ones (mass
    // 1e300 at com 1e300) overflow a double: bad input, reported as such
    // (exit status 2), not as an internal error.
    // Regression input: tests/fuzz/regressions/overflowing_constants.yaml.
    throw ir::ModelError(model.source_path, {},
                            "model '" + model.name + "': " + e.what() +
                                " (a product of its masses, lengths, inertias or loads exceeds 1.8e308; "
                                "use values of a physical magnitude)");
  }
}

namespace {

GeneratedSolver generate_solver_unchecked(const ir::Model& model) {
  RigidDerivation d;
  derive_rigid_dynamics(model, d);

  SymbolNames inputs;
  for (std::size_t i = 0; i < d.q.size(); ++i) {
    inputs.emplace(d.q[i], "q[" + std::to_string(i) + "]");
    inputs.emplace(d.qd[i], "qd[" + std::to_string(i) + "]");
  }
  inputs.emplace(d.t, "t");
  KernelParams params = {{"q", {}}, {"qd", {}}, {"t", {d.t}}};
  for (std::size_t i = 0; i < d.q.size(); ++i) {
    params[0].symbols.push_back(d.q[i]);
    params[1].symbols.push_back(d.qd[i]);
  }

  GeneratedSolver solver;
  std::ostringstream kernels;
  for (Kernel* k : {&d.mass_matrix, &d.inertial_forces, &d.generalized_forces, &d.dynamics}) {
    eliminate_common_subexpressions(*k);
    const EmittedKernel e = emit_kernel(*k, inputs, params, "");
    // The fused kernel repeats the other three; count it apart, not in the total.
    if (k != &d.dynamics) solver.operations.push_back({k->name, e.emitted, e.executed});
    else solver.fused = {k->name, e.emitted, e.executed};
    kernels << "\n" << e.text;
  }
  if (d.mass_matrix.assembly) {
    solver.assembly_pairs = d.mass_matrix.assembly->pairs();
    solver.assembly_operations_per_pass = d.mass_matrix.assembly->operations_per_pass();
  }
  // Contact kernels (Section 4): same inputs q, qd, plus the element's DOFs.
  ContactSymbols contact_symbols;
  contact_symbols.q = d.q;
  contact_symbols.qd = d.qd;
  for (int l = 0; l < 4; ++l) {
    contact_symbols.qe.emplace_back("qe" + std::to_string(l));
    contact_symbols.qed.emplace_back("qed" + std::to_string(l));
    inputs.emplace(contact_symbols.qe[l], "qe[" + std::to_string(l) + "]");
    inputs.emplace(contact_symbols.qed[l], "qed[" + std::to_string(l) + "]");
  }
  inputs.emplace(contact_symbols.s0, "s0");
  inputs.emplace(contact_symbols.le, "le");
  params.push_back({"qe", {contact_symbols.qe.begin(), contact_symbols.qe.end()}});
  params.push_back({"qed", {contact_symbols.qed.begin(), contact_symbols.qed.end()}});
  params.push_back({"s0", {contact_symbols.s0}});
  params.push_back({"le", {contact_symbols.le}});
  std::vector<ContactKernels> contacts = derive_contacts(model, contact_symbols, d.code);
  std::ostringstream contact_text;
  for (ContactKernels& c : contacts) {
    for (Kernel* k : {&c.position, &c.phi, &c.jacobians, &c.gamma}) {
      eliminate_common_subexpressions(*k);
      const EmittedKernel e = emit_kernel(*k, inputs, params, "static ");
      solver.operations.push_back({k->name, e.emitted, e.executed});
      contact_text << "\n" << e.text;
    }
    // The ABI wants the position as a return value.
    contact_text << "\nstatic double " << c.position.name << "_value(const double* q) {\n  double s = 0.0;\n  "
                 << c.position.name << "(q, &s);\n  return s;\n}\n";
  }

  std::ostringstream points;
  for (auto& pk : d.points) {
    eliminate_common_subexpressions(pk.kernel);
    points << "\n" << emit_kernel(pk.kernel, inputs, params, "static ").text;
  }

  const std::string& name = model.name;
  const int n = static_cast<int>(model.bodies.size());
  const std::string ns = "mbfe_generated::" + name;
  const std::string entry = "mbfe_model_" + name;

  std::ostringstream header;
  header << banner(model, name + ".h", solver) << "#pragma once\n\n#include \"mbfe_model_abi.h\"\n\n"
         << "namespace mbfe_generated {\nnamespace " << name << " {\n\n"
         << "// Generalized coordinates, one per body, in model order:";
  for (const auto& body : model.bodies) header << " " << body.name;
  header << ".\nconstexpr int kNumCoordinates = " << n << ";\n\n"
         << "void mass_matrix(const double* q, double* M);\n"
         << "void inertial_forces(const double* q, const double* qd, double* F);\n"
         << "void generalized_forces(const double* q, const double* qd, double t, double* Q);\n"
         << "void point_position(const double* q, int body, int point, double* xy);\n"
         << "void dynamics(const double* q, const double* qd, double t, double* M, double* F, double* Q);\n\n"
         << "}  // namespace " << name << "\n}  // namespace mbfe_generated\n\n"
         << "extern \"C\" const mbfe_model_v1* " << entry << "(void);\n";

  std::ostringstream source;
  source << banner(model, name + ".cpp", solver) << "#include \"" << name << ".h\"\n\n#include <cmath>\n\n"
         << "namespace mbfe_generated {\nnamespace " << name << " {\n";
  if (d.mass_matrix.assembly && !d.mass_matrix.assembly->is_chain()) {
    source << "\n// Parent of each body (-1: the ground), for the assembly loop of M; a parent comes before its\n"
           << "// children.\nconstexpr int " << kParentTable << "[kNumCoordinates] = {";
    const std::vector<int>& parent = d.mass_matrix.assembly->parent;
    for (std::size_t i = 0; i < parent.size(); ++i) source << (i ? ", " : "") << parent[i];
    source << "};\n";
  }
  source << kernels.str() << points.str()
         << contact_text.str()
         << "\n// Ground-frame position of point `point` of body `body` (indices in model order).\n"
         << "void point_position(const double* q, int body, int point, double* xy) {\n";
  for (const auto& pk : d.points)
    source << "  if (body == " << pk.body << " && point == " << pk.point << ") return " << pk.kernel.name
           << "(q, xy);\n";
  source << "  (void)q;\n  xy[0] = xy[1] = 0.0;  // unknown point: the caller validated indices\n}\n\n"
         << "namespace {\n\nconst char* const kCoordinateNames[] = {";
  for (int i = 0; i < n; ++i) source << (i ? ", " : "") << "\"" << model.bodies[i].name << "\"";
  source << "};\n\n";
  if (!contacts.empty()) {
    source << "const mbfe_contact_kernels_v1 kContacts[] = {\n";
    for (const ContactKernels& c : contacts)
      source << "    {\"" << c.name << "\", " << c.type << ", " << c.beam << ", " << print_double(c.at) << ", "
             << c.rows << ", " << c.position.name << "_value, " << c.phi.name << ", " << c.jacobians.name << ", "
             << c.gamma.name << "},\n";
    source << "};\n\n";
  }
  source << "const mbfe_model_v1 kModel = {\n"
         << "    MBFE_MODEL_ABI_VERSION,\n"
         << "    \"" << name << "\",\n"
         << "    \"" << model.source_sha256 << "\",\n"
         << "    \"" << generator_version() << "\",\n"
         << "    kNumCoordinates,\n    kCoordinateNames,\n    mass_matrix,\n    inertial_forces,\n"
         << "    generalized_forces,\n    point_position,\n    " << contacts.size() << ",\n    "
         << (contacts.empty() ? "nullptr" : "kContacts") << ",\n    dynamics,\n};\n\n"
         << "}  // namespace\n}  // namespace " << name << "\n}  // namespace mbfe_generated\n\n"
         << "extern \"C\" const mbfe_model_v1* " << entry << "(void) { return &" << ns << "::kModel; }\n\n"
         << "#ifdef MBFE_SHARED_ENTRY  // defined when compiled into a run-time loaded library\n"
         << "extern \"C\" const mbfe_model_v1* mbfe_model_entry(void) { return " << entry << "(); }\n"
         << "#endif\n";

  solver.files.push_back({name + ".h", header.str()});
  solver.files.push_back({name + ".cpp", source.str()});
  return solver;
}

}  // namespace

}  // namespace mbfe::gen
