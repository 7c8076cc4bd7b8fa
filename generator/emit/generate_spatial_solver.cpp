// The spatial pipeline: derive the kernels (symbolic/spatial_dynamics.h),
// remove common subexpressions, print them (kernel_emitter.h) and lay out
// the two files (spatial_solver_files.h).
#include "generator/emit/generate_spatial_solver.h"

#include <sstream>

#include "generator/emit/kernel_emitter.h"
#include "generator/emit/spatial_solver_files.h"
#include "generator/symbolic/cse.h"
#include "generator/symbolic/driven_motion.h"
#include "generator/symbolic/loop_constraints.h"
#include "generator/symbolic/loop_kinematics.h"
#include "generator/symbolic/spatial_dynamics.h"

namespace mbfe::gen {

GeneratedSolver generate_spatial_solver(const ir::Model& model) {
  SpatialDerivation d;
  derive_spatial_dynamics(model, d);

  SymbolNames inputs;
  KernelParams params = {{"q", {}}, {"v", {}}, {"t", {d.t}}};
  for (std::size_t i = 0; i < d.q.size(); ++i) {
    inputs.emplace(d.q[i], "q[" + std::to_string(i) + "]");
    params[0].symbols.push_back(d.q[i]);
  }
  for (std::size_t i = 0; i < d.v.size(); ++i) {
    inputs.emplace(d.v[i], "v[" + std::to_string(i) + "]");
    params[1].symbols.push_back(d.v[i]);
  }
  inputs.emplace(d.t, "t");

  GeneratedSolver solver;
  SpatialSolverParts parts;
  std::ostringstream kernels;
  for (Kernel* k : {&d.mass_matrix, &d.inertial_forces, &d.generalized_forces, &d.dynamics, &d.position_derivative}) {
    eliminate_common_subexpressions(*k);
    const EmittedKernel e = emit_kernel(*k, inputs, params, "");
    // The fused kernel repeats the other three; count it apart, not in the total.
    if (k != &d.dynamics) solver.operations.push_back({k->name, e.emitted, e.executed});
    else solver.fused = {k->name, e.emitted, e.executed};
    kernels << "\n" << e.text;
  }
  const AncestorPairAssembly& assembly = *d.mass_matrix.assembly;
  solver.assembly_pairs = assembly.pairs();
  solver.assembly_operations_per_pass = assembly.operations_per_pass();
  if (!assembly.is_chain()) parts.parent_table = assembly.parent;

  // Driven joints: the motion kernel counts them in model order; the ABI
  // wants their indices into v and into q.
  std::vector<int> driven_bodies;
  Kernel motion = derive_motion_kernel(model, d.t, d.code, driven_bodies);
  if (!driven_bodies.empty()) {
    eliminate_common_subexpressions(motion);
    const EmittedKernel e = emit_kernel(motion, inputs, params, "static ");
    solver.operations.push_back({motion.name, e.emitted, e.executed});
    parts.motion = "\n" + e.text;
    for (int b : driven_bodies) {
      parts.driven_velocities.push_back(d.layout.first_velocity[b]);
      parts.driven_positions.push_back(d.layout.first_position[b]);
    }
  }

  if (!model.constraints.empty()) {
    const LoopKinematics loop_kinematics = spatial_loop_kinematics(model, d.layout, d.kinematics);
    LoopKernels loops = derive_loop_constraints(model, loop_kinematics, "v", d.code);
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

  solver.files.push_back({model.name + ".h", spatial_solver_header(model, d.layout, solver)});
  solver.files.push_back({model.name + ".cpp", spatial_solver_source(model, d.layout, solver, parts)});
  return solver;
}

}  // namespace mbfe::gen
