#pragma once

// Products with a few rows of a tall row-major matrix (the kept modes Phi_L
// of a beam at the DOFs where forces act), four rows per pass over the
// vectors: the rows come from far caches and the vectors from near ones, so a
// pass that reads each vector entry once for four rows does a quarter of the
// near-cache traffic of four row-by-row products (docs/performance.md, "The
// ten-span models in real time").

#include <Eigen/Core>

namespace mbfe::runtime {

/// out_x[i] = a.row(rows[i]) . x and out_y[i] = a.row(rows[i]) . y for i < n;
/// a row-major with m columns, x and y of m entries.
void dot_rows(const double* a, Eigen::Index m, const int* rows, int n, const double* x, const double* y,
              double* out_x, double* out_y);

/// g += sum over i < n of c[i] a.row(rows[i]); g of m entries.
void add_rows(const double* a, Eigen::Index m, const int* rows, const double* c, int n, double* g);

/// g = a^T x for a row-major with n rows and m columns and x with k <= 4
/// columns (column-major, n x k; g column-major, m x k), in one pass over a:
/// Eigen's product with a few columns first copies a into a packed form,
/// three passes over a matrix that fits no cache.
void transposed_product(const double* a, Eigen::Index n, Eigen::Index m, const double* x, int k, double* g);

}  // namespace mbfe::runtime
