// `mbfe modal MODEL.yaml [--json] [--all] [--beam NAME] [--modes K]`:
// modal analysis of each beam and the state-space eigenvalues of eq (28),
// printed as the paper's Table 1 (text) or as JSON.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "runtime/coupled/tangent_spectrum.h"
#include "runtime/simulation/assembled_model.h"
#include "frontend/parse_model.h"
#include "runtime/damping/beam_model.h"
#include "runtime/errors/invalid_input.h"
#include "tool/cli_args.h"
#include "tool/commands.h"
#include "tool/file_checks.h"
#include "tool/model_warnings_notice.h"
#include "api/json_text.h"
#include "tool/linearization_notice.h"
#include "tool/modal_report.h"
#include "tool/plot_spectrum.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::tool {

namespace {

constexpr const char* kHelp =
    R"(Usage: mbfe modal MODEL.yaml [--json] [--all] [--beam NAME] [--modes K] [--set PATH=VALUE ...]

Modal analysis of every beam of the model (K Phi = M Phi Omega^2, mass-normalised)
and the eigenvalues of its state matrix B = [[0, I], [-M^-1 K, -M^-1 C]] (eq (28)),
sorted by modulus: the paper's Table 1.

Columns of the table (a conjugate pair is one row, numbered by its first index):
  #                position in the list sorted by modulus (1 = slowest)
  real, imaginary  the eigenvalue in 1/s ("+-" marks a conjugate pair)
  f damped [Hz]    |Im| / 2 pi
  zeta [%]         damping ratio -Re / |lambda|
  f undamped [Hz]  |lambda| / 2 pi (the mode's natural frequency)
The summary line gives the DOF, the number of oscillatory pairs, the fastest
eigenvalue and forward Euler's stable-step limit h_max = min -2 Re / |lambda|^2.

Options:
  --json        print {"beams": [{"name", "dof", "natural_frequencies_rad_s",
                "original": {"eigenvalues": [[re, im], ...], "oscillatory_pairs",
                "h_max": {"forward_euler"}}}], "warnings": [...]} instead of the
                table ("warnings": the lines about likely unit mistakes also
                printed on stderr, docs/robustness.md)
  --all         print every row (default: the first and last five, "..." between)
  --beam NAME   only this beam
  --modes K     modes found by the sparse path for beams above 2000 DOF (default 20)
  --set PATH=VALUE  replace a value of the file first (repeatable; as for
                mbfe simulate: --set beams.deck.section.inertia=0.3)
  --plot FILE.png  draw the original and adjusted eigenvalues in the complex
                plane (-Re on a log axis) with forward Euler's stability
                region for the step --step (needs gnuplot); a coupled model
                draws its coupled spectrum; eigenvalues with Re >= 0 sit on
                the marked left edge
  --step H      step for --plot's stability region (default: forward Euler's
                limit of the adjusted model, or of the original without one)

A coupled model (bodies, beams and contacts) also gets the spectrum of its
linearised, partitioned system at the initial state (after the beams; in JSON
a "coupled" block with "original" and "adjusted" of the same form).

A beam with an `adjustment:` block (see docs/damping-adjustment.md) also gets
the adjusted spectrum: printed beside the original (the paper's Table 1, right
half) and, in JSON, an "adjusted" block of the same form as "original" plus
"policy", "omega_limit", "adjusted_modes" and "floored_modes" (policy mass:
also "modal_masses", one per mode, 1 where the mode is kept). A beam adjusted
with the beams linked to it (scope: joined) has no adjusted spectrum of its own
(JSON: {"scope": "joined"}); the coupled spectrum shows its structure's.

Example:
  mbfe modal models/paper_beam.yaml
  mbfe modal models/paper_beam.yaml --json --beam beam1
  mbfe modal models/paper_beam.yaml --plot spectrum.png --step 1.4e-5
)";

}  // namespace

