#include "tool/coupled_model.h"

#include <stdexcept>

#include "tool/cli_args.h"
#include "runtime/damping/low_rank_kernel.h"
#include "runtime/multibody/linearization.h"
#include "runtime/multibody/rigid_system.h"

namespace mbfe::tool {

bool is_coupled(const ir::Model& model) { return !model.bodies.empty() && !model.beams.empty(); }

runtime::BeamForceFn beam_force(const runtime::BeamPart& beam, bool adjusted) {
  const runtime::BeamSystem& sys = beam.system;
  if (!adjusted || !beam.has_adjustment) return runtime::sparse_beam_force(sys.C, sys.K);
  auto na = std::make_shared<runtime::NodalAdjusted>(
      beam.adjusted.uniform ? runtime::low_rank_adjusted(sys.M, beam.basis, beam.adjusted)
                            : runtime::eq27_adjusted(sys.M, beam.basis, beam.adjusted));
  auto M = std::make_shared<Eigen::SparseMatrix<double>>(sys.M);
  const int n = static_cast<int>(sys.M.rows());
  const int m = static_cast<int>(na->U.cols());
  // C qd + K q = S_C qd + S_K q + M (s_C qd + s_K q) + U (d_C .* U^T qd + d_K .* U^T q):
  // one sparse product with M and one pass over U each way (the fused form of
  // NodalOperator::apply for the two operators). Scratch captured by value:
  // one callback per CoupledDynamics, one thread.
  Eigen::VectorXd z(n), ux(m), uv(m), r(m);
  return [na, M, z, ux, uv, r](const Eigen::Ref<const Eigen::VectorXd>& q,
                               const Eigen::Ref<const Eigen::VectorXd>& qd,
                               Eigen::Ref<Eigen::VectorXd> f) mutable {
    const runtime::NodalOperator& C = na->C;
    const runtime::NodalOperator& K = na->K;
    z = C.s * qd + K.s * q;
    f.noalias() = *M * z;
    if (C.S.size() > 0) f.noalias() += C.S * qd;
    if (K.S.size() > 0) f.noalias() += K.S * q;
    if (na->U.cols() > 0) {
      r.setZero();
      if (C.d.size() > 0) {
        uv.noalias() = na->U.transpose() * qd;
        r += C.d.cwiseProduct(uv);
      }
      if (K.d.size() > 0) {
        ux.noalias() = na->U.transpose() * q;
        r += K.d.cwiseProduct(ux);
      }
      f.noalias() += na->U * r;
    }
  };
}

runtime::BeamForceFn beam_acceleration(const runtime::BeamPart& beam, bool adjusted) {
  const runtime::BeamSystem& sys = beam.system;
  if (!adjusted || !beam.has_adjustment || !beam.adjusted.uniform) return {};
  const runtime::NodalAdjusted na = runtime::low_rank_adjusted(sys.M, beam.basis, beam.adjusted);
  if (na.C.S.size() > 0 || na.K.S.size() > 0) return {};
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(sys.M);
  if (ldlt.info() != Eigen::Success) return {};
  const Eigen::VectorXd minv_p = ldlt.solve(sys.P);
  const Eigen::Index m = na.U.cols();
  auto low_rank = std::make_shared<runtime::LowRankCorrection>();
  low_rank->U = na.U;
  low_rank->phi = na.phi;
  // An operator without a modal part has an empty d: no correction.
  low_rank->d_C = na.C.d.size() == 0 ? Eigen::VectorXd::Zero(m) : na.C.d;
  low_rank->d_K = na.K.d.size() == 0 ? Eigen::VectorXd::Zero(m) : na.K.d;
  runtime::check_shape(*low_rank);
  const double s_C = na.C.s, s_K = na.K.s;
  return [low_rank, minv_p, s_C, s_K](const Eigen::Ref<const Eigen::VectorXd>& q,
                                      const Eigen::Ref<const Eigen::VectorXd>& qd,
                                      Eigen::Ref<Eigen::VectorXd> a) {
    a = minv_p - s_C * qd - s_K * q;
    if (low_rank->U.cols() > 0) runtime::subtract_low_rank(*low_rank, q.data(), qd.data(), a.data());
  };
}

CoupledModel load_coupled(const ir::Model& model, std::optional<bool> adjust, bool quiet) {
  CoupledModel out;
  out.beams = runtime::analyse_beams(model);
  out.adjusted = adjust.value_or(out.beams.any_adjustment);
  if (out.adjusted && !out.beams.any_adjustment)
    throw UsageError("--adjust on: no beam of '" + model.name +
                     "' has an `adjustment:` block (e.g. adjustment: {omega_limit: 1.0e5, margin: 0.1})");
  out.solver = load_solver(model, quiet);
  std::vector<runtime::CoupledBeam> beams;
  for (const runtime::BeamPart& b : out.beams.beams) {
    beams.push_back(runtime::coupled_beam(b.system, beam_force(b, out.adjusted)));
    beams.back().acceleration = beam_acceleration(b, out.adjusted);
  }
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

runtime::StateSpectrum coupled_spectrum(const ir::Model& model, bool adjusted, bool quiet) {
  CoupledModel cm = load_coupled(model, adjusted, quiet);
  return runtime::linearized_spectrum(cm.dynamics, 0.0, cm.q0, cm.qd0);
}

}  // namespace mbfe::tool
