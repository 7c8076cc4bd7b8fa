#include "runtime/structure/coupled_beams.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <memory>

#include "runtime/structure/low_rank_kernel.h"

namespace mbfe::runtime {

namespace {

/// The beam's adjusted operators in nodal form: low rank for a uniform cap,
/// eq (27) over every mode otherwise. Built once per beam: it holds the modes.
std::shared_ptr<const NodalAdjusted> nodal_adjusted(const BeamPart& beam) {
  const BeamSystem& sys = beam.system;
  return std::make_shared<const NodalAdjusted>(beam.adjusted.uniform
                                                   ? low_rank_adjusted(sys.M, beam.basis, beam.adjusted)
                                                   : eq27_adjusted(sys.M, beam.basis, beam.adjusted));
}

BeamForceFn adjusted_force(const BeamSystem& sys, std::shared_ptr<const NodalAdjusted> na) {
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
    const NodalOperator& C = na->C;
    const NodalOperator& K = na->K;
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

/// Empty unless `na` is the low-rank form with no sparse part.
BeamForceFn adjusted_acceleration(const BeamSystem& sys, const NodalAdjusted& na) {
  if (!na.low_rank || na.C.S.size() > 0 || na.K.S.size() > 0) return {};
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(sys.M);
  if (ldlt.info() != Eigen::Success) return {};
  const Eigen::VectorXd minv_p = ldlt.solve(sys.P);
  const Eigen::Index m = na.U.cols();
  auto low_rank = std::make_shared<LowRankCorrection>();
  low_rank->U = na.U;
  low_rank->phi = na.phi;
  // An operator without a modal part has an empty d: no correction.
  low_rank->d_C = na.C.d.size() == 0 ? Eigen::VectorXd::Zero(m) : na.C.d;
  low_rank->d_K = na.K.d.size() == 0 ? Eigen::VectorXd::Zero(m) : na.K.d;
  check_shape(*low_rank);
  const double s_C = na.C.s, s_K = na.K.s;
  return [low_rank, minv_p, s_C, s_K](const Eigen::Ref<const Eigen::VectorXd>& q,
                                      const Eigen::Ref<const Eigen::VectorXd>& qd,
                                      Eigen::Ref<Eigen::VectorXd> a) {
    a = minv_p - s_C * qd - s_K * q;
    if (low_rank->U.cols() > 0) subtract_low_rank(*low_rank, q.data(), qd.data(), a.data());
  };
}

}  // namespace

BeamForceFn beam_force(const BeamPart& beam, bool adjusted) {
  if (!adjusted || !beam.has_adjustment) return sparse_beam_force(beam.system.C, beam.system.K);
  return adjusted_force(beam.system, nodal_adjusted(beam));
}

BeamForceFn beam_acceleration(const BeamPart& beam, bool adjusted) {
  if (!adjusted || !beam.has_adjustment || !beam.adjusted.uniform) return {};
  return adjusted_acceleration(beam.system, *nodal_adjusted(beam));
}

namespace {

/// A joined structure's member: c* M q' + k* M q, and its free acceleration
/// M^-1 P - c* q' - k* q without a solve.
CoupledBeam joined_member(const BeamSystem& sys, double c_star, double k_star) {
  Eigen::SparseMatrix<double> C = c_star * sys.M, K = k_star * sys.M;
  CoupledBeam out = coupled_beam(sys, sparse_beam_force(C, K));
  out.C = std::move(C);
  out.K = std::move(K);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(sys.M);
  if (ldlt.info() != Eigen::Success) return out;  // CoupledDynamics reports the mass matrix
  const Eigen::VectorXd minv_p = ldlt.solve(sys.P);
  out.acceleration = [minv_p, c_star, k_star](const Eigen::Ref<const Eigen::VectorXd>& q,
                                              const Eigen::Ref<const Eigen::VectorXd>& qd,
                                              Eigen::Ref<Eigen::VectorXd> a) { a = minv_p - c_star * qd - k_star * q; };
  return out;
}

}  // namespace

std::vector<CoupledBeam> coupled_beams(const BeamModel& beams, bool adjusted,
                                       const std::vector<JoinedStructure>& joined) {
  std::vector<CoupledBeam> out;
  for (std::size_t k = 0; k < beams.beams.size(); ++k) {
    const BeamPart& b = beams.beams[k];
    const JoinedStructure* structure = nullptr;
    for (const JoinedStructure& s : joined)
      if (std::find(s.beams.begin(), s.beams.end(), static_cast<int>(k)) != s.beams.end()) structure = &s;
    if (adjusted && structure) {
      out.push_back(joined_member(b.system, structure->c_star, structure->k_star));
    } else if (!adjusted || !b.has_adjustment) {
      out.push_back(coupled_beam(b.system, beam_force(b, false)));
      out.back().C = b.system.C;
      out.back().K = b.system.K;
    } else {
      const std::shared_ptr<const NodalAdjusted> operators = nodal_adjusted(b);
      const NodalAdjusted& na = *operators;
      out.push_back(coupled_beam(b.system, adjusted_force(b.system, operators)));
      out.back().acceleration = adjusted_acceleration(b.system, na);
      if (na.low_rank && na.C.S.size() == 0 && na.K.S.size() == 0) {
        out.back().C = na.C.s * b.system.M;
        out.back().K = na.K.s * b.system.M;
        auto low_rank = std::make_shared<BeamLowRank>();
        const Eigen::Index m = na.U.cols();
        low_rank->U = na.U;
        low_rank->d_C = na.C.d.size() == 0 ? Eigen::VectorXd::Zero(m) : na.C.d;
        low_rank->d_K = na.K.d.size() == 0 ? Eigen::VectorXd::Zero(m) : na.K.d;
        low_rank->phi_rows = na.phi;
        low_rank->c_star = na.C.s;
        low_rank->k_star = na.K.s;
        out.back().low_rank = std::move(low_rank);
      }
    }
    if (b.system.has_time_loads()) {
      auto system = std::make_shared<const BeamSystem>(b.system);
      out.back().time_loads = [system](double t, std::vector<NodalForce>& forces) {
        time_dependent_loads(*system, t, forces);
      };
    }
  }
  return out;
}

}  // namespace mbfe::runtime
