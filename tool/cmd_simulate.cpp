// mbfe simulate MODEL.yaml [--integrator NAME] [--step H] [--t-end T] [--out FILE.csv] ...
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "api/mbfe.h"
#include "api/model_warnings.h"
#include "api/results_output.h"
#include "api/run_record.h"
#include "api/vtk_animation.h"
#include "runtime/simulation/simulate.h"
#include "tool/adjustment_check.h"
#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/file_checks.h"
#include "tool/interrupt_guard.h"
#include "tool/progress_line.h"

namespace mbfe::tool {

namespace {

constexpr const char* kHelp = R"(Usage: mbfe simulate MODEL.yaml [options]

Integrates the model in time and writes a CSV: for rigid models the columns
are t,<q names>,<q names>_dot (coordinates named by their bodies, in model
order); for beam models t and the beam coordinates (see mbfe modal --help) or
the --probe columns; for coupled models (bodies, beams and contacts) t, the
rigid coordinates, the beam coordinates (or the --probe columns), their rates
(_dot), the contact forces lambda_<contact> (slider_pin) and
lambda_<contact>_1/_2 (pin: along and across the beam), N, phi_abs, the
largest constraint residual |Phi| in m, force_<contact> of each slider_spring
(N, compression positive), deflection_<contact>, the beam's deflection under
its point (m, 0 off the beam), and <body>_drive, the force or torque a driven joint
(joint.motion) exerts. Driven coordinates hold their motion's values. Flags
override the model's `simulation:` block.

Options:
  --integrator NAME  forward_euler, backward_euler, explicit_midpoint, trapezoid,
                     rk4, generalized_alpha (beams, coupled), ab2, bdf2,
                     lmm:alpha=a0,..,ak:beta=b0,..,bk
  --step H           step in s (one longer than the run is shortened to the
                     run; more than 2^53 steps are refused)
  --t-end T          end time in s
  --out FILE.csv     output file (default: standard output); FILE.npy writes a
                     NumPy array (rows x columns, numpy.load reads it) instead;
                     FILE.csv.json / FILE.npy.json beside it says what it holds:
                     model and SHA-256, integrator, step, damping variant, each
                     column's name and unit, how the run ended (not beside
                     a device such as /dev/null)
  --every N          write every N-th step (default: at most about 10000 rows)
  --adjust on|off    beam and coupled models: use the modal adjustment of
                     damping (default: on when a beam has an adjustment block)
  --probe BEAM@S     beam and coupled models: displacement at S m along BEAM
                     (several as a comma-separated list); BEAM@S:acc its
                     acceleration (m/s^2), BODY:acc a body's joint coordinate
                     acceleration (coupled models; m/s^2 or rad/s^2), both as
                     columns at the end of a coupled model's row
  --formulation F    coupled models and closed loops: partitioned (default;
                     eqs (16)-(17), |Phi| closed by Newton at every step) or
                     augmented (multipliers; a cross-check: |Phi| drifts in
                     coupled models, loops are projected after each step)
  --rho-inf R        generalized_alpha spectral radius at infinity (0..1)
                     (coupled models: generalized_alpha, trapezoid, backward_euler
                     and bdf2 run the original model in index-3 form with a
                     modified Newton iteration; docs/implicit-integration.md)
  --start static     start from the static equilibrium at t = 0 of everything
                     not driven (as `initial: {static: true}`); --start given
                     starts from `initial:` as written
  --vtk DIR          also write an animation ParaView opens: DIR/<model>.pvd and
                     its frames (beams' deformed axes, bodies through their
                     points, spring contact forces; docs/animation.md)
  --vtk-scale S      deflections drawn S times enlarged (default 1)
  --vtk-frames N     at most N frames, evenly spaced in time (default 200,
                     at most 10000)
  --check-adjustment T
                     after an adjusted run, run its first T s again with the
                     original model (generalized_alpha, at least 2000 steps,
                     fine enough for the fastest frequency the run keeps) and
                     report how far the contact forces and displacements are
                     from it, and how far that reference moves at twice its
                     step (stderr, and "adjustment_check" in the sidecar);
                     docs/damping-adjustment.md
  --set PATH=VALUE   replace a value of the model file before it is read
                     (repeatable): PATH as a sweep's vary paths, list items by
                     their name: (loads.front_susp.stiffness=2e6,
                     beams.bridge.section.inertia=0.3); errors point into the
                     file and name the --set
  --strict           an initial state that violates the contacts or the loops
                     is an error (exit 2) instead of being projected onto
                     them; so is an initial.q quaternion off unit length
                     (instead of being scaled to it), and a body that fell
                     through space (no contact of it touched a beam and it
                     ended farther from the beams than the structure's size;
                     docs/robustness.md), after the run, its rows kept
  --quiet            no progress or cache messages on stderr

An output (--out, its sidecar, the --vtk folder and its files) that is the
model file or a file it reads (a profile table), a folder where a file goes
(or a file where the folder goes), or in a folder that does not exist is bad
input, refused before the solver is compiled.

Exit status: 0 done; 2 bad input; 3 the simulation diverged or failed part-way
(everything computed up to there is in the output, flushed).

Examples:
  mbfe simulate models/double_pendulum.yaml --integrator rk4 --step 1e-3 --t-end 2 --out pendulum.csv
  mbfe simulate models/paper_platform.yaml --integrator forward_euler --step 1.4e-5 --t-end 1 --out platform.csv
  mbfe simulate models/bridge_moving_mass.yaml --probe deck@10 --out crossing.csv
  mbfe simulate models/vehicle_bridge_30m.yaml --integrator rk4 --step 1e-3 --check-adjustment 0.2 --out v.csv
  mbfe simulate models/bridge_moving_mass.yaml --probe deck@10,deck@10:acc,wheel:acc --out acc.csv
  mbfe simulate models/bridge_moving_mass.yaml --set beams.deck.section.inertia=0.3 --out stiffer.csv
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

// The request of the model's `simulation:` block, the flags overriding it.
// Ranges (a step > 0, ...) are the runtime's to check: its errors name the
// request's fields, which main() says as these flags.
runtime::SimulationRequest request_of(const ParsedArgs& parsed, const Model& model) {
  runtime::SimulationRequest request = model.request();
  if (const auto integrator = parsed.value("integrator")) {
    try {
      request.integrator = runtime::parse_integrator(*integrator);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  if (const auto step = parsed.number("step")) request.step = *step;
  if (const auto t_end = parsed.number("t-end")) request.t_end = *t_end;
  if (const auto rho = parsed.number("rho-inf")) {
    if (*rho < 0 || *rho > 1) throw UsageError("--rho-inf must be in [0, 1]");
    request.integrator.rho_inf = *rho;
  }
  if (const auto adjust = parsed.value("adjust")) {
    if (*adjust != "on" && *adjust != "off") throw UsageError("--adjust takes on or off, got '" + *adjust + "'");
    request.adjust = *adjust == "on";
  }
  if (const auto probe = parsed.value("probe"))
    for (const std::string& text : split_commas(*probe)) request.probes.push_back(runtime::parse_probe(text));
  if (const auto every = parsed.number("every")) {
    if (*every < 1 || *every != static_cast<double>(static_cast<std::int64_t>(*every)))
      throw UsageError("--every must be a positive integer");
    request.every = static_cast<std::int64_t>(*every);
  }
  const std::string formulation = parsed.value("formulation").value_or("partitioned");
  if (formulation != "partitioned" && formulation != "augmented")
    throw UsageError("--formulation takes partitioned or augmented, got '" + formulation + "'");
  request.formulation = formulation == "augmented" ? runtime::CoupledFormulation::kAugmented
                                                   : runtime::CoupledFormulation::kPartitioned;
  if (const auto start = parsed.value("start")) {
    if (*start != "static" && *start != "given") throw UsageError("--start takes static or given, got '" + *start + "'");
    request.static_start = *start == "static";
  }
  request.strict = parsed.has("strict");
  return request;
}

/// Hands every call to two observers (the results file and the animation).
class TeeObserver : public runtime::SimulationObserver {
 public:
  TeeObserver(runtime::SimulationObserver& a, runtime::SimulationObserver& b) : a_(a), b_(b) {}
  void begin(const runtime::OutputLayout& layout) override {
    a_.begin(layout);
    b_.begin(layout);
  }
  void row(const runtime::OutputRow& row) override {
    a_.row(row);
    b_.row(row);
  }
  void notice(const std::string& text) override { a_.notice(text); }

 private:
  runtime::SimulationObserver& a_;
  runtime::SimulationObserver& b_;
};

/// "mbfe: contact 'tyre': 2 lift-offs, 0.0123 s off contact" per
/// slider_spring, and one line for the links that can go slack (a catenary
/// has dozens of droppers: each one's figures are in the record beside the
/// results).
void print_tallies(const runtime::SimulationReport& report, const std::optional<std::string>& out) {
  for (const runtime::SpringContactTally& c : report.springs)
    std::cerr << "mbfe: contact '" << c.name << "': " << c.lift_offs << " lift-off" << (c.lift_offs == 1 ? "" : "s")
              << ", " << c.time_off << " s off contact while over the beam\n";
  if (report.links.empty()) return;
  int went_slack = 0;
  const runtime::LinkSlackTally* longest = nullptr;
  const runtime::LinkSlackTally* most = nullptr;
  for (const runtime::LinkSlackTally& l : report.links) {
    if (l.time_slack > 0.0 || l.slackenings > 0) ++went_slack;
    if (!longest || l.time_slack > longest->time_slack) longest = &l;
    if (!most || l.slackenings > most->slackenings) most = &l;
  }
  std::cerr << "mbfe: links: " << went_slack << " of " << report.links.size() << " that can go slack did";
  if (went_slack > 0)
    std::cerr << " (longest '" << longest->name << "', " << longest->time_slack << " s in all; most often '"
              << most->name << "', " << most->slackenings << " time" << (most->slackenings == 1 ? "" : "s") << ")";
  std::cerr << (out ? "; each link in " + *out + ".json" : std::string()) << "\n";
}

}  // namespace

int cmd_simulate(const Args& args) {
  const ParsedArgs parsed(args, {"integrator", "step", "t-end", "out", "every", "adjust", "probe", "rho-inf", "formulation", "start",
                           "vtk", "vtk-scale", "vtk-frames", "check-adjustment", "set"},
                          {"help", "quiet", "strict"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1) throw UsageError("expected one model file (see --help)");
  const std::string& model_path = parsed.positional()[0];
  // Every output checked before the model is even read (never over the model
  // file, whatever the names; never into a missing folder or onto a folder),
  // and again once it is read against every file it read (profile tables),
  // before its solver is compiled.
  const auto out = parsed.value("out");
  const auto vtk_dir = parsed.value("vtk");
  const auto check_outputs = [&](const std::vector<std::string>& inputs, const ir::Model* read) {
    if (out && !out->empty()) {
      check_output_file(*out, "--out", inputs);
      check_output_file(*out + ".json", "--out (its sidecar)", inputs);
    }
    if (!vtk_dir) return;
    check_output_folder(*vtk_dir, "--vtk", inputs);
    if (!read) return;  // the collection is named after the model
    check_output_file((std::filesystem::path(*vtk_dir) / (read->name + ".pvd")).string(), "--vtk", inputs, true);
    const std::string frames_dir = (std::filesystem::path(*vtk_dir) / "frames").string();
    check_output_folder(frames_dir, "--vtk", inputs);
    check_folder_holds_no_input(frames_dir, "--vtk", inputs);
  };
  check_outputs({model_path}, nullptr);
  if (const auto probe = parsed.value("probe")) {
    const std::vector<std::string> labels = split_commas(*probe);
    for (std::size_t i = 0; i < labels.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (labels[i] == labels[j])
          throw UsageError("--probe: '" + labels[i] + "' is given twice; each probe is a column and needs a name of its own");
  }
  const double frames = parsed.number("vtk-frames").value_or(200.0);
  if (vtk_dir) {
    if (!(frames >= 1) || frames != std::floor(frames)) throw UsageError("--vtk-frames must be a positive whole number");
    if (frames > kMaxVtkFrames)
      throw UsageError("--vtk-frames: at most " + std::to_string(kMaxVtkFrames) + " frames (a file each), got " +
                       parsed.value("vtk-frames").value_or(""));
  } else if (parsed.has("vtk-scale") || parsed.has("vtk-frames")) {
    throw UsageError("--vtk-scale and --vtk-frames go with --vtk DIR");
  }
  LoadOptions load;
  load.quiet = parsed.has("quiet");
  load.overrides = model_overrides(parsed);
  load.on_read = [&](const ir::Model& read) { check_outputs(model_inputs(model_path, read), &read); };
  const Model model = Model::load(model_path, load);
  // Likely unit mistakes, before a run that may take long (and again in the sidecar).
  for (const std::string& w : model_warnings(model.ir())) std::cerr << w << "\n";
  runtime::SimulationRequest request = request_of(parsed, model);
  std::unique_ptr<VtkAnimation> vtk;
  if (vtk_dir) {
    const double scale = parsed.number("vtk-scale").value_or(1.0);
    request.state_in_rows = true;  // the frames need every coordinate
    vtk = std::make_unique<VtkAnimation>(model, *vtk_dir, scale, static_cast<int>(frames), request.t_end);
  }
  if (parsed.has("formulation") && model.kind() != runtime::ModelKind::kCoupled && model.ir().constraints.empty())
    throw UsageError("--formulation applies to coupled models (bodies, beams and contacts) and models with closed "
                     "loops (constraints:) only");
  // What the model file alone rules out, before seconds of assembly; then a
  // beam the analysis refuses is bad input before the output file is opened.
  runtime::check_request_early(model.ir(), request);
  model.assembled_for(request.adjust);
  std::optional<double> check_until;
  if (parsed.has("check-adjustment")) {
    const double t = parsed.number("check-adjustment").value_or(NAN);
    if (!(t > 0.0) || !(t <= request.t_end)) {
      std::ostringstream text;
      text << "--check-adjustment: expected a time in s in (0, t_end = " << request.t_end << "], got '"
           << parsed.value("check-adjustment").value_or("") << "'";
      throw UsageError(text.str());
    }
    if (!model.assembled().resolve_adjusted(request.adjust))
      throw UsageError("--check-adjustment compares an adjusted run with the original model; this run is not "
                       "adjusted (no active adjustment block, or --adjust off)");
    check_until = t;
  }

  const bool quiet = parsed.has("quiet");
  ResultsOutput csv(out.value_or(""));
  ResultsObserver results(csv);
  // With --check-adjustment the rows up to T are also kept for the comparison.
  RowsUpTo kept(check_until.value_or(0.0));
  TeeObserver results_and_kept(results, kept);
  runtime::SimulationObserver& observer_used = check_until ? static_cast<runtime::SimulationObserver&>(results_and_kept)
                                                           : static_cast<runtime::SimulationObserver&>(results);
  runtime::SimulationReport report;
  // Ctrl-C, SIGTERM, SIGHUP: the run (or the adjustment check after it) stops
  // before its next step, whole rows written and the record beside them says
  // so (exit status 3). One guard for both, so that no signal between them
  // finds the default handler and loses the record.
  const InterruptGuard interrupts;
  {
    ProgressLine progress(!quiet, request.t_end);
    const runtime::StepMonitor keep_going = [&](double t, std::int64_t steps) {
      progress.update(t, steps);
      return !InterruptGuard::interrupted();
    };
    try {
      if (vtk) {
        TeeObserver both(observer_used, *vtk);
        report = model.simulate(request, both, keep_going);
      } else {
        report = model.simulate(request, observer_used, keep_going);
      }
    } catch (...) {
      progress.finish();
      csv.discard_if_empty();  // bad input found on the way (a static start that fails): no file left
      throw;
    }
    progress.finish();
  }
  csv.flush();
  if (vtk) {
    vtk->finish();
    if (!quiet)
      std::cerr << "mbfe: " << vtk->frames_written() << " animation frames in " << *parsed.value("vtk") << "/"
                << model.ir().name << ".pvd\n";
  }
  nlohmann::json record = run_record(model, request, report, results.layout(), csv.rows());
  record["set"] = parsed.values("set");  // the --set values the run's model has, "PATH=VALUE" each, in order
  for (const std::string& w : run_warnings(model.ir(), report)) std::cerr << "mbfe: warning: " << w << "\n";
  bool check_interrupted = false;
  if (check_until && report.message.empty()) {
    // The check runs the original model, which can take longer than the run:
    // a signal during it ends the check, and the run's rows and record stay.
    const runtime::StepMonitor keep_going = [](double, std::int64_t) { return !InterruptGuard::interrupted(); };
    const AdjustmentCheck check = check_adjustment(model, request, report, kept, *check_until, keep_going);
    record["adjustment_check"] = adjustment_check_json(check);
    check_interrupted = check.interrupted;
    std::cerr << "mbfe: " << adjustment_check_line(check) << "\n";
  }
  if (out) write_run_record(*out, record);
  if (check_interrupted) {
    std::cerr << "mbfe simulate: the adjustment check was interrupted; the run's " << csv.rows() << " rows"
              << (out ? " and its record are written to " + *out : std::string(" are written")) << "\n";
    return 3;
  }
  const runtime::SimulationResult& run = report.run;
  const std::string where = out ? " to " + *out : std::string();
  if (parsed.has("strict") && report.message.empty())
    if (const std::vector<FreeFall> falls = free_falls(model.ir(), report); !falls.empty()) {
      std::cerr << "mbfe simulate: --strict: body '" << falls.front().body
                << "' fell through space (the warning above says where); " << csv.rows() << " rows written"
                << where << "\n";
      return 2;
    }
  const std::string variant = report.variant.empty() ? "" : " (" + report.variant + ")";
  if (report.message.empty()) {
    if (!quiet)
      std::cerr << "mbfe: " << model.ir().name << variant << ": " << run.steps << " " << run.integrator
                << " steps of " << run.step << " s to t = " << run.t << " s in " << run.wall_seconds << " s; "
                << csv.rows() << " rows written" << where << "\n";
    if (!quiet && run.newton.iterations > 0)
      std::cerr << "mbfe: Newton: " << run.newton.iterations << " iterations ("
                << static_cast<double>(run.newton.iterations) / std::max<long>(run.newton.steps, 1)
                << " per step), " << run.newton.factorizations << " factorisations of the iteration matrix\n";
    if (!quiet) print_tallies(report, out);
    return 0;
  }
  std::cerr << "mbfe simulate: " << report.message << (report.variant.empty() ? "" : "; " + report.variant) << "; "
            << csv.rows() << " rows written" << where
            << (run.status == runtime::SimulationStatus::kInterrupted ? "" : " up to there") << "\n";
  print_tallies(report, out);
  return 3;
}

}  // namespace mbfe::tool
