// mbfe simulate MODEL.yaml [--integrator NAME] [--step H] [--t-end T] [--out FILE.csv]
#include <Eigen/Core>
#include <iostream>

#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/coupled_model.h"
#include "tool/csv_output.h"
#include "runtime/integrators/integrator.h"
#include "runtime/integrators/simulation_driver.h"
#include "frontend/parse_model.h"
#include "runtime/multibody/multibody_errors.h"
#include "runtime/multibody/rigid_system.h"
#include "tool/simulate_options.h"
#include "tool/solver_cache.h"

namespace mbfe::tool {

namespace {

constexpr const char* kHelp = R"(Usage: mbfe simulate MODEL.yaml [options]

Integrates the model in time and writes a CSV: for rigid models the columns
are t,<q names>,<q names>_dot (coordinates named by their bodies, in model
order); for beam models t and the beam coordinates (see mbfe modal --help) or
the --probe columns; for coupled models (bodies, beams and contacts) t, the
rigid coordinates, the beam coordinates (or the --probe columns), their rates
(_dot), the contact forces lambda_<contact> (slider_pin) and
lambda_<contact>_1/_2 (pin: along and across the beam), N, and phi_abs, the
largest constraint residual |Phi| in m. Flags override the model's
`simulation:` block.

Options:
  --integrator NAME  forward_euler, backward_euler, explicit_midpoint, trapezoid,
                     rk4, generalized_alpha (beams), ab2, bdf2,
                     lmm:alpha=a0,..,ak:beta=b0,..,bk
  --step H           step in s
  --t-end T          end time in s
  --out FILE.csv     output file (default: standard output)
  --every N          write every N-th step (default: at most about 10000 rows)
  --adjust on|off    beam and coupled models: use the modal adjustment of
                     damping (default: on when a beam has an adjustment block)
  --probe BEAM@S     beam and coupled models: displacement at S m along BEAM
                     (several as a comma-separated list)
  --formulation F    coupled models: partitioned (default; eqs (16)-(17),
                     |Phi| closed by Newton at every step) or augmented
                     (multipliers; a cross-check, |Phi| drifts)
  --rho-inf R        generalized_alpha spectral radius at infinity (0..1)
  --quiet            no progress or cache messages on stderr

Exit status: 0 done; 2 bad input; 3 the simulation diverged or failed part-way
(everything computed up to there is in the output, flushed).

Examples:
  mbfe simulate models/double_pendulum.yaml --integrator rk4 --step 1e-3 --t-end 2 --out pendulum.csv
  mbfe simulate models/paper_platform.yaml --integrator forward_euler --step 1.4e-5 --t-end 1 --out platform.csv
)";

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const auto comma = text.find(',', start);
    out.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

int simulate_rigid(const ir::Model& model, const SimulateOptions& options, std::int64_t every) {
  runtime::IntegratorSpec integrator;
  try {
    integrator = runtime::parse_integrator(options.integrator);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (integrator.kind == runtime::IntegratorKind::kGeneralizedAlpha)
    throw UsageError("generalized_alpha needs a linear second-order (beam) model; for rigid models use "
                     "rk4, trapezoid, backward_euler, ...");
  if (options.rho_inf) integrator.rho_inf = *options.rho_inf;

  const LoadedSolver solver = load_solver(model, options.quiet);
  runtime::RigidSystem system(*solver.model, runtime::body_inertias(model));
  const int n = system.num_coordinates();
  Eigen::VectorXd y0(2 * n);
  for (int i = 0; i < n; ++i) {
    y0[i] = model.initial.q[i];
    y0[n + i] = model.initial.qd[i];
  }

  CsvOutput csv(options.out.value_or(""));
  std::vector<std::string> columns{"t"};
  for (int i = 0; i < 2 * n; ++i) columns.push_back(system.name(i));
  csv.header(columns);
  std::vector<double> row(1 + 2 * n);

  runtime::SimulationOptions run;
  run.step = options.step;
  run.t_end = options.t_end;
  run.every = every;
  run.quiet = options.quiet;
  const runtime::SimulationResult result =
      runtime::run_simulation(system, integrator, y0, run, [&](double t, const Eigen::VectorXd& y) {
        row[0] = t;
        for (int i = 0; i < 2 * n; ++i) row[1 + i] = y[i];
        csv.row(row.data(), row.size());
      });
  csv.flush();
  switch (result.status) {
    case runtime::SimulationStatus::kCompleted:
      if (!options.quiet)
        std::cerr << "mbfe: " << model.name << ": " << result.steps << " " << result.integrator
                  << " steps of " << result.step << " s to t = " << result.t << " s in "
                  << result.wall_seconds << " s; " << csv.rows() << " rows written"
                  << (options.out ? " to " + *options.out : std::string()) << "\n";
      return 0;
    case runtime::SimulationStatus::kDiverged:
      std::cerr << "mbfe simulate: " << runtime::describe(result) << "; " << csv.rows()
                << " rows written up to there\n";
      return 3;
    case runtime::SimulationStatus::kInterrupted:
      std::cerr << "mbfe simulate: interrupted at t = " << result.t << " s; " << csv.rows()
                << " rows written\n";
      return 3;
    case runtime::SimulationStatus::kFailed:
      std::cerr << "mbfe simulate: failed at t = " << result.t << " s: " << result.message << "; "
                << csv.rows() << " rows written up to there\n";
      return 3;
  }
  return 1;
}

}  // namespace

int cmd_simulate(const Args& args) {
  const ParsedArgs parsed(args, {"integrator", "step", "t-end", "out", "every", "adjust", "probe", "rho-inf", "formulation"},
                          {"help", "quiet"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1) throw UsageError("expected one model file (see --help)");
  const ir::Model model = frontend::load_model_file(parsed.positional()[0]);

  SimulateOptions options;
  options.integrator = parsed.value("integrator").value_or(model.simulation.integrator);
  options.step = parsed.number("step").value_or(model.simulation.step);
  options.t_end = parsed.number("t-end").value_or(model.simulation.t_end);
  if (!(options.step > 0)) throw UsageError("--step must be > 0");
  if (!(options.t_end > 0)) throw UsageError("--t-end must be > 0");
  options.out = parsed.value("out");
  options.quiet = parsed.has("quiet");
  options.rho_inf = parsed.number("rho-inf");
  if (options.rho_inf && (*options.rho_inf < 0 || *options.rho_inf > 1))
    throw UsageError("--rho-inf must be in [0, 1]");
  if (const auto adjust = parsed.value("adjust")) {
    if (*adjust != "on" && *adjust != "off") throw UsageError("--adjust takes on or off, got '" + *adjust + "'");
    options.adjust = *adjust == "on";
  }
  if (const auto probe = parsed.value("probe")) options.probes = split_commas(*probe);
  std::int64_t every = 0;
  if (const auto e = parsed.number("every")) {
    if (*e < 1 || *e != static_cast<double>(static_cast<std::int64_t>(*e)))
      throw UsageError("--every must be a positive integer");
    every = static_cast<std::int64_t>(*e);
  }
  options.every = every;

  const std::string formulation = parsed.value("formulation").value_or("partitioned");
  if (formulation != "partitioned" && formulation != "augmented")
    throw UsageError("--formulation takes partitioned or augmented, got '" + formulation + "'");
  if (is_coupled(model)) return simulate_coupled(model, options, formulation == "augmented");
  if (parsed.has("formulation")) throw UsageError("--formulation applies to coupled models (bodies, beams and contacts) only");
  if (model.bodies.empty()) return simulate_beams(model, options);
  if (options.adjust || !options.probes.empty())
    throw UsageError("--adjust and --probe apply to beam models only");
  return simulate_rigid(model, options, every);
}

}  // namespace mbfe::tool
