// Writing results: one CSV row of 404 columns (the paper platform's full
// state: 4 rigid coordinates and 200 beam DOFs, their rates) to /dev/null,
// the way `mbfe simulate` writes it (api/csv_format.h: std::to_chars into one
// buffer, one fwrite) against the way it did before (fprintf "%.17g" per
// value), side by side in one run.
//
//   build/bin/csv_output_bench
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "api/csv_format.h"

namespace {

constexpr int kColumns = 404;

std::vector<double> values() {
  std::mt19937 rng(5);
  std::normal_distribution<double> d(0.0, 1.0);
  std::vector<double> v(kColumns);
  for (double& x : v) x = d(rng) * std::pow(10.0, static_cast<int>(d(rng) * 3));  // 1e-9 .. 1e9
  return v;
}

void BM_RowPrintf(benchmark::State& state) {
  const std::vector<double> v = values();
  std::FILE* f = std::fopen("/dev/null", "w");
  for (auto _ : state) {
    for (std::size_t i = 0; i < v.size(); ++i) std::fprintf(f, "%s%.17g", i ? "," : "", v[i]);
    std::fputc('\n', f);
  }
  std::fclose(f);
  state.SetItemsProcessed(state.iterations() * kColumns);
}

void BM_RowToChars(benchmark::State& state) {
  const std::vector<double> v = values();
  std::FILE* f = std::fopen("/dev/null", "w");
  std::string line;
  for (auto _ : state) {
    mbfe::format_csv_row(v.data(), v.size(), line);
    std::fwrite(line.data(), 1, line.size(), f);
  }
  std::fclose(f);
  state.SetItemsProcessed(state.iterations() * kColumns);
}

BENCHMARK(BM_RowPrintf)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RowToChars)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
