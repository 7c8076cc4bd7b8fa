// simulate_coupled(): `mbfe simulate` for coupled models (bodies + beams +
// contacts), eqs (14)-(17) of the paper.
//
// The partitioned formulation (default) integrates y = [u; q_c; u'; q_c'] with
// the dependent rigid coordinates closed by Newton at every evaluation; the
// augmented one y = [q_b; q_c; q_b'; q_c'] with the multipliers (a
// cross-check; |Phi| drifts). Rows: t, the rigid coordinates (model order), the
// beam coordinates in contract order (or the --probe columns), their rates
// (_dot), the multipliers (lambda_<contact>, lambda_<contact>_1/_2 for a pin:
// N, stacked like the constraint rows of `mbfe eval`) and phi_abs = max |Phi|.
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tool/beam_probe.h"
#include "tool/cli_args.h"
#include "tool/coupled_model.h"
#include "tool/csv_output.h"
#include "runtime/integrators/integrator.h"
#include "runtime/integrators/simulation_driver.h"
#include "runtime/multibody/linearization.h"
#include "runtime/multibody/multibody_errors.h"
#include "tool/simulate_options.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::tool {

namespace {

struct Probe {
  std::string label;
  int offset = 0;  // of the beam in the full q
  runtime::BeamPointWeights weights;
};

std::vector<Probe> parse_probes(const std::vector<std::string>& specs, const ir::Model& model,
                                const CoupledModel& cm) {
  const int nb = cm.dynamics->nb();
  std::vector<Probe> out;
  auto system_of = [&](int i) -> const runtime::BeamSystem& { return cm.beams.beams[i].system; };
  for (BeamProbe& b : parse_beam_probes(specs, model, system_of))
    out.push_back({std::move(b.label), nb + cm.dynamics->constraints().beam_offset(b.beam), b.weights});
  return out;
}

double probe_value(const Probe& p, const Eigen::VectorXd& x) {
  double v = 0.0;
  for (int e = 0; e < 4; ++e)
    if (p.weights.free_index[e] >= 0) v += p.weights.w[e] * x[p.offset + p.weights.free_index[e]];
  return v;
}

std::string short_sci(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.4e", v);
  std::string s = buf;
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  return s.substr(0, e) + "e" + std::to_string(std::stoi(s.substr(e + 1)));
}

std::string eigenvalue_text(std::complex<double> l) {
  std::string s = short_sci(l.real());
  if (l.imag() != 0.0) s += (l.imag() > 0 ? " + " : " - ") + short_sci(std::abs(l.imag())) + "i";
  return s;
}

}  // namespace

std::vector<std::string> coupled_multiplier_names(const ir::Model& model) {
  std::vector<std::string> out;
  for (const ir::Contact& c : model.contacts) {
    if (c.type == ir::ContactType::kPin) {
      out.push_back("lambda_" + c.name + "_1");
      out.push_back("lambda_" + c.name + "_2");
    } else {
      out.push_back("lambda_" + c.name);
    }
  }
  return out;
}

