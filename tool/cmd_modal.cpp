// `mbfe modal MODEL.yaml [--json] [--all] [--beam NAME] [--modes K]`:
// modal analysis of each beam and the state-space eigenvalues of eq (28),
// printed as the paper's Table 1 (text) or as the JSON contract of issue 3.
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_args.h"
#include "commands.h"
#include "modal_report.h"
#include "model/parse_model.h"

namespace mbfe::tool {

namespace {

constexpr const char* kHelp = R"(Usage: mbfe modal MODEL.yaml [--json] [--all] [--beam NAME] [--modes K]

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
                "h_max": {"forward_euler"}}}]} instead of the table
  --all         print every row (default: the first and last five, "..." between)
  --beam NAME   only this beam
  --modes K     modes found by the sparse path for beams above 2000 DOF (default 20)

Example:
  mbfe modal models/paper_beam.yaml
  mbfe modal models/paper_beam.yaml --json --beam beam1
)";

/// The JSON of one beam; an "adjusted" block goes next to "original".
nlohmann::json beam_json(const BeamModalResult& r) {
  nlohmann::json omega = nlohmann::json::array();
  for (Eigen::Index j = 0; j < r.basis.omega.size(); ++j) omega.push_back(r.basis.omega[j]);
  nlohmann::json beam;
  beam["name"] = r.name;
  beam["dof"] = r.system.M.rows();
  beam["modal_path"] = r.dense ? "dense" : "sparse";
  beam["natural_frequencies_rad_s"] = std::move(omega);
  beam["original"] = spectrum_json(r.original);
  return beam;
}

void print_beam_text(std::ostream& out, const BeamModalResult& r, bool all) {
  const int dof = static_cast<int>(r.system.M.rows());
  out << "beam '" << r.name << "': " << dof << " DOF, Rayleigh alpha = " << r.system.rayleigh_alpha
      << " 1/s, beta = " << r.system.rayleigh_beta << " s ("
      << (r.dense ? "dense modal analysis, every mode"
                  : "sparse Lanczos, lowest " + std::to_string(r.basis.omega.size()) + " modes")
      << ")\n";
  out << "state-space eigenvalues of eq (28), sorted by modulus (the paper's Table 1):\n";
  for (const std::string& line : spectrum_table_lines(r.original, all)) out << line << "\n";
  out << "summary: " << spectrum_summary(r.original, dof) << "\n";
}

}  // namespace

int cmd_modal(const Args& args) {
  const ParsedArgs parsed(args, {"beam", "modes"}, {"json", "all", "help"});
  if (parsed.has("help")) {
    std::cout << kHelp;
    return 0;
  }
  if (parsed.positional().size() != 1) {
    throw UsageError("expected one MODEL.yaml, got " +
                     std::to_string(parsed.positional().size()) + " arguments (see --help)");
  }
  BeamModalOptions options;
  if (const auto k = parsed.number("modes")) {
    if (*k < 1 || *k != static_cast<int>(*k)) {
      throw UsageError("--modes: expected a whole number >= 1, got " + *parsed.value("modes"));
    }
    options.sparse_modes = static_cast<int>(*k);
  }
  const std::string& path = parsed.positional()[0];
  const model::Model m = model::load_model_file(path);
  if (m.beams.empty()) {
    std::cerr << "mbfe modal: " << path << ": model '" << m.name
              << "' has no beams; modal analysis needs at least one (see `beams:`)\n";
    return 2;
  }
  std::vector<const model::Beam*> chosen;
  const auto beam_name = parsed.value("beam");
  for (const model::Beam& b : m.beams) {
    if (!beam_name || b.name == *beam_name) chosen.push_back(&b);
  }
  if (chosen.empty()) {
    std::string names;
    for (const model::Beam& b : m.beams) names += (names.empty() ? "" : ", ") + b.name;
    throw UsageError("--beam: no beam named '" + *beam_name + "' in " + path + " (beams: " +
                     names + ")");
  }

  std::vector<BeamModalResult> results;
  try {
    for (const model::Beam* b : chosen) results.push_back(analyse_beam(*b, m.gravity, options));
  } catch (const std::invalid_argument& e) {
    std::cerr << "mbfe modal: " << path << ": " << e.what() << "\n";
    return 2;
  }

  if (parsed.has("json")) {
    nlohmann::json root;
    root["beams"] = nlohmann::json::array();
    for (const BeamModalResult& r : results) root["beams"].push_back(beam_json(r));
    std::cout << root.dump(2) << "\n";
    return 0;
  }
  for (size_t i = 0; i < results.size(); ++i) {
    if (i > 0) std::cout << "\n";
    print_beam_text(std::cout, results[i], parsed.has("all"));
  }
  return 0;
}

}  // namespace mbfe::tool
