// Generated M and bias of spatial models against two numerical rigid-body
// libraries, built from the same model file by code of their own
// (tests/reference/): MuJoCo (Debian's libmujoco-dev; built when CMake finds
// it) and RBDL (when configured with -DMBFE_RBDL_DIR=<its install prefix>).
// Random trees (hinges and sliders about skew axes, joint rotations, full
// inertia tensors, a free root and a ball joint) and the shipped models the
// benchmark times (docs/performance.md, "Spatial models against RBDL and
// MuJoCo"), each at random states:
//   M = M_lib,  F - Q = bias_lib (gravity on),  F = bias_lib (gravity off),
// to 1e-12 of the largest entry.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <memory>
#include <random>
#include <string>

#include "api/solver_cache.h"
#include "frontend/parse_model.h"
#include "ir/coordinate_layout.h"
#include "runtime/abi/mbfe_model_abi.h"
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

namespace mbfe {
namespace {

// Three codes of the same recursions in different orders and bases: they
// agree to a few dozen ulps of the largest entry (measured: at most 1.1e-14).
constexpr double kEqualTol = 1e-12;
constexpr int kStates = 10;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using MakeBaseline = std::unique_ptr<reference::SpatialBaseline> (*)(const ir::Model&);

double relative_difference(const Eigen::MatrixXd& got, const Eigen::MatrixXd& want) {
  return (got - want).cwiseAbs().maxCoeff() / std::max(1e-300, want.cwiseAbs().maxCoeff());
}

/// The generated kernels `k` of `m` against `make(m)` at random states.
void check_model(const ir::Model& m, const mbfe_model_v1& k, MakeBaseline make, std::mt19937& rng) {
  const ir::CoordinateLayout layout = ir::coordinate_layout(m);
  const int nv = layout.num_velocities;
  ASSERT_EQ(k.num_coordinates, layout.num_positions);
  ASSERT_EQ(k.num_velocities, nv);
  std::unique_ptr<reference::SpatialBaseline> lib = make(m);
  SCOPED_TRACE(lib->name());
  Eigen::VectorXd native_q(lib->native_positions()), native_v(lib->native_velocities());
  for (int trial = 0; trial < kStates; ++trial) {
    Eigen::VectorXd q, v;
    test::random_state(rng, m, layout, q, v);
    RowMajor M(nv, nv), M_lib(nv, nv);
    Eigen::VectorXd F(nv), Q(nv), bias(nv), bias_off(nv);
    k.dynamics(q.data(), v.data(), 0.0, M.data(), F.data(), Q.data());
    lib->to_native(q.data(), v.data(), native_q.data(), native_v.data());
    lib->set_gravity(false);
    lib->evaluate(native_q.data(), native_v.data());
    lib->result(M_lib.data(), bias_off.data());
    lib->set_gravity(true);
    lib->evaluate(native_q.data(), native_v.data());
    lib->result(M_lib.data(), bias.data());
    EXPECT_LT(relative_difference(M, M_lib), kEqualTol) << "M\ngot:\n" << M << "\nwant:\n" << M_lib;
    EXPECT_LT(relative_difference(F, bias_off), kEqualTol) << "F\ngot: " << F.transpose() << "\nwant: "
                                                          << bias_off.transpose();
    EXPECT_LT(relative_difference(F - Q, bias), kEqualTol) << "F - Q\ngot: " << (F - Q).transpose() << "\nwant: "
                                                           << bias.transpose();
  }
}

/// A random tree of tests/support/random_spatial_tree.h without its loads
/// (the libraries' bias holds gravity only).
ir::Model random_tree(std::mt19937& rng, int bodies, bool quaternions) {
  std::string yaml = test::random_spatial_tree_yaml(rng, bodies, quaternions);
  yaml.erase(yaml.find("loads:"));
  return frontend::parse_model_text(yaml, "tree.yaml");
}

// Two trees, because each is compiled at run time (about 3 s each on the
// 2-core CI machine; the solver cache keeps them for the next test).
void check_random_trees(MakeBaseline make) {
  std::mt19937 rng(20261124);
  for (bool quaternions : {false, true}) {
    const int bodies = quaternions ? 5 : 6;
    SCOPED_TRACE(std::to_string(bodies) + (quaternions ? " bodies, free root and a ball joint" : " bodies"));
    const ir::Model m = random_tree(rng, bodies, quaternions);
    const LoadedSolver solver = load_solver(m, /*quiet=*/true);
    check_model(m, *solver.model, make, rng);
  }
}

void check_shipped_models(MakeBaseline make) {
  std::mt19937 rng(7);
  const struct {
    const char* file;
    const mbfe_model_v1* solver;
  } models[] = {{"arm7", mbfe_model_arm7()},
                {"spatial_chain_12", mbfe_model_spatial_chain_12()},
                {"humanoid_35", mbfe_model_humanoid_35()}};
  for (const auto& model : models) {
    SCOPED_TRACE(model.file);
    const ir::Model m = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/" + model.file + ".yaml");
    ASSERT_TRUE(m.loads.empty()) << "the libraries' bias holds gravity only";
    check_model(m, *model.solver, make, rng);
  }
}

#ifdef MBFE_HAVE_MUJOCO
std::unique_ptr<reference::SpatialBaseline> make_mujoco(const ir::Model& m) {
  return std::make_unique<reference::MujocoTree>(m);
}

TEST(SpatialBaselines, RandomTreesMatchMujoco) { check_random_trees(make_mujoco); }
TEST(SpatialBaselines, ShippedModelsMatchMujoco) { check_shipped_models(make_mujoco); }
#endif

#ifdef MBFE_HAVE_RBDL
std::unique_ptr<reference::SpatialBaseline> make_rbdl(const ir::Model& m) {
  return std::make_unique<reference::RbdlTree>(m);
}

TEST(SpatialBaselines, RandomTreesMatchRbdl) { check_random_trees(make_rbdl); }
TEST(SpatialBaselines, ShippedModelsMatchRbdl) { check_shipped_models(make_rbdl); }
#endif

}  // namespace
}  // namespace mbfe
