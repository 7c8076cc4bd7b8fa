// The adjusted paper beam, forward Euler, 1 s at h = 1.4e-5 (71,429 steps,
// 100 DOF): the run the paper's method makes possible. Target < 0.1 s.
//
//   build/bench/adjusted_beam_bench          (or build/bin/adjusted_beam_bench)
//
// BM_AdjustedBeamModal      modal coordinates (what `mbfe simulate` uses)
// BM_AdjustedBeamNodalLowRank nodal coordinates, sparse M + low rank (the form
//                           for large models), same steps
// BM_OriginalBeamNodal2e-4  the original model at its own limit 1.5e-8 for
//                           2e-4 s (13,334 steps), for scale
// Rows are handed to an empty sink every 100 steps (the CSV writer's cost is
// the caller's; `mbfe simulate` writes at most ~10,000 rows by default).
#include <benchmark/benchmark.h>

#include "runtime/damping/beam_model.h"
#include "runtime/damping/beam_ode.h"
#include "runtime/structure/adjusted_parts.h"
#include "runtime/structure/nodal_beam_ode.h"
#include "runtime/integrators/integrator.h"
#include "runtime/integrators/simulation_driver.h"
#include "frontend/parse_model.h"

namespace {

using namespace mbfe;

const runtime::BeamModel& paper() {
  static const runtime::BeamModel b =
      runtime::analyse_beams(frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/paper_beam.yaml"));
  return b;
}

void run(benchmark::State& state, runtime::OdeSystem& ode, double h, double t_end) {
  runtime::SimulationOptions opt;
  opt.step = h;
  opt.t_end = t_end;
  opt.every = 100;
  const auto fe = runtime::parse_integrator("forward_euler");
  const Eigen::VectorXd y0 = Eigen::VectorXd::Zero(ode.size());
  double sink = 0.0;
  std::int64_t steps = 0;
  for (auto _ : state) {
    const auto r = runtime::run_simulation(ode, fe, y0, opt, [&](double, const Eigen::VectorXd& y) { sink += y[0]; });
    if (r.status != runtime::SimulationStatus::kCompleted) state.SkipWithError("did not complete");
    steps = r.steps;
  }
  benchmark::DoNotOptimize(sink);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["steps/s"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_AdjustedBeamModal(benchmark::State& state) {
  auto ode = runtime::modal_beam_ode(paper(), true);
  run(state, *ode, 1.4e-5, 1.0);
}
BENCHMARK(BM_AdjustedBeamModal)->Unit(benchmark::kMillisecond);

void BM_AdjustedBeamNodalLowRank(benchmark::State& state) {
  const auto& p = paper().beams.at(0);
  runtime::NodalBeamOde ode(std::make_shared<const runtime::LowRankStructure>(runtime::adjusted_parts(
                                p.system.name, {{0, static_cast<int>(p.system.M.rows())}}, p.system.M, p.system.K,
                                p.system.P, p.basis, p.adjusted)));
  state.counters["kept_modes"] = static_cast<double>(p.basis.omega.size() - p.adjusted.adjusted);
  run(state, ode, 1.4e-5, 1.0);
}
BENCHMARK(BM_AdjustedBeamNodalLowRank)->Unit(benchmark::kMillisecond);

void BM_OriginalBeamNodal2em4(benchmark::State& state) {
  const auto& p = paper().beams.at(0);
  runtime::NodalBeamOde ode(p.system.M, p.system.K, p.system.C, p.system.P);
  run(state, ode, 1.5e-8, 2e-4);
}
BENCHMARK(BM_OriginalBeamNodal2em4)->Unit(benchmark::kMillisecond);

void BM_AnalyseAndAdjust(benchmark::State& state) {
  const auto m = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/paper_beam.yaml");
  for (auto _ : state) benchmark::DoNotOptimize(runtime::analyse_beams(m));
}
BENCHMARK(BM_AnalyseAndAdjust)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
