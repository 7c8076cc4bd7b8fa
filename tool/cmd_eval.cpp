// mbfe eval MODEL.yaml --q ... --qd ... [--t T] --json
#include <Eigen/Core>
#include <iostream>
#include <tuple>
#include <nlohmann/json.hpp>
#include <vector>

#include "api/mbfe.h"
#include "frontend/parse_model.h"
#include "ir/coordinate_layout.h"
#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/model_warnings_notice.h"
#include "api/json_text.h"

namespace mbfe::tool {

namespace {
constexpr const char* kHelp = R"(Usage: mbfe eval MODEL.yaml --q v1,v2,... --qd v1,v2,... [--qc ...] [--qcd ...] [--t T] [--set PATH=VALUE] [--json]

Evaluates the generated solver at one state: the mass matrix M(q), the
velocity-dependent inertial terms F(q, q') and the generalized forces
Q(q, q', t) of M q'' + F = Q at time --t (s, default 0: time-dependent loads
and driven joints). Coordinates are in model order (one per body); missing
--q/--qd mean zeros; a driven joint's coordinate and rate are its motion's at
--t, whatever --q/--qd say. With --json the output is
  {"M": [[...], ...], "F": [...], "Q": [...], "warnings": [...]}
with "warnings" the lines printed on stderr about likely unit mistakes
(docs/robustness.md, "Warnings"; empty when none).

For a model with contacts, --qc/--qcd give the beam coordinates and their rates
(all beams in file order, each beam's free DOFs [w, w'] per node from s = 0 to
L, support-fixed DOFs removed; default zeros) and the output gains
  "constraints": {"Phi": [...], "Jb": [[...]], "Jc": [[...]], "gamma": [...]}
stacked over the constraint contacts in file order (2 rows per pin, 1 per
slider_pin; a slider_spring is a force, not a constraint, and has no row):
Phi (m), J_b = dPhi/dq_b, J_c = dPhi/dq_c over all beam coordinates and
gamma = -(dJ/dt) q' of J_b q_b'' + J_c q_c'' = gamma.

A spatial model (dimension: 3) takes --q with its nq position coordinates
(a quaternion as w, x, y, z, of unit length within 1e-6; missing --q: zeros
and identity quaternions)
and --qd with its nv velocity coordinates; M is nv x nv. A model with closed
loops (`constraints:`, planar or spatial) adds
  "loops": {"Phi": [...], "J": [[...]], "gamma": [...]}
with Phi' = J qd and J qd' = gamma (docs/model-format.md, "Closed loops").

--set PATH=VALUE (repeatable) replaces a value of the model file before it is
read, as a sweep's vary paths address it (list items by their name:); errors
point into the file and name the --set.

Examples:
  mbfe eval models/double_pendulum.yaml --q 0.3,-0.2 --qd 1,0 --json
  mbfe eval models/double_pendulum_beam.yaml --q -1.38,-0.93 --qd 0.1,0 --json
  mbfe eval models/double_pendulum.yaml --set bodies.link2.mass=2 --q 0.3,-0.2 --json
)";

nlohmann::json rows_of(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    std::vector<double> row(m.cols());
    for (Eigen::Index c = 0; c < m.cols(); ++c) row[c] = m(r, c);
    rows.push_back(row);
  }
  return rows;
}

std::vector<double> list_of(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

}  // namespace

int cmd_eval(const Args& args) {
  const ParsedArgs parsed(args, {"q", "qd", "t", "qc", "qcd", "set"}, {"help", "json", "quiet"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1) throw UsageError("expected one model file (see --help)");
  std::vector<std::string> warnings;
  {
    const ir::Model ir = frontend::load_model_file(parsed.positional()[0], {}, model_overrides(parsed));
    warnings = announce_model_warnings(ir);
  }
  LoadOptions load;
  load.quiet = parsed.has("quiet") || parsed.has("json");
  load.overrides = model_overrides(parsed);
  const Model model = Model::load(parsed.positional()[0], load);
  // A planar tree names its coordinates by body; a spatial model or one with
  // closed loops has position and velocity coordinates of its own.
  const bool by_body = model.ir().dimension == 2 && model.ir().constraints.empty();
  const ir::CoordinateLayout layout = ir::coordinate_layout(model.ir());
  State state;
  state.q = parsed.numbers("q").value_or(std::vector<double>{});
  state.qd = parsed.numbers("qd").value_or(std::vector<double>{});
  state.qc = parsed.numbers("qc").value_or(std::vector<double>{});
  state.qcd = parsed.numbers("qcd").value_or(std::vector<double>{});
  state.t = parsed.number("t").value_or(0.0);
  for (const auto& [flag, values, n] :
       {std::tuple<const char*, const std::vector<double>&, int>{"q", state.q, layout.num_positions},
        {"qd", state.qd, layout.num_velocities}}) {
    if (values.empty() || static_cast<int>(values.size()) == n) continue;
    const std::string what = by_body ? " (one per body, in model order)"
                                     : std::string(flag == std::string("q") ? " (position" : " (velocity") +
                                           " coordinates in model order)";
    throw UsageError(std::string("--") + flag + " has " + std::to_string(values.size()) + " entries, expected " +
                     std::to_string(n) + what);
  }
  Evaluation e;
  try {
    e = model.evaluate(state);
  } catch (const runtime::ContactError& error) {  // a slider off its beam
    std::cerr << "mbfe eval: " << error.what() << "\n";
    return 3;
  } catch (const runtime::InvalidInput& error) {
    // Model::evaluate names the state's field ("q: the quaternion of body
    // ..."); here that field is a flag.
    const std::string what = error.what();
    if (what.rfind("q: ", 0) == 0) throw UsageError("--" + what);
    throw;
  }

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
  if (e.has_loops) out["loops"] = {{"Phi", list_of(e.loop_phi)}, {"J", rows_of(e.loop_j)}, {"gamma", list_of(e.loop_gamma)}};
  out["warnings"] = warnings_json(warnings);
  if (parsed.has("json")) {
    std::cout << json_text(out) << "\n";
    return 0;
  }
  if (by_body) {
    std::cout << "coordinates:";
    for (const auto& b : model.ir().bodies) std::cout << " " << b.name;
  } else {
    std::cout << "position coordinates:";
    for (const std::string& name : layout.position_names) std::cout << " " << name;
    std::cout << "\nvelocity coordinates:";
    for (const std::string& name : layout.velocity_names) std::cout << " " << name;
  }
  std::cout << "\nM = " << json_text(out["M"]) << "\nF = " << json_text(out["F"]) << "\nQ = " << json_text(out["Q"])
            << "\n";
  if (out.contains("constraints"))
    for (const char* key : {"Phi", "Jb", "Jc", "gamma"})
      std::cout << key << " = " << json_text(out["constraints"][key]) << "\n";
  if (out.contains("loops"))
    for (const char* key : {"Phi", "J", "gamma"}) std::cout << key << " = " << json_text(out["loops"][key]) << "\n";
  return 0;
}

}  // namespace mbfe::tool
