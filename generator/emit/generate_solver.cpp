// The generator's pipeline: derive the kernels of a model (symbolic/), remove
// common subexpressions, print them (kernel_emitter.h) and lay out the two
// files (solver_files.h).
#include "generator/emit/generate_solver.h"

#include <sstream>
#include <stdexcept>

#include "generator/emit/generate_spatial_solver.h"
#include "generator/emit/kernel_emitter.h"
#include "generator/emit/solver_files.h"
#include "generator/symbolic/contact_kinematics.h"
#include "generator/symbolic/cse.h"
#include "generator/symbolic/driven_motion.h"
#include "generator/symbolic/loop_constraints.h"
#include "generator/symbolic/loop_kinematics.h"
#include "generator/symbolic/rigid_dynamics.h"
#include "generator/symbolic/rigid_jacobians.h"
#include "ir/model_error.h"

namespace mbfe::gen {

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
// Largest tree that gets the closed-form Jacobian kernel (see its use).
constexpr std::size_t kMaxJacobianCoordinates = 12;
}  // namespace

GeneratedSolver generate_solver(const ir::Model& model) {
  if (model.bodies.empty())
    throw std::invalid_argument("model '" + model.name + "' has no bodies: nothing to generate");
  try {
    return model.dimension == 3 ? generate_spatial_solver(model) : generate_solver_unchecked(model);
  } catch (const std::overflow_error& e) {
    // Every number of the file is finite, but products of huge ones (mass
    // 1e300 at com 1e300) overflow a double: bad input, reported as such
    // (exit status 2), not as an internal error.
    // Regression input: tests/fuzz/regressions/overflowing_constants.yaml.
    throw ir::ModelError(model.source_path, {},
                            "model '" + model.name + "': " + e.what() +
                                " (a product of its masses, lengths, inertias or loads exceeds 1.8e308; "
                                "use values of a physical magnitude)");
  } catch (const std::domain_error& e) {
    // GiNaC's pole_error and domain_error. The expressions of the file are
    // checked where they are converted (time_functions.h) and differentiated
    // (the motions), with their positions; this is the net under them.
    throw ir::ModelError(model.source_path, {},
                         "model '" + model.name + "': the symbolic derivation found an undefined value (GiNaC: " +
                             e.what() + ")");
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
  SolverParts parts;
  std::ostringstream kernels;
  for (const Kernel* k : {&d.mass_matrix, &d.inertial_forces, &d.generalized_forces, &d.dynamics}) {
    // A copy: CSE may hoist a repeated part of an output into a temporary of
    // this kernel alone, and the tangents below differentiate the outputs as
    // the code list defines them.
    Kernel printed = *k;
    eliminate_common_subexpressions(printed);
    const EmittedKernel e = emit_kernel(printed, inputs, params, "");
    // The fused kernel repeats the other three; count it apart, not in the total.
    if (k != &d.dynamics) solver.operations.push_back({k->name, e.emitted, e.executed});
    else solver.fused = {k->name, e.emitted, e.executed};
    kernels << "\n" << e.text;
  }
  // The tangents for the implicit integrators of coupled models. Their code
  // grows as nq^2 times the kinematics (a 20-link chain: 10,000 lines and a
  // minute of g++ -O2), so rigid-only models and large trees go without; the
  // runtime then takes differences of the dynamics kernel.
  const bool with_jacobians = !model.beams.empty() && d.q.size() <= kMaxJacobianCoordinates;
  if (with_jacobians) {
    std::vector<GiNaC::symbol> qdd;
    KernelParam qdd_param{"qdd", {}};
    for (std::size_t i = 0; i < d.q.size(); ++i) {
      qdd.emplace_back("qdd" + std::to_string(i));
      inputs.emplace(qdd.back(), "qdd[" + std::to_string(i) + "]");
      qdd_param.symbols.push_back(qdd.back());
    }
    params.push_back(qdd_param);
    Kernel jacobians = derive_dynamics_jacobians(model, d, qdd);
    eliminate_common_subexpressions(jacobians);
    const EmittedKernel e = emit_kernel(jacobians, inputs, params, "static ");
    solver.operations.push_back({jacobians.name, e.emitted, e.executed});
    parts.jacobians = "\n" + e.text;
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
    const ir::Contact& ic = model.contacts[parts.contact_entries.size()];
    parts.contact_entries.push_back({c.name, c.type, c.beam, c.rows, c.at, c.position.name + "_value", c.phi.name,
                                     c.jacobians.name, c.gamma.name, ic.stiffness, ic.damping, ic.unilateral,
                                     ic.from_below});
    // The ABI wants the position as a return value.
    contact_text << "\nstatic double " << c.position.name << "_value(const double* q) {\n  double s = 0.0;\n  "
                 << c.position.name << "(q, &s);\n  return s;\n}\n";
  }

  // Driven joints: q, q' and q'' of each motion, derived here in closed form.
  Kernel motion = derive_motion_kernel(model, d.t, d.code, parts.driven);
  if (!parts.driven.empty()) {
    eliminate_common_subexpressions(motion);
    const EmittedKernel e = emit_kernel(motion, inputs, params, "static ");
    solver.operations.push_back({motion.name, e.emitted, e.executed});
    parts.motion = "\n" + e.text;
  }

  // Closed loops (after every other kernel: their intermediates do not
  // change the numbering of the others).
  if (!model.constraints.empty()) {
    const LoopKinematics loop_kinematics = planar_loop_kinematics(model, d.kinematics, d.qd, d.code);
    LoopKernels loops = derive_loop_constraints(model, loop_kinematics, "qd", d.code);
    std::ostringstream text;
    for (Kernel* k : {&loops.constraints, &loops.jacobian, &loops.gamma}) {
      eliminate_common_subexpressions(*k);
      const EmittedKernel e = emit_kernel(*k, inputs, params, "static ");
      solver.operations.push_back({k->name, e.emitted, e.executed});
      text << "\n" << e.text;
    }
    parts.loops = text.str();
    for (const LoopKernels::Entry& entry : loops.entries)
      parts.loop_entries.push_back({entry.name, entry.type, entry.first_row, entry.rows});
    parts.loop_rows = loops.rows;
  }

  std::ostringstream points;
  for (auto& pk : d.points) {
    eliminate_common_subexpressions(pk.kernel);
    points << "\n" << emit_kernel(pk.kernel, inputs, params, "static ").text;
    parts.point_functions.push_back({pk.body, pk.point, pk.kernel.name});
  }
  parts.kernels = kernels.str();
  parts.points = points.str();
  parts.contacts = contact_text.str();
  if (d.mass_matrix.assembly && !d.mass_matrix.assembly->is_chain()) parts.parent_table = d.mass_matrix.assembly->parent;

  solver.files.push_back({model.name + ".h", solver_header(model, solver)});
  solver.files.push_back({model.name + ".cpp", solver_source(model, solver, parts)});
  return solver;
}

}  // namespace

}  // namespace mbfe::gen