int cmd_modal(const Args& args) {
  const ParsedArgs parsed(args, {"beam", "modes", "plot", "step", "set"}, {"json", "all", "help"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1) {
    throw UsageError("expected one MODEL.yaml, got " +
                     std::to_string(parsed.positional().size()) + " arguments (see --help)");
  }
  runtime::BeamAnalysisOptions options;
  options.sparse_modes = 20;  // large beams: the lowest modes
  if (const auto k = parsed.number("modes")) {
    if (*k < 1 || *k != static_cast<int>(*k)) {
      throw UsageError("--modes: expected a whole number >= 1, got " + *parsed.value("modes"));
    }
    options.sparse_modes = static_cast<int>(*k);
  }
  const std::string& path = parsed.positional()[0];
  // The picture never lands on the model or a file it reads (gnuplot would
  // write over it).
  const auto plot_file = parsed.value("plot");
  if (plot_file && !plot_file->empty()) check_output_file(*plot_file, "--plot", {path});
  const ir::ModelOverrides overrides = model_overrides(parsed);
  const ir::Model m = frontend::load_model_file(path, {}, overrides);
  if (plot_file && !plot_file->empty()) check_output_file(*plot_file, "--plot", model_inputs(path, m));
  const std::vector<std::string> warnings = announce_model_warnings(m);
  if (m.beams.empty()) {
    std::cerr << "mbfe modal: " << path << ": model '" << m.name
              << "' has no beams; modal analysis needs at least one (see `beams:`)\n";
    return 2;
  }
  std::vector<const ir::Beam*> chosen;
  const auto beam_name = parsed.value("beam");
  for (const ir::Beam& b : m.beams) {
    if (!beam_name || b.name == *beam_name) chosen.push_back(&b);
  }
  if (chosen.empty()) {
    std::string names;
    for (const ir::Beam& b : m.beams) names += (names.empty() ? "" : ", ") + b.name;
    throw UsageError("--beam: no beam named '" + *beam_name + "' in " + path + " (beams: " +
                     names + ")");
  }

  std::vector<runtime::BeamPart> results;
  try {
    for (const ir::Beam* b : chosen) results.push_back(runtime::analyse_beam(*b, m.gravity, options));
  } catch (const std::invalid_argument& e) {
    std::cerr << "mbfe modal: " << path << ": " << e.what() << "\n";
    return 2;
  }
  const auto step = parsed.number("step");
  if (step && !(*step > 0)) throw UsageError("--step must be > 0 s");
  if (step && !parsed.has("plot")) throw UsageError("--step goes with --plot FILE.png");
  // A coupled model (bodies + beams): also the linearised, partitioned system
  // at the initial state (runtime/coupled/linearization.h), original and adjusted.
  bool coupled = !m.bodies.empty() && !beam_name;
  runtime::ModelSpectrum coupled_original_model, coupled_adjusted_model;
  bool coupled_any_adjustment = false;
  std::string coupled_skipped;  // why the coupled spectrum is not shown (a model too large for it)
  if (coupled) {
    for (const ir::Beam& b : m.beams) coupled_any_adjustment = coupled_any_adjustment || b.adjustment.active();
    LoadOptions load;
    load.overrides = overrides;
    const Model model = Model::load(path, load);
    const int coordinates = static_cast<int>(m.bodies.size()) + model.assembled().beams().dof;
    if (coordinates <= runtime::kMaxLinearizedCoordinates && coordinates > kLinearizationNoticeCoordinates &&
        !runtime::linearized_from_tangents(model.assembled()))
      std::cerr << linearization_notice("modal", coordinates, coupled_any_adjustment ? 2 : 1);
    try {
      coupled_original_model = model.spectrum(false);
      if (coupled_any_adjustment) coupled_adjusted_model = model.spectrum(true);
    } catch (const runtime::InvalidInput& e) {
      // The beams' spectra are still worth printing.
      coupled_skipped = e.what();
      coupled = false;
    }
  }
  const runtime::StateSpectrum& coupled_original = coupled_original_model.full;
  const runtime::StateSpectrum& coupled_adjusted = coupled_adjusted_model.full;

  if (const auto plot = parsed.value("plot")) {
    if (plot->empty()) throw UsageError("--plot needs a file name");
    SpectrumPlot picture;
    double h = 0.0;
    if (coupled) {
      // The coupled system is what a run steps: its spectrum and its limit,
      // not the beams' alone.
      picture.title = "model '" + m.name + "', coupled system at the initial state";
      picture.series.push_back({"original", coupled_original.eigenvalues});
      if (coupled_any_adjustment) picture.series.push_back({"adjusted", coupled_adjusted.eigenvalues});
      const runtime::ModelSpectrum& limiting = coupled_any_adjustment ? coupled_adjusted_model : coupled_original_model;
      const runtime::StepLimit fe =
          runtime::stable_step(runtime::parse_integrator("forward_euler"), limiting.limiting.eigenvalues);
      if (fe.kind == runtime::StepLimit::Kind::kFinite) h = fe.h;
    } else {
      picture.title = "model '" + m.name + "'";
      for (std::size_t i = 0; i < results.size(); ++i) {
        const std::string prefix = results.size() > 1 ? results[i].system.name + " " : "";
        picture.series.push_back({prefix + "original", results[i].original_spectrum.eigenvalues});
        if (results[i].has_adjustment)
          picture.series.push_back({prefix + "adjusted", results[i].adjusted_spectrum.eigenvalues});
      }
      // Default step: the forward-Euler limit of the (first) adjusted spectrum.
      for (std::size_t i = 0; i < results.size() && h == 0.0; ++i)
        h = results[i].has_adjustment ? results[i].adjusted_spectrum.h_max_forward_euler : 0.0;
      if (h == 0.0 || !std::isfinite(h)) h = results.front().original_spectrum.h_max_forward_euler;
    }
    if (!std::isfinite(h)) h = 0.0;
    picture.step = step.value_or(h);
    const int status = draw_spectrum_plot(picture, *plot);
    if (status != 0) return status;
  }

  if (parsed.has("json")) {
    nlohmann::json root;
    if (coupled) {
      nlohmann::json c;
      c["states"] = coupled_original.eigenvalues.size();
      c["original"] = spectrum_json(coupled_original);
      c["adjusted"] = coupled_any_adjustment ? spectrum_json(coupled_adjusted) : nlohmann::json(nullptr);
      root["coupled"] = std::move(c);
    }
    root["beams"] = nlohmann::json::array();
    for (std::size_t i = 0; i < results.size(); ++i) {
      nlohmann::json beam = beam_json(results[i]);
      add_adjusted_json(beam, *chosen[i], results[i]);
      root["beams"].push_back(std::move(beam));
    }
    root["warnings"] = warnings_json(warnings);
    std::cout << json_text(root, 2) << "\n";
    return 0;
  }
  for (size_t i = 0; i < results.size(); ++i) {
    if (i > 0) std::cout << "\n";
    print_beam_text(std::cout, *chosen[i], results[i], parsed.has("all"));
  }
  if (coupled) {
    const int dof = coupled_original_model.coordinates;
    const std::string ends = std::to_string(runtime::kFastestEigenvalues) + " fastest and " +
                             std::to_string(runtime::kSlowestEigenvalues) + " slowest eigenvalues, by Arnoldi";
    std::cout << "\ncoupled system '" << m.name << "': linearised, partitioned (eqs (16)-(17)) at the initial "
              << "state; the contacts couple the beams to the bodies\n";
    std::cout << "original (Rayleigh)\n";
    for (const std::string& line : spectrum_table_lines(coupled_original, parsed.has("all"))) std::cout << line << "\n";
    // The limits from the eigenvalues `mbfe stability` takes (growth away
    // from equilibrium left out, and said).
    auto growing_note = [](const runtime::ModelSpectrum& sp) {
      return sp.growing > 0 ? "; " + std::to_string(sp.growing) +
                                  " eigenvalues with Re > 0 (the motion leaves the initial state) left out of h_max"
                            : std::string();
    };
    std::cout << "summary: " << spectrum_summary(coupled_original_model.limiting, dof, ends)
              << growing_note(coupled_original_model) << "\n";
    if (coupled_any_adjustment) {
      std::cout << "adjusted\n";
      for (const std::string& line : spectrum_table_lines(coupled_adjusted, parsed.has("all")))
        std::cout << line << "\n";
      std::cout << "summary: " << spectrum_summary(coupled_adjusted_model.limiting, dof, ends)
                << growing_note(coupled_adjusted_model) << "\n";
    }
  }
  if (!coupled_skipped.empty())
    std::cerr << "mbfe modal: the coupled system's spectrum is left out: " << coupled_skipped << "\n";
  return 0;
}

}  // namespace mbfe::tool
