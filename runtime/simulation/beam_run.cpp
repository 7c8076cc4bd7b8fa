// simulate() for a model of beams only. The model is integrated in
// mass-normalised modal coordinates (every mode; the same model as the nodal
// one, see runtime/damping/beam_ode.h), original or adjusted; rows are written
// in nodal coordinates: t, then the beam coordinates in contract order
// (<beam>_w<node>, <beam>_dw<node>, free DOFs only), or the probe columns.
#include "runtime/errors/invalid_input.h"
#include "runtime/simulation/run_diagnosis.h"
#include "runtime/simulation/runs.h"

namespace mbfe::runtime::detail {

SimulationReport run_beams(const AssembledModel& model, const SimulationRequest& request,
                           SimulationObserver& observer) {
  const BeamModel& beams = model.beams();
  const bool adjusted = model.resolve_adjusted(request.adjust);
  std::unique_ptr<ModalBeamOde> ode;
  try {
    ode = modal_beam_ode(beams, adjusted);
  } catch (const std::invalid_argument& e) {
    throw InvalidInput(e.what());
  }
  const int n = beams.dof;
  const Eigen::VectorXd y_static = modal_static_state(beams, adjusted, *ode);
  const std::vector<BeamProbe> probes = resolve_probes(request.probes, model.ir(), beams);

  OutputLayout layout;
  layout.columns.push_back("t");
  layout.units.push_back("s");
  if (probes.empty()) {
    for (const BeamPart& b : beams.beams)
      for (int f : b.system.free_dof) {
        layout.columns.push_back(b.system.name + (f % 2 == 0 ? "_w" : "_dw") + std::to_string(f / 2));
        layout.units.push_back(f % 2 == 0 ? "m" : "1");
      }
  } else {
    for (const BeamProbe& p : probes) {
      layout.columns.push_back(p.label);
      layout.units.push_back("m");
    }
  }
  observer.begin(layout);
  std::vector<double> values(layout.columns.size());
  Eigen::VectorXd q(n), qd(n);
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

  SimulationOptions options = driver_options(request);
  options.reference_norm = y_static.norm();
  // Beams start at rest, undeformed, or in static equilibrium under the loads at t = 0.
  const Eigen::VectorXd y0 = request.static_start.value_or(model.ir().initial.static_start) ? y_static : Eigen::VectorXd::Zero(2 * n);
  SimulationReport report;
  report.variant = adjusted ? "adjusted damping" : "original damping";
  try {
    report.run = run_simulation(*ode, request.integrator, y0, options, [&](double t, const Eigen::VectorXd& y) {
      values[0] = t;
      // Nodal coordinates cost n^2 per row: only when a column or the
      // observer needs them.
      if (probes.empty() || request.state_in_rows) ode->positions(y, q);
      if (request.state_in_rows) qd.noalias() = ode->phi() * y.tail(n);
      if (probes.empty()) {
        for (int i = 0; i < n; ++i) values[1 + i] = q[i];
      } else {
        probe_values.noalias() = probe_rows * y.head(n);
        for (std::size_t k = 0; k < probes.size(); ++k) values[1 + k] = probe_values[k];
      }
      observer.row(OutputRow{t, values, q, qd});
    });
  } catch (const std::invalid_argument& e) {
    throw InvalidInput(e.what());
  }
  if (report.run.status != SimulationStatus::kCompleted) {
    const StateSpectrum& spectrum = adjusted ? beams.adjusted : beams.original;
    report.message = diagnose_run(report.run, stable_step(request.integrator, spectrum.eigenvalues));
  }
  return report;
}

}  // namespace mbfe::runtime::detail
