// The stability advisor on the large coupled models: the spectrum
// `mbfe stability` takes (runtime::model_spectrum), original and adjusted,
// the model loaded and assembled once. Coupled models without constraint
// contacts are linearised from their tangents, and beyond 1,200 states the
// two ends of the spectrum come from Arnoldi (runtime/coupled/tangent_spectrum.h).
// Targets (docs/performance.md): the two-span catenary under 10 s, the
// ten-span under 60 s (the dense difference linearisation took about
// 12 minutes on the two-span and was refused on the ten-span).
//
//   build/bin/advisor_spectrum_bench
//   MBFE_BENCH_TEN_SPAN=catenary_ten_span.yaml build/bin/advisor_spectrum_bench
//
// The ten-span model is written by
//   python3 scripts/make_catenary.py --spans 10 --speed 300 --name catenary_ten_span -o catenary_ten_span.yaml
// and benchmarked only when MBFE_BENCH_TEN_SPAN names it.
//
// BM_Spectrum/<model>/<variant>   static start, tangents, both ends of the spectrum
// BM_Spectrum/vehicle             bridge_two_axle_vehicle, dense (234 states)
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "api/mbfe.h"

namespace {

using namespace mbfe;

std::string shipped(const char* model) { return std::string(MBFE_SOURCE_DIR) + "/models/" + model + ".yaml"; }

void BM_Spectrum(benchmark::State& state, const std::string& path, bool adjusted) {
  LoadOptions quiet;
  quiet.quiet = true;
  const Model m = Model::load(path, quiet);
  m.assembled();
  for (auto _ : state) {
    const runtime::ModelSpectrum spectrum = m.spectrum(adjusted);
    benchmark::DoNotOptimize(spectrum.limiting.eigenvalues.data());
    state.counters["states"] = 2.0 * spectrum.coordinates;
    state.counters["fastest"] = spectrum.full.eigenvalues.empty() ? 0.0 : std::abs(spectrum.full.eigenvalues.back());
  }
}

void register_model(const std::string& name, const std::string& path) {
  for (bool adjusted : {false, true})
    benchmark::RegisterBenchmark(("BM_Spectrum/" + name + (adjusted ? "/adjusted" : "/original")).c_str(),
                                 [path, adjusted](benchmark::State& s) { BM_Spectrum(s, path, adjusted); })
        ->Unit(benchmark::kSecond)
        ->Iterations(1);
}

}  // namespace

int main(int argc, char** argv) {
  register_model("vehicle", shipped("bridge_two_axle_vehicle"));
  register_model("catenary_2span", shipped("pantograph_catenary_2span"));
  if (const char* ten = std::getenv("MBFE_BENCH_TEN_SPAN")) register_model("catenary_ten_span", ten);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
