// Spatial models: the generated M and bias side by side with MuJoCo and RBDL
// in one binary, on the shipped 7-joint arm, 12-joint chain and 35-joint
// humanoid-shaped tree (docs/performance.md, "Spatial models against RBDL and
// MuJoCo"), and the generation of each.
//
// First, before anything is timed, every library's M and bias are checked
// against the generated kernels at the states the benchmark cycles through:
// M = M_lib and F - Q = bias_lib (with gravity; the models have no other
// load), to 1e-12 of the largest entry. A mismatch stops the binary with exit
// status 1 and the worst entry, so a figure can never come from two codes
// computing different things.
//
// What each benchmark does per iteration, at one of 64 random states:
//   Generated: the fused `dynamics` kernel (M dense, F, Q) and bias = F - Q;
//   MuJoCo:    mj_kinematics, mj_comPos, mj_crb, mj_comVel, mj_rne (M in its
//              sparse form qM, qfrc_bias), nothing else of mj_forward;
//   RBDL:      NonlinearEffects, then CompositeRigidBodyAlgorithm on the
//              joint transforms it left (one kinematic pass for both).
// The libraries get their own coordinates, converted once beforehand.
//
//   build/bin/spatial_baselines_bench --benchmark_repetitions=10 \
//       --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
//
// MuJoCo (Debian's libmujoco-dev) and RBDL (an installation given by
// -DMBFE_RBDL_DIR) are compiled in when CMake finds them; without them the
// generated kernels are timed alone and the binary says which is missing.
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "frontend/parse_model.h"
#include "generator/emit/generate_solver.h"
#include "ir/coordinate_layout.h"
#include "runtime/abi/mbfe_model_abi.h"
#include "tests/reference/spatial_baseline.h"
#include "tests/support/random_spatial_tree.h"
#ifdef MBFE_HAVE_MUJOCO
#include "tests/reference/mujoco_tree.h"
#endif
#ifdef MBFE_HAVE_RBDL
#include "tests/reference/rbdl_tree.h"
#endif

extern "C" {
const mbfe_model_v1* mbfe_model_arm7(void);
const mbfe_model_v1* mbfe_model_spatial_chain_12(void);
const mbfe_model_v1* mbfe_model_humanoid_35(void);
}