int simulate_coupled(const ir::Model& model, const SimulateOptions& options, bool augmented) {
  runtime::IntegratorSpec integrator;
  try {
    integrator = runtime::parse_integrator(options.integrator);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  if (integrator.kind == runtime::IntegratorKind::kGeneralizedAlpha)
    throw UsageError("generalized_alpha needs a linear second-order (beam) model; for coupled models use "
                     "forward_euler, rk4, trapezoid, backward_euler, ...");
  if (options.rho_inf) integrator.rho_inf = *options.rho_inf;

  CoupledModel cm;
  try {
    cm = load_coupled(model, options.adjust, options.quiet);
  } catch (const std::invalid_argument& e) {
    std::cerr << "mbfe simulate: " << model.source_path << ": " << e.what() << "\n";
    return 2;
  }
  const int nb = cm.dynamics->nb();
  const int n = cm.dynamics->n();
  const int m = cm.dynamics->m();
  const std::vector<Probe> probes = parse_probes(options.probes, model, cm);

  std::unique_ptr<runtime::CoupledSystem> system;
  if (augmented)
    system = std::make_unique<runtime::AugmentedSystem>(cm.dynamics);
  else
    system = std::make_unique<runtime::PartitionedSystem>(cm.dynamics);
  Eigen::VectorXd y0;
  try {
    y0 = system->initial_state(0.0, cm.q0, cm.qd0);
  } catch (const runtime::ContactError& e) {
    std::cerr << "mbfe simulate: " << model.source_path << ": inconsistent initial state: " << e.what() << "\n";
    return 2;
  }

  CsvOutput csv(options.out.value_or(""));
  const std::vector<std::string> names = runtime::coupled_coordinate_names(*cm.dynamics);
  std::vector<std::string> columns{"t"};
  std::vector<std::string> pos;
  for (int i = 0; i < nb; ++i) pos.push_back(names[i]);
  if (probes.empty())
    for (int i = nb; i < n; ++i) pos.push_back(names[i]);
  else
    for (const Probe& p : probes) pos.push_back(p.label);
  columns.insert(columns.end(), pos.begin(), pos.end());
  for (const std::string& p : pos) columns.push_back(p + "_dot");
  for (const std::string& l : coupled_multiplier_names(model)) columns.push_back(l);
  columns.push_back("phi_abs");
  csv.header(columns);
  std::vector<double> row(columns.size());
  Eigen::VectorXd q(n), qd(n);
  const int npos = static_cast<int>(pos.size());

  runtime::SimulationOptions run;
  run.step = options.step;
  run.t_end = options.t_end;
  run.every = options.every;
  run.quiet = options.quiet;
  // An unstable beam mode drags the contacts along; catch it while the Newton
  // closure can still follow (a state 1e4 times the largest seen).
  run.divergence_factor = 1.0e4;
  runtime::SimulationResult result;
  std::string row_error;
  try {
    result = runtime::run_simulation(*system, integrator, y0, run, [&](double t, const Eigen::VectorXd& y) {
      if (!row_error.empty()) return;
      runtime::ContactReport rep;
      try {
        system->full_state(t, y, q, qd);
        rep = system->report(t, y);
      } catch (const std::runtime_error& e) {
        row_error = e.what();  // the step after this one fails the same way
        return;
      }
      std::size_t k = 0;
      row[k++] = t;
      for (int i = 0; i < nb; ++i) row[k++] = q[i];
      if (probes.empty())
        for (int i = nb; i < n; ++i) row[k++] = q[i];
      else
        for (const Probe& p : probes) row[k++] = probe_value(p, q);
      for (int i = 0; i < nb; ++i) row[k++] = qd[i];
      if (probes.empty())
        for (int i = nb; i < n; ++i) row[k++] = qd[i];
      else
        for (const Probe& p : probes) row[k++] = probe_value(p, qd);
      for (int r = 0; r < m; ++r) row[k++] = rep.lambda[r];
      row[k++] = rep.phi_max;
      (void)npos;
      csv.row(row.data(), row.size());
    });
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  csv.flush();
  const std::string where = options.out ? " to " + *options.out : std::string();
  const std::string which = std::string(cm.adjusted ? "adjusted" : "original") + " damping, " +
                            (augmented ? "augmented" : "partitioned") + " formulation";
  if (result.status == runtime::SimulationStatus::kCompleted && row_error.empty()) {
    if (!options.quiet)
      std::cerr << "mbfe: " << model.name << " (" << which << "): " << result.steps << " " << result.integrator
                << " steps of " << result.step << " s to t = " << result.t << " s in " << result.wall_seconds
                << " s; " << csv.rows() << " rows written" << where << "\n";
    return 0;
  }
  if (result.status == runtime::SimulationStatus::kInterrupted) {
    std::cerr << "mbfe simulate: interrupted at t = " << result.t << " s; " << csv.rows() << " rows written"
              << where << "\n";
    return 3;
  }
  // Diverged, or a contact fault. The stable limit of the linearised system at
  // the initial state tells an instability of the integrator from a fault of
  // the model (a slider that leaves its beam at a stable step is the model's).
  runtime::StepLimit lim;
  bool have_limit = false;
  try {
    lim = runtime::stable_step(integrator,
                               runtime::linearized_spectrum(cm.dynamics, 0.0, cm.q0, cm.qd0).eigenvalues);
    have_limit = true;
  } catch (const std::exception&) {
  }
  // Only a step beyond a finite limit blames the integrator for a contact
  // fault; with no stable step at all (an eigenvalue with Re > 0: the motion
  // itself runs away from the initial state) the fault is the model's.
  const bool beyond = have_limit && lim.kind == runtime::StepLimit::Kind::kFinite && result.step > lim.h;
  std::ostringstream msg;
  msg.precision(5);
  const std::string fault = !row_error.empty() ? row_error : result.message;
  if (result.status == runtime::SimulationStatus::kDiverged || beyond) {
    const double t_fail = result.status == runtime::SimulationStatus::kDiverged ? result.t + result.step : result.t;
    msg << "diverged at t = " << t_fail << " s: step " << result.step;
    if (have_limit && lim.kind == runtime::StepLimit::Kind::kFinite && result.step > lim.h)
      msg << " exceeds " << result.integrator << "'s stable limit " << lim.text() << " (fastest eigenvalue "
          << eigenvalue_text(lim.critical) << ")";
    else if (have_limit && lim.kind == runtime::StepLimit::Kind::kNone)
      msg << ": " << result.integrator << " has no stable step for this model (eigenvalue "
          << eigenvalue_text(lim.critical) << ")";
    else
      msg << " with " << result.integrator << (have_limit ? " (stable limit " + lim.text() + ")" : std::string());
    if (result.status == runtime::SimulationStatus::kDiverged)
      msg << ": |y| = " << result.norm << " exceeded the bound " << result.bound;
    else
      msg << "; the growing state broke a contact: " << fault;
  } else {
    msg << "failed at t = " << result.t << " s: " << fault;
  }
  std::cerr << "mbfe simulate: " << msg.str() << "; " << which << "; " << csv.rows() << " rows written" << where
            << " up to there\n";
  return 3;
}

}  // namespace mbfe::tool
