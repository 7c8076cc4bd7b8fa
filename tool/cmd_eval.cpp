// mbfe eval MODEL.yaml --q ... --qd ... [--t T] --json
#include <Eigen/Core>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "tool/cli_args.h"
#include "tool/commands.h"
#include "runtime/fem/beam_system.h"
#include "frontend/parse_model.h"
#include "runtime/multibody/contact_constraints.h"
#include "runtime/multibody/coupled_system.h"
#include "tool/solver_cache.h"

namespace mbfe::tool {

namespace {
constexpr const char* kHelp = R"(Usage: mbfe eval MODEL.yaml --q v1,v2,... --qd v1,v2,... [--qc ...] [--qcd ...] [--t T] [--json]

Evaluates the generated solver at one state: the mass matrix M(q), the
velocity-dependent inertial terms F(q, q') and the generalized forces
Q(q, q', t) of M q'' + F = Q. Coordinates are in model order (one per body);
missing --q/--qd mean zeros. With --json the output is
  {"M": [[...], ...], "F": [...], "Q": [...]}

For a model with contacts, --qc/--qcd give the beam coordinates and their rates
(all beams in file order, each beam's free DOFs [w, w'] per node from s = 0 to
L, support-fixed DOFs removed; default zeros) and the output gains
  "constraints": {"Phi": [...], "Jb": [[...]], "Jc": [[...]], "gamma": [...]}
stacked over the contacts in file order (2 rows per pin, 1 per slider_pin):
Phi (m), J_b = dPhi/dq_b, J_c = dPhi/dq_c over all beam coordinates and
gamma = -(dJ/dt) q' of J_b q_b'' + J_c q_c'' = gamma.

Examples:
  mbfe eval models/double_pendulum.yaml --q 0.3,-0.2 --qd 1,0 --json
  mbfe eval models/double_pendulum_beam.yaml --q -1.38,-0.93 --qd 0.1,0 --json
)";

std::vector<double> state_vector(const ParsedArgs& parsed, const std::string& flag, int n) {
  std::vector<double> v = parsed.numbers(flag).value_or(std::vector<double>(n, 0.0));
  if (static_cast<int>(v.size()) != n)
    throw UsageError("--" + flag + " has " + std::to_string(v.size()) + " entries, expected " +
                     std::to_string(n) + " (one per body, in model order)");
  return v;
}
std::vector<double> beam_vector(const ParsedArgs& parsed, const std::string& flag, int n) {
  std::vector<double> v = parsed.numbers(flag).value_or(std::vector<double>(n, 0.0));
  if (static_cast<int>(v.size()) != n)
    throw UsageError("--" + flag + " has " + std::to_string(v.size()) + " entries, expected " +
                     std::to_string(n) + " (beam coordinates in contract order)");
  return v;
}
}  // namespace

int cmd_eval(const Args& args) {
  const ParsedArgs parsed(args, {"q", "qd", "t", "qc", "qcd"}, {"help", "json", "quiet"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1) throw UsageError("expected one model file (see --help)");
  const ir::Model model = frontend::load_model_file(parsed.positional()[0]);
  if (model.bodies.empty())
    throw UsageError("model '" + model.name + "' has no bodies: nothing to evaluate (try mbfe modal)");
  if ((parsed.has("qc") || parsed.has("qcd")) && model.contacts.empty())
    throw UsageError("--qc/--qcd: model '" + model.name + "' has no contacts (no beam coordinates to evaluate)");
  const int n = static_cast<int>(model.bodies.size());
  const std::vector<double> q = state_vector(parsed, "q", n);
  const std::vector<double> qd = state_vector(parsed, "qd", n);
  const double t = parsed.number("t").value_or(0.0);

  const LoadedSolver solver = load_solver(model, parsed.has("quiet") || parsed.has("json"));
  std::vector<double> M(static_cast<std::size_t>(n) * n), F(n), Q(n);
  solver.model->mass_matrix(q.data(), M.data());
  solver.model->inertial_forces(q.data(), qd.data(), F.data());
  solver.model->generalized_forces(q.data(), qd.data(), t, Q.data());

  nlohmann::json out;
  out["M"] = nlohmann::json::array();
  for (int r = 0; r < n; ++r)
    out["M"].push_back(std::vector<double>(M.begin() + r * n, M.begin() + (r + 1) * n));
  out["F"] = F;
  out["Q"] = Q;
  if (!model.contacts.empty()) {
    std::vector<runtime::BeamMesh> meshes;
    for (const ir::Beam& b : model.beams) meshes.push_back(runtime::beam_mesh(runtime::assemble_beam(b, model.gravity)));
    const runtime::ContactConstraints cc(*solver.model, meshes);
    const int nc = cc.num_beam_dofs();
    const std::vector<double> qc = beam_vector(parsed, "qc", nc);
    const std::vector<double> qcd = beam_vector(parsed, "qcd", nc);
    runtime::ConstraintValues cv;
    try {
      cc.evaluate(t, q.data(), qc.data(), qd.data(), qcd.data(), cv);
    } catch (const std::runtime_error& e) {  // a slider off its beam
      std::cerr << "mbfe eval: " << e.what() << "\n";
      return 3;
    }
    const int m = cc.num_rows();
    const Eigen::MatrixXd jc = cv.jc_dense(nc);
    nlohmann::json c;
    c["Phi"] = std::vector<double>(cv.phi.data(), cv.phi.data() + m);
    c["Jb"] = nlohmann::json::array();
    c["Jc"] = nlohmann::json::array();
    for (int r = 0; r < m; ++r) {
      std::vector<double> jb(n), jcr(nc);
      for (int k = 0; k < n; ++k) jb[k] = cv.jb(r, k);
      for (int k = 0; k < nc; ++k) jcr[k] = jc(r, k);
      c["Jb"].push_back(jb);
      c["Jc"].push_back(jcr);
    }
    c["gamma"] = std::vector<double>(cv.gamma.data(), cv.gamma.data() + m);
    out["constraints"] = c;
  }
  if (parsed.has("json")) {
    std::cout << out.dump() << "\n";
  } else {
    std::cout << "coordinates:";
    for (const auto& b : model.bodies) std::cout << " " << b.name;
    std::cout << "\nM = " << out["M"].dump() << "\nF = " << out["F"].dump() << "\nQ = " << out["Q"].dump()
              << "\n";
    if (out.contains("constraints"))
      for (const char* key : {"Phi", "Jb", "Jc", "gamma"})
        std::cout << key << " = " << out["constraints"][key].dump() << "\n";
  }
  return 0;
}

}  // namespace mbfe::tool
