// The paper's platform (models/paper_platform.yaml: 4 rigid coordinates, two
// beams of 100 DOFs, a pin and a slider-pin), adjusted damping, forward Euler
// at 0.95 x the limit of the linearised partitioned system, 1 s simulated.
// Target: under 0.5 s wall on a 2-core machine (docs/performance.md).
//
//   build/bench/paper_platform_bench         (or build/bin/paper_platform_bench)
//
// BM_PaperPlatform1s         the whole run (partitioned formulation; rows to an
//                            empty sink every 100 steps)
// BM_RhsPartitioned          one right-hand side (= one forward-Euler step)
// BM_PartMultibody           its multibody share: the generated M, F, Q kernel
// BM_PartBeams               its beam share: M_c^-1 (P - C q' - K q) for both
//                            beams (adjusted, low rank: no solve with M_c)
// BM_PartConstraints         its constraint share: Phi, J_b, J_c, gamma of the
//                            contacts (generated kernels + element lookup)
// What the right-hand side costs beyond the three parts is the partitioning
// itself (Newton closure of v, W = M_c^-1 J_c^T, H, the small dense solves of
// eqs (16)-(17)); docs/performance.md books it under constraints.
#include <benchmark/benchmark.h>

#include <memory>

#include "api/solver_cache.h"
#include "runtime/simulation/assembled_model.h"
#include "runtime/integrators/integrator.h"
#include "runtime/coupled/augmented_system.h"
#include "runtime/coupled/coordinate_partitioning.h"
#include "runtime/integrators/simulation_driver.h"
#include "frontend/parse_model.h"
#include "runtime/coupled/linearization.h"
#include "runtime/stability/step_limits.h"

