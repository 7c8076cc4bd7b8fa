// Vehicles crossing the bridge (models/bridge_moving_mass.yaml: 40 elements,
// a driven carriage, a wheel on a unilateral slider_spring, static start;
// models/bridge_two_axle_vehicle.yaml: three beams, five rigid coordinates,
// six slider_springs), each as shipped: adjusted damping, RK4 at 1e-3 s (its
// adjusted limit 1.0164e-3 s), 1.2 s and 1.6 s simulated.
// Targets: under 0.1 s and 0.2 s end to end (docs/performance.md).
//
//   build/bin/vehicle_crossing_bench
//
// BM_EndToEnd/<model>    load the file (parse, cached solver, modal analysis of
//                        the beams), static start, the whole run, rows to an
//                        empty observer every step: what `mbfe simulate` does
//                        in-process
// BM_RunOnly/<model>     the run alone, the model loaded once
#include <benchmark/benchmark.h>

#include <string>

#include "api/mbfe.h"

namespace {

using namespace mbfe;

class Sink : public runtime::SimulationObserver {
 public:
  void row(const runtime::OutputRow& row) override { benchmark::DoNotOptimize(row.values.data()); }
};

std::string path(const char* model) { return std::string(MBFE_SOURCE_DIR) + "/models/" + model + ".yaml"; }

/// The model's `simulation:` block, every row, a probe at midspan.
runtime::SimulationRequest request(const Model& m) {
  runtime::SimulationRequest r = m.request();
  r.every = 1;
  r.probes = {runtime::parse_probe("deck@10")};
  return r;
}

void BM_EndToEnd(benchmark::State& state, const char* model) {
  LoadOptions quiet;
  quiet.quiet = true;
  Model::load(path(model), quiet);  // the solver in the cache, as after a first run
  for (auto _ : state) {
    const Model m = Model::load(path(model), quiet);
    Sink sink;
    const runtime::SimulationReport report = m.simulate(request(m), sink);
    if (!report.message.empty()) state.SkipWithError(report.message.c_str());
  }
}

void BM_RunOnly(benchmark::State& state, const char* model) {
  LoadOptions quiet;
  quiet.quiet = true;
  const Model m = Model::load(path(model), quiet);
  m.assembled();
  for (auto _ : state) {
    Sink sink;
    const runtime::SimulationReport report = m.simulate(request(m), sink);
    if (!report.message.empty()) state.SkipWithError(report.message.c_str());
  }
}

BENCHMARK_CAPTURE(BM_EndToEnd, moving_mass, "bridge_moving_mass")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RunOnly, moving_mass, "bridge_moving_mass")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EndToEnd, two_axle, "bridge_two_axle_vehicle")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_RunOnly, two_axle, "bridge_two_axle_vehicle")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
