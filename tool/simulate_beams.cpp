// simulate_beams(): `mbfe simulate` for models with beams and no bodies.
//
// The model is integrated in mass-normalised modal coordinates (every mode;
// the same model as the nodal one, see runtime/damping/beam_ode.h), original
// or adjusted; rows are written in nodal coordinates: t, then the beam
// coordinates in contract order (<beam>_w<node>, <beam>_dw<node>, free DOFs
// only), or the --probe columns.
#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "tool/beam_probe.h"
#include "tool/cli_args.h"
#include "tool/csv_output.h"
#include "runtime/damping/beam_model.h"
#include "runtime/integrators/integrator.h"
#include "runtime/integrators/simulation_driver.h"
#include "tool/simulate_options.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::tool {

namespace {

/// -1.3702e5 (5 significant digits, no '+' or leading zeros in the exponent).
std::string short_sci(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.4e", v);
  std::string s = buf;
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mant = s.substr(0, e);
  int exp = std::stoi(s.substr(e + 1));
  return mant + "e" + std::to_string(exp);
}

/// -1.3702e5, or -3.6817e0 + 7.3542e1i for a complex one.
std::string eigenvalue_text(std::complex<double> l) {
  std::string s = short_sci(l.real());
  if (l.imag() != 0.0) s += (l.imag() > 0 ? " + " : " - ") + short_sci(std::abs(l.imag())) + "i";
  return s;
}

struct Probe {
  std::string label;
  int offset = 0;  // of the beam in the model's q
  runtime::BeamPointWeights weights;
};

std::vector<Probe> parse_probes(const std::vector<std::string>& specs, const ir::Model& model,
                                const runtime::BeamModel& beams) {
  std::vector<Probe> out;
  auto system_of = [&](int i) -> const runtime::BeamSystem& { return beams.beams[i].system; };
  for (BeamProbe& b : parse_beam_probes(specs, model, system_of))
    out.push_back({std::move(b.label), beams.beams[b.beam].offset, b.weights});
  return out;
}

}  // namespace

int simulate_beams(const ir::Model& model, const SimulateOptions& options) {
  if (model.beams.empty()) throw UsageError("model '" + model.name + "' has neither bodies nor beams");
  runtime::IntegratorSpec integrator;
  try {
    integrator = runtime::parse_integrator(options.integrator);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (options.rho_inf) integrator.rho_inf = *options.rho_inf;

  runtime::BeamModel beams;
  try {
    beams = runtime::analyse_beams(model);
  } catch (const std::invalid_argument& e) {
    std::cerr << "mbfe simulate: " << model.source_path << ": " << e.what() << "\n";
    return 2;
  }
  // --adjust on needs an adjustment block; absent = on when some beam has one.
  const bool adjust = options.adjust.value_or(beams.any_adjustment);
  if (adjust && !beams.any_adjustment)
    throw UsageError("--adjust on: no beam of '" + model.name +
                     "' has an `adjustment:` block (e.g. adjustment: {omega_limit: 1.0e5, margin: 0.1})");

  auto ode = runtime::modal_beam_ode(beams, adjust);
  const int n = beams.dof;
  const Eigen::VectorXd y_static = runtime::modal_static_state(beams, adjust, *ode);
  const std::vector<Probe> probes = parse_probes(options.probes, model, beams);

  CsvOutput csv(options.out.value_or(""));
  std::vector<std::string> columns{"t"};
  if (probes.empty()) {
    for (const auto& b : beams.beams)
      for (int f : b.system.free_dof)
        columns.push_back(b.system.name + (f % 2 == 0 ? "_w" : "_dw") + std::to_string(f / 2));
  } else {
    for (const Probe& p : probes) columns.push_back(p.label);
  }
  csv.header(columns);
  std::vector<double> row(columns.size());
  Eigen::VectorXd q(n);
  // A probe is a fixed linear map of q = Phi eta: fold it into one row of
  // modal weights, so a probe column costs n flops per row, not n^2.
  Eigen::MatrixXd probe_rows(probes.size(), n);
  for (std::size_t k = 0; k < probes.size(); ++k) {
    probe_rows.row(k).setZero();
    for (int e = 0; e < 4; ++e)
      if (probes[k].weights.free_index[e] >= 0)
        probe_rows.row(k) += probes[k].weights.w[e] * ode->phi().row(probes[k].offset + probes[k].weights.free_index[e]);
  }
  Eigen::VectorXd probe_values(probes.size());

  runtime::SimulationOptions run;
  run.step = options.step;
  run.t_end = options.t_end;
  run.every = options.every;
  run.quiet = options.quiet;
  run.reference_norm = y_static.norm();
  const Eigen::VectorXd y0 = Eigen::VectorXd::Zero(2 * n);  // beams start at rest, undeformed
  runtime::SimulationResult result;
  try {
    result = runtime::run_simulation(*ode, integrator, y0, run, [&](double t, const Eigen::VectorXd& y) {
      row[0] = t;
      if (probes.empty()) {
        ode->positions(y, q);
        for (int i = 0; i < n; ++i) row[1 + i] = q[i];
      } else {
        probe_values.noalias() = probe_rows * y.head(n);
        for (std::size_t k = 0; k < probes.size(); ++k) row[1 + k] = probe_values[k];
      }
      csv.row(row.data(), row.size());
    });
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  csv.flush();
  const std::string where = options.out ? " to " + *options.out : std::string();
  switch (result.status) {
    case runtime::SimulationStatus::kCompleted:
      if (!options.quiet)
        std::cerr << "mbfe: " << model.name << " (" << (adjust ? "adjusted" : "original") << " damping): "
                  << result.steps << " " << result.integrator << " steps of " << result.step << " s to t = "
                  << result.t << " s in " << result.wall_seconds << " s; " << csv.rows() << " rows written"
                  << where << "\n";
      return 0;
    case runtime::SimulationStatus::kDiverged: {
      const auto& spectrum = adjust ? beams.adjusted : beams.original;
      const runtime::StepLimit lim = runtime::stable_step(integrator, spectrum.eigenvalues);
      std::ostringstream msg;
      msg.precision(5);
      msg << "diverged at t = " << result.t + result.step << " s: step " << result.step;
      if (lim.kind == runtime::StepLimit::Kind::kFinite && result.step > lim.h) {
        msg << " exceeds " << result.integrator << "'s stable limit " << lim.text() << " (fastest eigenvalue "
            << eigenvalue_text(lim.critical) << ")";
      } else if (lim.kind == runtime::StepLimit::Kind::kNone) {
        msg << ": " << result.integrator << " has no stable step for this model (eigenvalue "
            << eigenvalue_text(lim.critical) << ")";
      } else {
        msg << " with " << result.integrator << " (stable limit " << lim.text() << "): |y| = " << result.norm
            << " exceeded the bound " << result.bound;
      }
      std::cerr << "mbfe simulate: " << msg.str() << "; " << (adjust ? "adjusted" : "original") << " model; "
                << csv.rows() << " rows written" << where << " up to there\n";
      return 3;
    }
    case runtime::SimulationStatus::kInterrupted:
      std::cerr << "mbfe simulate: interrupted at t = " << result.t << " s; " << csv.rows() << " rows written"
                << where << "\n";
      return 3;
    case runtime::SimulationStatus::kFailed:
      std::cerr << "mbfe simulate: failed at t = " << result.t << " s: " << result.message << "; " << csv.rows()
                << " rows written" << where << " up to there\n";
      return 3;
  }
  return 1;
}

}  // namespace mbfe::tool