namespace {

using mbfe::reference::SpatialBaseline;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr int kStates = 64;  // states cycled through, so no call sees the same inputs twice in a row
// The generated kernels, MuJoCo and RBDL agree to at most 1.1e-14 of the
// largest entry on these models (tests/generator/spatial_baselines_test.cpp).
constexpr double kEqualTol = 1e-12;

struct Model {
  std::string name;
  mbfe::ir::Model ir;
  const mbfe_model_v1* solver;
  int nq, nv;
  std::vector<double> q, v;  // kStates states, mbfe's layout
};

Model load(const std::string& name, const mbfe_model_v1* solver) {
  Model m{name, mbfe::frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/" + name + ".yaml"), solver,
          0, 0, {}, {}};
  const mbfe::ir::CoordinateLayout layout = mbfe::ir::coordinate_layout(m.ir);
  m.nq = layout.num_positions;
  m.nv = layout.num_velocities;
  std::mt19937 rng(2026);
  for (int k = 0; k < kStates; ++k) {
    Eigen::VectorXd q, v;
    mbfe::test::random_state(rng, m.ir, layout, q, v);
    m.q.insert(m.q.end(), q.data(), q.data() + q.size());
    m.v.insert(m.v.end(), v.data(), v.data() + v.size());
  }
  return m;
}

/// A library's tree of a model with the states in its own coordinates.
struct Baseline {
  std::unique_ptr<SpatialBaseline> tree;
  std::vector<double> q, v;  // kStates native states
};

Baseline prepare(const Model& m, std::unique_ptr<SpatialBaseline> tree) {
  Baseline b{std::move(tree), {}, {}};
  const int nq = b.tree->native_positions(), nv = b.tree->native_velocities();
  b.q.resize(kStates * nq);
  b.v.resize(kStates * nv);
  for (int k = 0; k < kStates; ++k)
    b.tree->to_native(&m.q[k * m.nq], &m.v[k * m.nv], &b.q[k * nq], &b.v[k * nv]);
  return b;
}

double relative_difference(const Eigen::MatrixXd& got, const Eigen::MatrixXd& want) {
  return (got - want).cwiseAbs().maxCoeff() / std::max(1e-300, want.cwiseAbs().maxCoeff());
}

/// M and bias of `b` against the generated kernels at every state; false
/// (after saying where) on a mismatch.
bool equal_to_generated(const Model& m, Baseline& b) {
  const int nq = b.tree->native_positions(), nv = b.tree->native_velocities();
  double worst_M = 0, worst_bias = 0;
  for (int k = 0; k < kStates; ++k) {
    RowMajor M(m.nv, m.nv), M_lib(m.nv, m.nv);
    Eigen::VectorXd F(m.nv), Q(m.nv), bias(m.nv);
    m.solver->dynamics(&m.q[k * m.nq], &m.v[k * m.nv], 0.0, M.data(), F.data(), Q.data());
    b.tree->evaluate(&b.q[k * nq], &b.v[k * nv]);
    b.tree->result(M_lib.data(), bias.data());
    worst_M = std::max(worst_M, relative_difference(M, M_lib));
    worst_bias = std::max(worst_bias, relative_difference(F - Q, bias));
  }
  const bool equal = worst_M <= kEqualTol && worst_bias <= kEqualTol;
  std::printf("%-17s %-14s M %.1e, bias %.1e of the largest entry over %d states: %s\n", m.name.c_str(),
              b.tree->name().c_str(), worst_M, worst_bias, kStates, equal ? "equal" : "NOT EQUAL");
  return equal;
}

void generated(benchmark::State& state, const Model* m) {
  std::vector<double> M(m->nv * m->nv), F(m->nv), Q(m->nv), bias(m->nv);
  int i = 0;
  for (auto _ : state) {
    const int k = i++ % kStates;
    m->solver->dynamics(&m->q[k * m->nq], &m->v[k * m->nv], 0.0, M.data(), F.data(), Q.data());
    for (int j = 0; j < m->nv; ++j) bias[j] = F[j] - Q[j];
    benchmark::DoNotOptimize(M.data());
    benchmark::DoNotOptimize(bias.data());
    benchmark::ClobberMemory();
  }
}

void library(benchmark::State& state, Baseline* b) {
  const int nq = b->tree->native_positions(), nv = b->tree->native_velocities();
  int i = 0;
  for (auto _ : state) {
    const int k = i++ % kStates;
    b->tree->evaluate(&b->q[k * nq], &b->v[k * nv]);
    benchmark::ClobberMemory();
  }
}

// Derivation + CSE + emission, in process (no compilation); operation counts
// as counters.
void generation(benchmark::State& state, const Model* m) {
  mbfe::gen::GeneratedSolver solver;
  for (auto _ : state) {
    solver = mbfe::gen::generate_solver(m->ir);
    benchmark::DoNotOptimize(solver.files.data());
  }
  state.counters["ops_MFQ_emitted"] = static_cast<double>(solver.total_emitted());
  state.counters["ops_MFQ_executed"] = static_cast<double>(solver.total_executed());
  state.counters["ops_fused_emitted"] = static_cast<double>(solver.fused.emitted);
  state.counters["ops_fused_executed"] = static_cast<double>(solver.fused.executed);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  static std::vector<Model> models;
  models.push_back(load("arm7", mbfe_model_arm7()));
  models.push_back(load("spatial_chain_12", mbfe_model_spatial_chain_12()));
  models.push_back(load("humanoid_35", mbfe_model_humanoid_35()));

  static std::vector<std::vector<Baseline>> baselines(models.size());
  bool equal = true;
  for (std::size_t i = 0; i < models.size(); ++i) {
#ifdef MBFE_HAVE_MUJOCO
    baselines[i].push_back(prepare(models[i], std::make_unique<mbfe::reference::MujocoTree>(models[i].ir)));
#endif
#ifdef MBFE_HAVE_RBDL
    baselines[i].push_back(prepare(models[i], std::make_unique<mbfe::reference::RbdlTree>(models[i].ir)));
#endif
    for (Baseline& b : baselines[i]) equal = equal_to_generated(models[i], b) && equal;
  }
#ifndef MBFE_HAVE_MUJOCO
  std::printf("MuJoCo not compiled in (Debian libmujoco-dev, scripts/install-deps.sh): timing without it\n");
#endif
#ifndef MBFE_HAVE_RBDL
  std::printf("RBDL not compiled in (configure with -DMBFE_RBDL_DIR=<its install prefix>): timing without it\n");
#endif
  if (!equal) {
    std::fprintf(stderr, "spatial_baselines_bench: M or bias differ between the codes; nothing timed\n");
    return 1;
  }

  for (std::size_t i = 0; i < models.size(); ++i) {
    const Model* m = &models[i];
    benchmark::RegisterBenchmark(("BM_Generated/" + m->name).c_str(), generated, m);
    for (Baseline& b : baselines[i]) {
      const std::string library_name = b.tree->name().substr(0, b.tree->name().find(' '));
      benchmark::RegisterBenchmark(("BM_" + library_name + "/" + m->name).c_str(), library, &b);
    }
    benchmark::RegisterBenchmark(("BM_Generate/" + m->name).c_str(), generation, m)->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
