#include "coupled_model.h"

#include <stdexcept>

#include "cli_args.h"
#include "multibody/linearization.h"
#include "multibody/rigid_system.h"

namespace mbfe::tool {

bool is_coupled(const model::Model& model) { return !model.bodies.empty() && !model.beams.empty(); }

runtime::BeamForceFn beam_force(const runtime::BeamPart& beam, bool adjusted) {
  const runtime::BeamSystem& sys = beam.system;
  if (!adjusted || !beam.has_adjustment) return runtime::sparse_beam_force(sys.C, sys.K);
  auto na = std::make_shared<runtime::NodalAdjusted>(
      beam.adjusted.uniform ? runtime::low_rank_adjusted(sys.M, beam.basis, beam.adjusted)
                            : runtime::eq27_adjusted(sys.M, beam.basis, beam.adjusted));
  auto M = std::make_shared<Eigen::SparseMatrix<double>>(sys.M);
  const int n = static_cast<int>(sys.M.rows());
  const int m = static_cast<int>(na->U.cols());
  // Scratch captured by value: one callback per CoupledDynamics, one thread.
  Eigen::VectorXd x(n), mx(n), ux(m), y(n);
  return [na, M, x, mx, ux, y](const Eigen::Ref<const Eigen::VectorXd>& q,
                               const Eigen::Ref<const Eigen::VectorXd>& qd,
                               Eigen::Ref<Eigen::VectorXd> f) mutable {
    x = qd;
    mx.noalias() = *M * x;
    ux.noalias() = na->U.transpose() * x;
    na->C.apply(x, mx, ux, na->U, y);
    f = y;
    x = q;
    mx.noalias() = *M * x;
    ux.noalias() = na->U.transpose() * x;
    na->K.apply(x, mx, ux, na->U, y);
    f += y;
  };
}

CoupledModel load_coupled(const model::Model& model, std::optional<bool> adjust, bool quiet) {
  CoupledModel out;
  out.beams = runtime::analyse_beams(model);
  out.adjusted = adjust.value_or(out.beams.any_adjustment);
  if (out.adjusted && !out.beams.any_adjustment)
    throw UsageError("--adjust on: no beam of '" + model.name +
                     "' has an `adjustment:` block (e.g. adjustment: {omega_limit: 1.0e5, margin: 0.1})");
  out.solver = load_solver(model, quiet);
  std::vector<runtime::CoupledBeam> beams;
  for (const runtime::BeamPart& b : out.beams.beams)
    beams.push_back(runtime::coupled_beam(b.system, beam_force(b, out.adjusted)));
  out.dynamics = std::make_shared<runtime::CoupledDynamics>(*out.solver.model, std::move(beams),
                                                            runtime::body_inertias(model));
  const int nb = static_cast<int>(model.bodies.size());
  const int n = out.dynamics->n();
  out.q0 = Eigen::VectorXd::Zero(n);
  out.qd0 = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < nb; ++i) {
    out.q0[i] = model.initial.q[i];
    out.qd0[i] = model.initial.qd[i];
  }
  return out;
}

runtime::StateSpectrum coupled_spectrum(const model::Model& model, bool adjusted, bool quiet) {
  CoupledModel cm = load_coupled(model, adjusted, quiet);
  return runtime::linearized_spectrum(cm.dynamics, 0.0, cm.q0, cm.qd0);
}

}  // namespace mbfe::tool
