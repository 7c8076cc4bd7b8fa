// Spectrum slicing of one ten-span catenary wire (the messenger, 4,800 DOF):
// every mode its cap keeps (omega <= 1500 rad/s, 1,785 modes and the first
// above), at several modes per Lanczos run. What the run size of the
// slicing's default was chosen by (docs/performance.md, "The set-up paid
// once"). One iteration each: a run takes seconds.
#include <benchmark/benchmark.h>

#include <string>

#include "frontend/parse_model.h"
#include "runtime/fem/beam_system.h"
#include "runtime/modal/modal_analysis.h"

namespace {

using namespace mbfe;

constexpr double kCap = 1500.0;  // rad/s, the cap the ten-span models were adjusted with (kept for comparison)

const runtime::BeamSystem& messenger() {
  static const ir::Model model =
      frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/pantograph_catenary_300.yaml");
  static const runtime::BeamSystem wire = runtime::assemble_beam(model.beams[0], model.gravity);
  return wire;
}

void BM_SliceKeptModes(benchmark::State& state) {
  const runtime::BeamSystem& wire = messenger();
  runtime::ModalOptions options;
  options.up_to_omega = kCap;
  options.slice_modes = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const runtime::ModalBasis basis = runtime::modal_analysis(wire, options);
    state.counters["modes"] = static_cast<double>(basis.omega.size());
  }
}
BENCHMARK(BM_SliceKeptModes)->Arg(20)->Arg(30)->Arg(50)->Arg(100)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
