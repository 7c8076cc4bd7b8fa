#include "damping/low_rank_kernel.h"

#include <cstddef>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define MBFE_LOW_RANK_AVX2 1
#include <immintrin.h>
#endif

namespace mbfe::runtime {

void subtract_low_rank_eigen(const LowRankCorrection& op, const double* q, const double* qd,
                             double* a) {
  const Eigen::Index n = op.U.rows();
  const Eigen::Map<const Eigen::VectorXd> qv(q, n), qdv(qd, n);
  Eigen::Map<Eigen::VectorXd> av(a, n);
  thread_local Eigen::VectorXd r;  // m entries, kept per thread: no allocation after the first call
  r.noalias() = op.d_C.cwiseProduct(op.U.transpose() * qdv);
  r.noalias() += op.d_K.cwiseProduct(op.U.transpose() * qv);
  av.noalias() -= op.phi * r;
}

#ifdef MBFE_LOW_RANK_AVX2

namespace {

__attribute__((target("avx2,fma"))) double horizontal_sum(__m256d v) {
  const __m128d pair = _mm_add_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
  return _mm_cvtsd_f64(_mm_add_sd(pair, _mm_unpackhi_pd(pair, pair)));
}

}  // namespace

__attribute__((target("avx2,fma"))) void subtract_low_rank_avx2(const LowRankCorrection& op,
                                                                 const double* q,
                                                                 const double* qd, double* a) {
  const int n = static_cast<int>(op.U.rows());
  const int m = static_cast<int>(op.U.cols());
  for (int j = 0; j < m; ++j) {
    // u_j . q and u_j . qd in one pass over the column, two accumulators each
    // (the FMA latency, not the loads, bounds a single chain).
    const double* u = op.U.data() + static_cast<std::ptrdiff_t>(j) * n;
    __m256d uq0 = _mm256_setzero_pd(), uq1 = _mm256_setzero_pd();
    __m256d uv0 = _mm256_setzero_pd(), uv1 = _mm256_setzero_pd();
    int k = 0;
    for (; k + 8 <= n; k += 8) {
      const __m256d u0 = _mm256_loadu_pd(u + k), u1 = _mm256_loadu_pd(u + k + 4);
      uq0 = _mm256_fmadd_pd(u0, _mm256_loadu_pd(q + k), uq0);
      uq1 = _mm256_fmadd_pd(u1, _mm256_loadu_pd(q + k + 4), uq1);
      uv0 = _mm256_fmadd_pd(u0, _mm256_loadu_pd(qd + k), uv0);
      uv1 = _mm256_fmadd_pd(u1, _mm256_loadu_pd(qd + k + 4), uv1);
    }
    double uq = horizontal_sum(_mm256_add_pd(uq0, uq1));
    double uv = horizontal_sum(_mm256_add_pd(uv0, uv1));
    for (; k < n; ++k) {
      uq += u[k] * q[k];
      uv += u[k] * qd[k];
    }
    // a -= r_j phi_j
    const double r = op.d_C[j] * uv + op.d_K[j] * uq;
    const double* p = op.phi.data() + static_cast<std::ptrdiff_t>(j) * n;
    const __m256d rj = _mm256_set1_pd(r);
    k = 0;
    for (; k + 4 <= n; k += 4) {
      _mm256_storeu_pd(a + k, _mm256_fnmadd_pd(rj, _mm256_loadu_pd(p + k), _mm256_loadu_pd(a + k)));
    }
    for (; k < n; ++k) a[k] -= r * p[k];
  }
}

bool avx2_available() {
  static const bool available = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return available;
}

#else

void subtract_low_rank_avx2(const LowRankCorrection& op, const double* q, const double* qd,
                            double* a) {
  subtract_low_rank_eigen(op, q, qd, a);  // never chosen: avx2_available() is false
}

bool avx2_available() { return false; }

#endif

void subtract_low_rank(const LowRankCorrection& op, const double* q, const double* qd, double* a) {
  if (avx2_available()) {
    subtract_low_rank_avx2(op, q, qd, a);
  } else {
    subtract_low_rank_eigen(op, q, qd, a);
  }
}

}  // namespace mbfe::runtime
