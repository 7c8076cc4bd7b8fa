#include "runtime/linalg/row_products.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace mbfe::runtime {

namespace {

// Two doubles as one value, one SSE2 register (x86-64's baseline): eight
// partial sums and the three operands fit its sixteen registers.
using Lanes = double __attribute__((vector_size(16)));

Lanes load(const double* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof v);  // unaligned: the rows start anywhere
  return v;
}

double sum(Lanes v) { return v[0] + v[1]; }

}  // namespace

void dot_rows(const double* a, Eigen::Index m, const int* rows, int n, const double* x, const double* y,
              double* out_x, double* out_y) {
  const Eigen::Index body = m - m % 2;
  int i = 0;
  for (; i < n; i += 4) {
    const int k = n - i < 4 ? n - i : 4;  // rows in this pass; a short pass repeats its first
    const double* r[4];
    for (int b = 0; b < 4; ++b) r[b] = a + static_cast<Eigen::Index>(rows[i + (b < k ? b : 0)]) * m;
    Lanes sx[4] = {}, sy[4] = {};
    for (Eigen::Index j = 0; j < body; j += 2) {
      const Lanes xj = load(x + j), yj = load(y + j);
      for (int b = 0; b < 4; ++b) {
        const Lanes rj = load(r[b] + j);
        sx[b] += rj * xj;
        sy[b] += rj * yj;
      }
    }
    for (int b = 0; b < k; ++b) {
      double tx = sum(sx[b]), ty = sum(sy[b]);
      for (Eigen::Index j = body; j < m; ++j) {
        tx += r[b][j] * x[j];
        ty += r[b][j] * y[j];
      }
      out_x[i + b] = tx;
      out_y[i + b] = ty;
    }
  }
}

void add_rows(const double* a, Eigen::Index m, const int* rows, const double* c, int n, double* g) {
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    const double* r0 = a + rows[i] * m;
    const double* r1 = a + rows[i + 1] * m;
    const double* r2 = a + rows[i + 2] * m;
    const double* r3 = a + rows[i + 3] * m;
    const double c0 = c[i], c1 = c[i + 1], c2 = c[i + 2], c3 = c[i + 3];
    for (Eigen::Index j = 0; j < m; ++j) g[j] += (c0 * r0[j] + c1 * r1[j]) + (c2 * r2[j] + c3 * r3[j]);
  }
  for (; i < n; ++i) {
    const double* r = a + rows[i] * m;
    const double ci = c[i];
    for (Eigen::Index j = 0; j < m; ++j) g[j] += ci * r[j];
  }
}

namespace {

template <int K>
void transposed_product_of(const double* a, Eigen::Index n, Eigen::Index m, const double* x, double* g) {
  std::fill(g, g + K * m, 0.0);
  Eigen::Index i = 0;
  for (; i + 4 <= n; i += 4) {
    const double* r0 = a + i * m;
    const double* r1 = r0 + m;
    const double* r2 = r1 + m;
    const double* r3 = r2 + m;
    double c[K][4];
    for (int col = 0; col < K; ++col)
      for (int b = 0; b < 4; ++b) c[col][b] = x[col * n + i + b];
    for (Eigen::Index j = 0; j < m; ++j)
      for (int col = 0; col < K; ++col)
        g[col * m + j] += (c[col][0] * r0[j] + c[col][1] * r1[j]) + (c[col][2] * r2[j] + c[col][3] * r3[j]);
  }
  for (; i < n; ++i) {
    const double* r = a + i * m;
    for (int col = 0; col < K; ++col) {
      const double ci = x[col * n + i];
      for (Eigen::Index j = 0; j < m; ++j) g[col * m + j] += ci * r[j];
    }
  }
}

}  // namespace

void transposed_product(const double* a, Eigen::Index n, Eigen::Index m, const double* x, int k, double* g) {
  switch (k) {
    case 1: return transposed_product_of<1>(a, n, m, x, g);
    case 2: return transposed_product_of<2>(a, n, m, x, g);
    case 3: return transposed_product_of<3>(a, n, m, x, g);
    case 4: return transposed_product_of<4>(a, n, m, x, g);
    default: throw std::invalid_argument("transposed_product: " + std::to_string(k) + " columns, at most 4");
  }
}

}  // namespace mbfe::runtime
