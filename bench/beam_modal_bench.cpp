// Beam FE + modal analysis speed:
//  - the paper beam (100 DOF): assembly + dense modal analysis + state-space
//    eigenvalues (target < 50 ms);
//  - a 100,000-DOF beam: its 20 lowest modes by sparse shift-invert Lanczos
//    (target < 10 s on 2 cores; memory O(nnz + 20 n), never dense n x n).
// Run: build/bin/beam_modal_bench
#include <benchmark/benchmark.h>

#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_analysis.h"
#include "runtime/modal/state_spectrum.h"

namespace {

using namespace mbfe;

ir::Beam paper_beam(int elements) {
  ir::Beam b;
  b.name = "beam1";
  b.length = 1.0;
  b.elements = elements;
  const double a = 0.005;
  b.area = a * a;
  b.second_moment = a * a * a * a / 12.0;
  b.youngs_modulus = 2.1e11;
  b.density = 7860.0;
  b.rayleigh_alpha = 3.0e-3;
  b.rayleigh_beta = 1.5e-4;
  b.supports = {{0.0, ir::SupportType::kPinned, -1, {}},
                {1.0, ir::SupportType::kPinned, -1, {}}};
  b.loads = {{0.5, ir::Expression::number(-10.0), -1, {}, {}}};
  return b;
}

void BM_PaperBeamAssemblyModalSpectrum(benchmark::State& state) {
  const ir::Beam b = paper_beam(50);
  for (auto _ : state) {
    const runtime::BeamSystem s = runtime::assemble_beam(b, {0.0, -9.81});
    const runtime::ModalBasis m = runtime::modal_analysis(s);
    const runtime::StateSpectrum sp =
        runtime::rayleigh_spectrum(m, b.rayleigh_alpha, b.rayleigh_beta);
    benchmark::DoNotOptimize(sp.h_max_forward_euler);
  }
  state.counters["dof"] = 100;
}
BENCHMARK(BM_PaperBeamAssemblyModalSpectrum)->Unit(benchmark::kMillisecond);

void BM_PaperBeamAssemblyOnly(benchmark::State& state) {
  const ir::Beam b = paper_beam(50);
  for (auto _ : state) benchmark::DoNotOptimize(runtime::assemble_beam(b, {0.0, -9.81}).P.data());
}
BENCHMARK(BM_PaperBeamAssemblyOnly)->Unit(benchmark::kMicrosecond);

// elements -> 2 (elements + 1) - 2 DOF: 50,000 elements = 100,000 DOF.
void BM_LargeBeamLowest20Sparse(benchmark::State& state) {
  const int elements = static_cast<int>(state.range(0));
  const ir::Beam b = paper_beam(elements);
  const runtime::BeamSystem s = runtime::assemble_beam(b, {0.0, -9.81});
  runtime::ModalOptions options;
  options.num_modes = 20;
  for (auto _ : state) {
    const runtime::ModalBasis m = runtime::modal_analysis(s, options);
    benchmark::DoNotOptimize(m.omega.data());
  }
  state.counters["dof"] = static_cast<double>(s.M.rows());
}
BENCHMARK(BM_LargeBeamLowest20Sparse)
    ->Arg(5000)
    ->Arg(50000)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

void BM_LargeBeamAssembly(benchmark::State& state) {
  const ir::Beam b = paper_beam(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(runtime::assemble_beam(b, {0.0, -9.81}).P.data());
}
BENCHMARK(BM_LargeBeamAssembly)->Arg(50000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
