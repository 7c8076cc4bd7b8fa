#include "generator/emit/spatial_solver_files.h"

#include <sstream>

#include "generator/emit/kernel_emitter.h"

namespace mbfe::gen {

namespace {

void write_names(std::ostringstream& out, const char* array, const std::vector<std::string>& names) {
  out << "const char* const " << array << "[] = {";
  for (std::size_t i = 0; i < names.size(); ++i) out << (i ? ", " : "") << "\"" << names[i] << "\"";
  out << "};\n\n";
}

void write_indices(std::ostringstream& out, const char* array, const std::vector<int>& indices) {
  out << "const int " << array << "[] = {";
  for (std::size_t i = 0; i < indices.size(); ++i) out << (i ? ", " : "") << indices[i];
  out << "};\n\n";
}

}  // namespace

std::string spatial_solver_header(const ir::Model& model, const ir::CoordinateLayout& layout,
                                  const GeneratedSolver& solver) {
  const std::string& name = model.name;
  std::ostringstream header;
  header << banner(model, name + ".h", solver) << "#pragma once\n\n#include \"mbfe_model_abi.h\"\n\n"
         << "namespace mbfe_generated {\nnamespace " << name << " {\n\n"
         << "// A spatial model. Position coordinates q, model order:";
  for (const std::string& n : layout.position_names) header << " " << n;
  header << ".\n// Velocity coordinates v:";
  for (const std::string& n : layout.velocity_names) header << " " << n;
  header << ".\n// A quaternion is (w, x, y, z), read as unit; its velocities are the angular velocity in the body frame.\n"
         << "constexpr int kNumCoordinates = " << layout.num_positions << ";\n"
         << "constexpr int kNumVelocities = " << layout.num_velocities << ";\n\n"
         << "void mass_matrix(const double* q, double* M);\n"
         << "void inertial_forces(const double* q, const double* v, double* F);\n"
         << "void generalized_forces(const double* q, const double* v, double t, double* Q);\n"
         << "void point_position3(const double* q, int body, int point, double* xyz);\n"
         << "void dynamics(const double* q, const double* v, double t, double* M, double* F, double* Q);\n"
         << "void position_derivative(const double* q, const double* v, double* qdot);\n\n"
         << "}  // namespace " << name << "\n}  // namespace mbfe_generated\n\n"
         << "extern \"C\" const mbfe_model_v1* mbfe_model_" << name << "(void);\n";
  return header.str();
}

std::string spatial_solver_source(const ir::Model& model, const ir::CoordinateLayout& layout,
                                  const GeneratedSolver& solver, const SpatialSolverParts& parts) {
  const std::string& name = model.name;
  const std::string entry = "mbfe_model_" + name;
  std::ostringstream source;
  source << banner(model, name + ".cpp", solver) << "#include \"" << name << ".h\"\n\n#include <cmath>\n\n"
         << "namespace mbfe_generated {\nnamespace " << name << " {\n";
  if (!parts.parent_table.empty()) {
    source << "\n// Parent of each velocity coordinate (-1: the ground), for the assembly loop of M: the previous\n"
           << "// coordinate of the same joint, else the last one of the parent body's joint.\n"
           << "constexpr int " << kParentTable << "[kNumVelocities] = {";
    for (std::size_t i = 0; i < parts.parent_table.size(); ++i) source << (i ? ", " : "") << parts.parent_table[i];
    source << "};\n";
  }
  source << parts.kernels << parts.points << parts.motion << parts.loops
         << "\n// Ground-frame position of point `point` of body `body` (indices in model order).\n"
         << "void point_position3(const double* q, int body, int point, double* xyz) {\n";
  for (const SolverParts::PointFunction& pf : parts.point_functions)
    source << "  if (body == " << pf.body << " && point == " << pf.point << ") return " << pf.function
           << "(q, xyz);\n";
  source << "  (void)q;\n  xyz[0] = xyz[1] = xyz[2] = 0.0;  // unknown point: the caller validated indices\n}\n\n"
         << "namespace {\n\n";
  write_names(source, "kCoordinateNames", layout.position_names);
  write_names(source, "kVelocityNames", layout.velocity_names);
  const bool driven = !parts.driven_velocities.empty();
  const bool driven_positions_differ = parts.driven_positions != parts.driven_velocities;
  if (driven) write_indices(source, "kDrivenCoordinates", parts.driven_velocities);
  if (driven && driven_positions_differ) write_indices(source, "kDrivenPositions", parts.driven_positions);
  source << loop_table(parts.loop_entries);
  const bool loops = !parts.loop_entries.empty();
  source << "const mbfe_model_v1 kModel = {\n"
         << "    MBFE_MODEL_ABI_VERSION,\n"
         << "    \"" << name << "\",\n"
         << "    \"" << model.source_sha256 << "\",\n"
         << "    \"" << generator_version() << "\",\n"
         << "    kNumCoordinates,\n    kCoordinateNames,\n    mass_matrix,\n    inertial_forces,\n"
         << "    generalized_forces,\n"
         << "    nullptr,  // point_position: planar models only, see point_position3\n"
         << "    0,\n    nullptr,  // contacts: none in spatial models\n"
         << "    dynamics,\n    " << parts.driven_velocities.size() << ",\n    "
         << (driven ? "kDrivenCoordinates,\n    motion" : "nullptr,\n    nullptr") << ",\n"
         << "    nullptr,  // dynamics_jacobians\n"
         << "    3,  // dimension\n"
         << "    kNumVelocities,\n    kVelocityNames,\n    position_derivative,\n    "
         << (driven && driven_positions_differ ? "kDrivenPositions" : "nullptr") << ",\n    " << parts.loop_rows
         << ",\n    " << parts.loop_entries.size() << ",\n    "
         << (loops ? "kLoops,\n    loop_constraints,\n    loop_jacobian,\n    loop_gamma"
                   : "nullptr,\n    nullptr,\n    nullptr,\n    nullptr")
         << ",\n    point_position3,\n};\n\n"
         << "}  // namespace\n}  // namespace " << name << "\n}  // namespace mbfe_generated\n\n"
         << "extern \"C\" const mbfe_model_v1* " << entry << "(void) { return &mbfe_generated::" << name
         << "::kModel; }\n\n"
         << "#ifdef MBFE_SHARED_ENTRY  // defined when compiled into a run-time loaded library\n"
         << "extern \"C\" const mbfe_model_v1* mbfe_model_entry(void) { return " << entry << "(); }\n"
         << "#endif\n";
  return source.str();
}

}  // namespace mbfe::gen
