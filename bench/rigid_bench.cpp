// Rigid chains: the generated solver against the hand-coded double pendulum,
// and how generation time, operation counts (emitted and executed per call)
// and evaluation time grow with N.
//
//   build/bin/rigid_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <random>
#include <vector>

#include "runtime/abi/mbfe_model_abi.h"
#include "generator/emit/generate_solver.h"
#include "frontend/parse_model.h"
#include "tests/reference/double_pendulum.h"

extern "C" {
const mbfe_model_v1* mbfe_model_double_pendulum(void);
const mbfe_model_v1* mbfe_model_chain_2(void);
const mbfe_model_v1* mbfe_model_chain_5(void);
const mbfe_model_v1* mbfe_model_chain_10(void);
const mbfe_model_v1* mbfe_model_chain_20(void);
}

namespace {

constexpr int kStates = 64;  // states cycled through, so no call sees the same inputs twice in a row

struct States {
  explicit States(int n) : q(kStates * n), qd(kStates * n) {
    std::mt19937 rng(2026);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    for (double& v : q) v = u(rng);
    for (double& v : qd) v = u(rng);
  }
  std::vector<double> q, qd;
};

// M + F + Q of the generated double pendulum (the fused kernel an integrator calls).
void BM_DoublePendulum_Generated(benchmark::State& state) {
  const mbfe_model_v1& m = *mbfe_model_double_pendulum();
  const States s(2);
  double M[4], F[2], Q[2];
  int i = 0;
  for (auto _ : state) {
    const int k = (i++ % kStates) * 2;
    m.dynamics(&s.q[k], &s.qd[k], 0.0, M, F, Q);
    benchmark::DoNotOptimize(M);
    benchmark::DoNotOptimize(F);
    benchmark::DoNotOptimize(Q);
  }
}
BENCHMARK(BM_DoublePendulum_Generated);

// The same through the three separate kernels (kinematics computed three times).
void BM_DoublePendulum_GeneratedSeparateKernels(benchmark::State& state) {
  const mbfe_model_v1& m = *mbfe_model_double_pendulum();
  const States s(2);
  double M[4], F[2], Q[2];
  int i = 0;
  for (auto _ : state) {
    const int k = (i++ % kStates) * 2;
    m.mass_matrix(&s.q[k], M);
    m.inertial_forces(&s.q[k], &s.qd[k], F);
    m.generalized_forces(&s.q[k], &s.qd[k], 0.0, Q);
    benchmark::DoNotOptimize(M);
    benchmark::DoNotOptimize(F);
    benchmark::DoNotOptimize(Q);
  }
}
BENCHMARK(BM_DoublePendulum_GeneratedSeparateKernels);

void BM_DoublePendulum_HandCoded(benchmark::State& state) {
  const mbfe::reference::DoublePendulumParams p;  // the values of models/double_pendulum.yaml
  const States s(2);
  int i = 0;
  for (auto _ : state) {
    const int k = (i++ % kStates) * 2;
    const Eigen::Vector2d q(s.q[k], s.q[k + 1]), qd(s.qd[k], s.qd[k + 1]);
    Eigen::Matrix2d M = mbfe::reference::mass_matrix(p, q);
    Eigen::Vector2d F = mbfe::reference::inertial_forces(p, q, qd);
    Eigen::Vector2d Q = mbfe::reference::generalized_forces(p, q);
    benchmark::DoNotOptimize(M);
    benchmark::DoNotOptimize(F);
    benchmark::DoNotOptimize(Q);
  }
}
BENCHMARK(BM_DoublePendulum_HandCoded);

const mbfe_model_v1* chain(int n) {
  switch (n) {
    case 2: return mbfe_model_chain_2();
    case 5: return mbfe_model_chain_5();
    case 10: return mbfe_model_chain_10();
    default: return mbfe_model_chain_20();
  }
}

// Derivation + CSE + emission of models/chain_N.yaml (no compilation).
void BM_Chain_Generate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const mbfe::ir::Model model =
      mbfe::frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/chain_" + std::to_string(n) + ".yaml");
  mbfe::gen::GeneratedSolver solver;
  for (auto _ : state) {
    solver = mbfe::gen::generate_solver(model);
    benchmark::DoNotOptimize(solver.files.data());
  }
  // Emitted: operations written in the source (M's assembly loop body once);
  // executed: per call (the loop body once per ancestor pair, N(N+1)/2 of them).
  auto kernel = [&](const char* name) {
    for (const auto& k : solver.operations)
      if (k.kernel == name) return k;
    return mbfe::gen::KernelOperations{};
  };
  state.counters["ops_M_emitted"] = static_cast<double>(kernel("mass_matrix").emitted);
  state.counters["ops_M_executed"] = static_cast<double>(kernel("mass_matrix").executed);
  state.counters["ops_F"] = static_cast<double>(kernel("inertial_forces").executed);
  state.counters["ops_Q"] = static_cast<double>(kernel("generalized_forces").executed);
  state.counters["ops_MFQ_emitted"] = static_cast<double>(solver.total_emitted());
  state.counters["ops_MFQ_executed"] = static_cast<double>(solver.total_executed());
  state.counters["ops_fused_emitted"] = static_cast<double>(solver.fused.emitted);
  state.counters["ops_fused_executed"] = static_cast<double>(solver.fused.executed);
}
BENCHMARK(BM_Chain_Generate)->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

// One evaluation of M, F, Q (fused kernel) of the generated chain.
void BM_Chain_Evaluate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const mbfe_model_v1& m = *chain(n);
  const States s(n);
  std::vector<double> M(n * n), F(n), Q(n);
  int i = 0;
  for (auto _ : state) {
    const int k = (i++ % kStates) * n;
    m.dynamics(&s.q[k], &s.qd[k], 0.0, M.data(), F.data(), Q.data());
    benchmark::DoNotOptimize(M.data());
    benchmark::DoNotOptimize(F.data());
    benchmark::DoNotOptimize(Q.data());
  }
}
BENCHMARK(BM_Chain_Evaluate)->Arg(2)->Arg(5)->Arg(10)->Arg(20);

}  // namespace

BENCHMARK_MAIN();
