// The hot loop of an adjusted beam in nodal coordinates (the low-rank form of
// section 3), once per right-hand side of a coupled model:
//
//   a -= Phi_L (d_C .* (U^T qd) + d_K .* (U^T q)),     U = M Phi_L (n x m)
//
// three passes over n x m dense matrices (100 x 19 per beam of the paper), a
// third of the platform's step. The portable build compiles Eigen for SSE2,
// so next to the Eigen form there is an AVX2 + FMA form of the same loop,
// compiled for that instruction set alone (a `target` attribute, not a
// build-wide -march that would mix Eigen's alignment rules between files) and
// chosen at run time when the processor has it. Both are tested against a
// dense product (tests/runtime/structure/low_rank_kernel_test.cpp); they differ by
// summation order only.
#pragma once

#include <Eigen/Core>

namespace mbfe::runtime {

/// The low-rank part of an adjusted beam: Phi_L, U = M Phi_L and the modal
/// corrections d_C, d_K of the kept modes (NodalAdjusted, NodalOperator::d).
struct LowRankCorrection {
  Eigen::MatrixXd U, phi;  // n x m, column-major
  Eigen::VectorXd d_C, d_K;  // m
};

/// @throws std::invalid_argument unless U and phi are both n x m and d_C,
///         d_K have m entries (the kernels below do not check).
void check_shape(const LowRankCorrection& op);

/// a -= Phi_L (d_C .* (U^T qd) + d_K .* (U^T q)) by the fastest form this
/// processor runs. q, qd, a: n entries; a may not alias q or qd. The forms
/// differ in summation order (and FMA rounding), so results agree across
/// processors to round-off, not bit for bit.
void subtract_low_rank(const LowRankCorrection& op, const double* q, const double* qd, double* a);

/// The two forms, for tests and benchmarks. The AVX2 one exists only when
/// avx2_available() is true (calling it otherwise is undefined).
void subtract_low_rank_eigen(const LowRankCorrection& op, const double* q, const double* qd,
                             double* a);
void subtract_low_rank_avx2(const LowRankCorrection& op, const double* q, const double* qd,
                            double* a);
/// True when this build has the AVX2 form and this processor can run it.
bool avx2_available();

}  // namespace mbfe::runtime
