// The passes an evaluation of the ten-span catenary makes over its wires'
// kept modes, alone: the rows of Phi_L a split evaluation reads (dot_rows,
// q and q' at the DOFs the droppers and the contact read) and loads
// (add_rows, Phi_L^T f), at the sizes of that model's contact wire (1549 kept
// modes, 94 rows read; docs/performance.md, "The ten-span models in real
// time"). What a step costs beyond four of each pair on each core is the
// rest of the step; bytes_per_second is the rate the rows stream in at.
//
//   build/bin/row_products_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <numeric>
#include <random>
#include <vector>

#include "runtime/linalg/row_products.h"

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr int kDofs = 4800;   // a wire's DOFs
constexpr int kModes = 1549;  // its modes below 1257 rad/s
constexpr int kRows = 94;     // the DOFs 90 droppers and the contact read

struct Wire {
  RowMajor phi;
  std::vector<int> rows;
  Eigen::VectorXd x, y, g, c;
  std::vector<double> out_x, out_y;
  Wire() : phi(kDofs, kModes), x(kModes), y(kModes), g(kModes), c(kRows), out_x(kRows), out_y(kRows) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (Eigen::Index i = 0; i < phi.size(); ++i) phi.data()[i] = u(rng);
    for (Eigen::Index i = 0; i < kModes; ++i) x[i] = u(rng), y[i] = u(rng), g[i] = 0.0;
    for (int i = 0; i < kRows; ++i) c[i] = u(rng);
    // Droppers every ~50 DOFs along the wire, as the model spaces them.
    for (int i = 0; i < kRows; ++i) rows.push_back((i * kDofs) / kRows);
  }
};

void BM_DotRows(benchmark::State& state) {
  Wire w;
  for (auto _ : state) {
    mbfe::runtime::dot_rows(w.phi.data(), kModes, w.rows.data(), kRows, w.x.data(), w.y.data(), w.out_x.data(),
                            w.out_y.data());
    benchmark::DoNotOptimize(w.out_x.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * int64_t{kRows} * kModes * 8);
  state.counters["flops"] = benchmark::Counter(double(state.iterations()) * 4.0 * kRows * kModes,
                                               benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DotRows);

void BM_AddRows(benchmark::State& state) {
  Wire w;
  for (auto _ : state) {
    mbfe::runtime::add_rows(w.phi.data(), kModes, w.rows.data(), w.c.data(), kRows, w.g.data());
    benchmark::DoNotOptimize(w.g.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * int64_t{kRows} * kModes * 8);
  state.counters["flops"] = benchmark::Counter(double(state.iterations()) * 2.0 * kRows * kModes,
                                               benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AddRows);

// Both, one after the other, as an evaluation makes them: the second pass
// finds in cache whatever of the rows the first left there.
void BM_DotThenAddRows(benchmark::State& state) {
  Wire w;
  for (auto _ : state) {
    mbfe::runtime::dot_rows(w.phi.data(), kModes, w.rows.data(), kRows, w.x.data(), w.y.data(), w.out_x.data(),
                            w.out_y.data());
    mbfe::runtime::add_rows(w.phi.data(), kModes, w.rows.data(), w.c.data(), kRows, w.g.data());
    benchmark::DoNotOptimize(w.g.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * 2 * int64_t{kRows} * kModes * 8);
}
BENCHMARK(BM_DotThenAddRows)->Threads(1)->Threads(2);

}  // namespace

BENCHMARK_MAIN();
