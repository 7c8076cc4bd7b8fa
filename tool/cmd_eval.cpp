// mbfe eval MODEL.yaml --q ... --qd ... [--t T] --json
#include <Eigen/Core>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "api/mbfe.h"
#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/json_text.h"

namespace mbfe::tool {

namespace {
constexpr const char* kHelp = R"(Usage: mbfe eval MODEL.yaml --q v1,v2,... --qd v1,v2,... [--qc ...] [--qcd ...] [--t T] [--json]

Evaluates the generated solver at one state: the mass matrix M(q), the
velocity-dependent inertial terms F(q, q') and the generalized forces
Q(q, q', t) of M q'' + F = Q at time --t (s, default 0: time-dependent loads
and driven joints). Coordinates are in model order (one per body); missing
--q/--qd mean zeros; a driven joint's coordinate and rate are its motion's at
--t, whatever --q/--qd say. With --json the output is
  {"M": [[...], ...], "F": [...], "Q": [...]}

For a model with contacts, --qc/--qcd give the beam coordinates and their rates
(all beams in file order, each beam's free DOFs [w, w'] per node from s = 0 to
L, support-fixed DOFs removed; default zeros) and the output gains
  "constraints": {"Phi": [...], "Jb": [[...]], "Jc": [[...]], "gamma": [...]}
stacked over the constraint contacts in file order (2 rows per pin, 1 per
slider_pin; a slider_spring is a force, not a constraint, and has no row):
Phi (m), J_b = dPhi/dq_b, J_c = dPhi/dq_c over all beam coordinates and
gamma = -(dJ/dt) q' of J_b q_b'' + J_c q_c'' = gamma.

Examples:
  mbfe eval models/double_pendulum.yaml --q 0.3,-0.2 --qd 1,0 --json
  mbfe eval models/double_pendulum_beam.yaml --q -1.38,-0.93 --qd 0.1,0 --json
)";

}  // namespace

int cmd_eval(const Args& args) {
  const ParsedArgs parsed(args, {"q", "qd", "t", "qc", "qcd"}, {"help", "json", "quiet"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1) throw UsageError("expected one model file (see --help)");
  LoadOptions load;
  load.quiet = parsed.has("quiet") || parsed.has("json");
  const Model model = Model::load(parsed.positional()[0], load);
  State state;
  state.q = parsed.numbers("q").value_or(std::vector<double>{});
  state.qd = parsed.numbers("qd").value_or(std::vector<double>{});
  state.qc = parsed.numbers("qc").value_or(std::vector<double>{});
  state.qcd = parsed.numbers("qcd").value_or(std::vector<double>{});
  state.t = parsed.number("t").value_or(0.0);
  const std::size_t nb = model.ir().bodies.size();
  for (const auto& [flag, values] : {std::pair<const char*, const std::vector<double>&>{"q", state.q}, {"qd", state.qd}})
    if (!values.empty() && values.size() != nb)
      throw UsageError(std::string("--") + flag + " has " + std::to_string(values.size()) + " entries, expected " +
                       std::to_string(nb) + " (one per body, in model order)");
  Evaluation e;
  try {
    e = model.evaluate(state);
  } catch (const runtime::ContactError& error) {  // a slider off its beam
    std::cerr << "mbfe eval: " << error.what() << "\n";
    return 3;
  }

  auto rows_of = [](const Eigen::MatrixXd& m) {
    nlohmann::json rows = nlohmann::json::array();
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
      std::vector<double> row(m.cols());
      for (Eigen::Index c = 0; c < m.cols(); ++c) row[c] = m(r, c);
      rows.push_back(row);
    }
    return rows;
  };
  auto list_of = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  nlohmann::json out;
  out["M"] = rows_of(e.M);
  out["F"] = list_of(e.F);
  out["Q"] = list_of(e.Q);
  if (e.has_constraints) {
    nlohmann::json c;
    c["Phi"] = list_of(e.phi);
    c["Jb"] = rows_of(e.jb);
    c["Jc"] = rows_of(e.jc);
    c["gamma"] = list_of(e.gamma);
    out["constraints"] = c;
  }
  if (parsed.has("json")) {
    std::cout << json_text(out) << "\n";
  } else {
    std::cout << "coordinates:";
    for (const auto& b : model.ir().bodies) std::cout << " " << b.name;
    std::cout << "\nM = " << json_text(out["M"]) << "\nF = " << json_text(out["F"]) << "\nQ = " << json_text(out["Q"])
              << "\n";
    if (out.contains("constraints"))
      for (const char* key : {"Phi", "Jb", "Jc", "gamma"})
        std::cout << key << " = " << json_text(out["constraints"][key]) << "\n";
  }
  return 0;
}

}  // namespace mbfe::tool
