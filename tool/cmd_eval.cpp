// mbfe eval MODEL.yaml --q ... --qd ... [--t T] --json
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "cli_args.h"
#include "commands.h"
#include "model/parse_model.h"
#include "solver_cache.h"

namespace mbfe::tool {

namespace {
constexpr const char* kHelp = R"(Usage: mbfe eval MODEL.yaml --q v1,v2,... --qd v1,v2,... [--t T] [--json]

Evaluates the generated solver at one state: the mass matrix M(q), the
velocity-dependent inertial terms F(q, q') and the generalized forces
Q(q, q', t) of M q'' + F = Q. Coordinates are in model order (one per body);
missing --q/--qd mean zeros. With --json the output is
  {"M": [[...], ...], "F": [...], "Q": [...]}

Example:
  mbfe eval models/double_pendulum.yaml --q 0.3,-0.2 --qd 1,0 --json
)";

std::vector<double> state_vector(const ParsedArgs& parsed, const std::string& flag, int n) {
  std::vector<double> v = parsed.numbers(flag).value_or(std::vector<double>(n, 0.0));
  if (static_cast<int>(v.size()) != n)
    throw UsageError("--" + flag + " has " + std::to_string(v.size()) + " entries, expected " +
                     std::to_string(n) + " (one per body, in model order)");
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
  const model::Model model = model::load_model_file(parsed.positional()[0]);
  if (model.bodies.empty())
    throw UsageError("model '" + model.name + "' has no bodies: nothing to evaluate (try mbfe modal)");
  if (parsed.has("qc") || parsed.has("qcd"))
    throw UsageError("--qc/--qcd (contact constraints) are not supported yet");
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
  if (parsed.has("json")) {
    std::cout << out.dump() << "\n";
  } else {
    std::cout << "coordinates:";
    for (const auto& b : model.bodies) std::cout << " " << b.name;
    std::cout << "\nM = " << out["M"].dump() << "\nF = " << out["F"].dump() << "\nQ = " << out["Q"].dump()
              << "\n";
  }
  return 0;
}

}  // namespace mbfe::tool
