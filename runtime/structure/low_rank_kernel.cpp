#include "runtime/structure/low_rank_kernel.h"

#include <cstddef>
#include <stdexcept>
#include <string>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define MBFE_LOW_RANK_AVX2 1
#include <immintrin.h>
#endif

namespace mbfe::runtime {

void check_shape(const LowRankCorrection& op) {
  const Eigen::Index m = op.U.cols();
  if (op.phi.rows() != op.U.rows() || op.phi.cols() != m || op.d_C.size() != m || op.d_K.size() != m) {
    throw std::invalid_argument("low-rank correction: U is " + std::to_string(op.U.rows()) + " x " +
                                std::to_string(m) + ", Phi_L " + std::to_string(op.phi.rows()) + " x " +
                                std::to_string(op.phi.cols()) + ", d_C and d_K have " +
                                std::to_string(op.d_C.size()) + " and " + std::to_string(op.d_K.size()) +
                                " entries; expected the same n x m shapes and m entries");
  }
}

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

// Columns j .. j + B - 1 at once: the dot products share the loads of q and
// qd and run 2 B independent FMA chains (one chain is bound by the FMA
// latency); the update of `a` loads and stores it once per B columns.
template <int B>
__attribute__((target("avx2,fma"))) void subtract_block(const LowRankCorrection& op, int j,
                                                        const double* q, const double* qd,
                                                        double* a) {
  const int n = static_cast<int>(op.U.rows());
  const double* u[B];
  const double* p[B];
  for (int c = 0; c < B; ++c) {
    u[c] = op.U.data() + static_cast<std::ptrdiff_t>(j + c) * n;
    p[c] = op.phi.data() + static_cast<std::ptrdiff_t>(j + c) * n;
  }
  __m256d uq[B], uv[B];
  for (int c = 0; c < B; ++c) uq[c] = uv[c] = _mm256_setzero_pd();
  int k = 0;
  for (; k + 4 <= n; k += 4) {
    const __m256d q4 = _mm256_loadu_pd(q + k), qd4 = _mm256_loadu_pd(qd + k);
    for (int c = 0; c < B; ++c) {
      const __m256d u4 = _mm256_loadu_pd(u[c] + k);
      uq[c] = _mm256_fmadd_pd(u4, q4, uq[c]);
      uv[c] = _mm256_fmadd_pd(u4, qd4, uv[c]);
    }
  }
  double r[B];
  for (int c = 0; c < B; ++c) {
    double dot_q = horizontal_sum(uq[c]), dot_qd = horizontal_sum(uv[c]);
    for (int i = k; i < n; ++i) {
      dot_q += u[c][i] * q[i];
      dot_qd += u[c][i] * qd[i];
    }
    r[c] = op.d_C[j + c] * dot_qd + op.d_K[j + c] * dot_q;
  }
  // a -= sum_c r_c phi_(j+c)
  __m256d rc[B];
  for (int c = 0; c < B; ++c) rc[c] = _mm256_set1_pd(r[c]);
  k = 0;
  for (; k + 4 <= n; k += 4) {
    __m256d a4 = _mm256_loadu_pd(a + k);
    for (int c = 0; c < B; ++c) a4 = _mm256_fnmadd_pd(rc[c], _mm256_loadu_pd(p[c] + k), a4);
    _mm256_storeu_pd(a + k, a4);
  }
  for (; k < n; ++k) {
    for (int c = 0; c < B; ++c) a[k] -= r[c] * p[c][k];
  }
}

}  // namespace

void subtract_low_rank_avx2(const LowRankCorrection& op, const double* q, const double* qd,
                            double* a) {
  const int m = static_cast<int>(op.U.cols());
  int j = 0;
  for (; j + 4 <= m; j += 4) subtract_block<4>(op, j, q, qd, a);
  for (; j < m; ++j) subtract_block<1>(op, j, q, qd, a);
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