namespace {

using namespace mbfe;

// The platform's dynamics (adjusted beams) and initial coordinates.
struct CoupledModel {
  std::shared_ptr<runtime::AssembledModel> assembled;
  std::shared_ptr<runtime::CoupledDynamics> dynamics;
  Eigen::VectorXd q0, qd0;
};

struct Setup {
  ir::Model model;
  CoupledModel cm;
  double h = 0.0;
};

Setup& setup() {
  static Setup* s = [] {
    auto* out = new Setup;
    out->model = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/paper_platform.yaml");
    out->cm.assembled =
        std::make_shared<runtime::AssembledModel>(out->model, load_solver(out->model, /*quiet=*/true).model);
    out->cm.dynamics = out->cm.assembled->make_dynamics(/*adjusted=*/true);
    out->cm.assembled->initial_coordinates(out->cm.q0, out->cm.qd0);
    const auto spectrum = runtime::linearized_spectrum(out->cm.dynamics, 0.0, out->cm.q0, out->cm.qd0);
    out->h = 0.95 * runtime::stable_step(runtime::parse_integrator("forward_euler"), spectrum.eigenvalues).h;
    return out;
  }();
  return *s;
}

void BM_PaperPlatform1s(benchmark::State& state) {
  Setup& s = setup();
  runtime::SimulationOptions opt;
  opt.step = s.h;
  opt.t_end = 1.0;
  opt.every = 100;
  opt.divergence_factor = 1e4;
  const auto fe = runtime::parse_integrator("forward_euler");
  double sink = 0.0;
  std::int64_t steps = 0;
  for (auto _ : state) {
    runtime::PartitionedSystem sys(s.cm.dynamics);
    const Eigen::VectorXd y0 = sys.initial_state(0.0, s.cm.q0, s.cm.qd0);
    const auto r = runtime::run_simulation(sys, fe, y0, opt, [&](double, const Eigen::VectorXd& y) { sink += y[0]; });
    if (r.status != runtime::SimulationStatus::kCompleted) state.SkipWithError(r.message.c_str());
    steps = r.steps;
  }
  benchmark::DoNotOptimize(sink);
  state.counters["h"] = s.h;
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["us/step"] = benchmark::Counter(static_cast<double>(steps) * 1e-6,
                                                 benchmark::Counter::kIsIterationInvariantRate |
                                                     benchmark::Counter::kInvert);
}
BENCHMARK(BM_PaperPlatform1s)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// A state a few milliseconds into the run, so that beams are deformed and moving.
struct MidState {
  std::unique_ptr<runtime::PartitionedSystem> sys;
  Eigen::VectorXd y, q, qd;
};

MidState& mid() {
  static MidState* m = [] {
    Setup& s = setup();
    auto* out = new MidState;
    out->sys = std::make_unique<runtime::PartitionedSystem>(s.cm.dynamics);
    out->y = out->sys->initial_state(0.0, s.cm.q0, s.cm.qd0);
    Eigen::VectorXd yd(out->y.size());
    for (int i = 0; i < 200; ++i) {
      out->sys->rhs(i * s.h, out->y, yd);
      out->y += s.h * yd;
      out->sys->after_step((i + 1) * s.h, out->y);
    }
    out->sys->full_state(200 * s.h, out->y, out->q, out->qd);
    return out;
  }();
  return *m;
}

void BM_RhsPartitioned(benchmark::State& state) {
  MidState& m = mid();
  Eigen::VectorXd yd(m.y.size());
  for (auto _ : state) {
    m.sys->rhs(0.01, m.y, yd);
    benchmark::DoNotOptimize(yd.data());
  }
}
BENCHMARK(BM_RhsPartitioned)->Unit(benchmark::kMicrosecond);

void BM_PartMultibody(benchmark::State& state) {
  Setup& s = setup();
  MidState& m = mid();
  const mbfe_model_v1& model = *s.cm.assembled->kernels();
  const int nb = model.num_coordinates;
  std::vector<double> M(nb * nb), F(nb), Q(nb);
  for (auto _ : state) {
    model.dynamics(m.q.data(), m.qd.data(), 0.01, M.data(), F.data(), Q.data());
    benchmark::DoNotOptimize(M.data());
  }
}
BENCHMARK(BM_PartMultibody)->Unit(benchmark::kMicrosecond);

void BM_PartBeams(benchmark::State& state) {
  Setup& s = setup();
  MidState& m = mid();
  const runtime::CoupledModel& model = s.cm.dynamics->model();
  const int nb = model.nb();
  Eigen::VectorXd a = Eigen::VectorXd::Zero(model.nc()), f;
  std::vector<runtime::LowRankStructure::Workspace> ws;
  for (const auto& st : model.structures()) ws.push_back(st->make_workspace());
  for (auto _ : state) {
    // The adjusted beams' free accelerations M_adj^-1 (P - C q' - K q) (a
    // closed form over the kept modes), the others' by a solve with M.
    for (std::size_t k = 0; k < model.structures().size(); ++k)
      model.structures()[k]->free_acceleration(m.q.data() + nb, m.qd.data() + nb, model.loads().data(), a.data(),
                                                ws[k]);
    for (std::size_t k = 0; k < model.beams().size(); ++k) {
      const runtime::CoupledBeam& b = model.beams()[k];
      if (b.structure >= 0) continue;
      f = b.P - b.C * m.qd.segment(nb + b.offset, b.mesh.num_free) - b.K * m.q.segment(nb + b.offset, b.mesh.num_free);
      a.segment(b.offset, b.mesh.num_free) = model.mass_factor(static_cast<int>(k)).solve(f);
    }
    benchmark::DoNotOptimize(a.data());
  }
}
BENCHMARK(BM_PartBeams)->Unit(benchmark::kMicrosecond);

void BM_PartConstraints(benchmark::State& state) {
  Setup& s = setup();
  MidState& m = mid();
  const auto& cc = s.cm.dynamics->constraints();
  const int nb = s.cm.dynamics->nb();
  runtime::ConstraintValues cv;
  for (auto _ : state) {
    cc.evaluate(0.01, m.q.data(), m.q.data() + nb, m.qd.data(), m.qd.data() + nb, cv);
    benchmark::DoNotOptimize(cv.phi.data());
  }
}
BENCHMARK(BM_PartConstraints)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
