// The generated loop kernels (`constraints:`), planar and spatial, against
// two oracles: Phi against the rows written from the definitions of
// docs/model-format.md with independent forward kinematics
// (tests/support/spatial_oracle.h, and a planar one here), and J and gamma
// against finite differences of Phi along the velocity coordinates:
//   J = dPhi(q (+) h e_j)/dh,   gamma = -d^2 Phi(q (+) s v)/ds^2 at v' = 0.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "api/solver_cache.h"
#include "frontend/parse_model.h"
#include "tests/support/random_spatial_tree.h"
#include "tests/support/spatial_oracle.h"

namespace mbfe {
namespace {

using test::vec;

// Phi from the kernel and from the oracle: the same arithmetic in another
// order, a few hundred ulps of O(1) positions.
constexpr double kSameArithmeticTol = 1e-13;
// Central differences of the generated Phi (O(1) values): h = 1e-5 gives
// ~1e-10 for J; the second difference with h = 1e-4 gives ~1e-8 for gamma.
constexpr double kJacobianTol = 1e-8;
constexpr double kGammaTol = 1e-6;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// n1, n2 with (n1, n2, axis) right-handed: n1 = axis x e / |axis x e|, e the
/// coordinate axis least aligned with `axis` (docs/model-format.md).
std::pair<Eigen::Vector3d, Eigen::Vector3d> perpendicular_pair(const Eigen::Vector3d& axis) {
  Eigen::Index least = 0;
  axis.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d n1 = axis.cross(Eigen::Vector3d::Unit(least)).normalized();
  return {n1, axis.cross(n1)};
}

/// The planar body frames: origin (x, y, 0) and rotation about z.
struct PlanarFrame {
  Eigen::Vector3d origin;
  Eigen::Matrix3d rotation;
};

PlanarFrame planar_frame(const ir::Model& m, const Eigen::VectorXd& q, int body) {
  if (body < 0) return {Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
  std::vector<PlanarFrame> frames;
  std::vector<double> angles;
  for (std::size_t i = 0; i <= static_cast<std::size_t>(body); ++i) {
    const ir::Body& b = m.bodies[i];
    const double pa = b.parent < 0 ? 0.0 : angles[b.parent];
    const PlanarFrame parent = b.parent < 0 ? PlanarFrame{Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()}
                                            : frames[b.parent];
    Eigen::Vector3d at(b.joint.at[0], b.joint.at[1], 0.0);
    if (b.joint.type == ir::JointType::kPrismatic) at += q[i] * Eigen::Vector3d(b.joint.axis[0], b.joint.axis[1], 0.0);
    const double angle = b.joint.type == ir::JointType::kRevolute ? pa + q[i] : pa;
    angles.push_back(angle);
    frames.push_back({parent.origin + parent.rotation * at,
                      Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix()});
  }
  return frames[body];
}

/// Phi from the definitions, for a planar or a spatial model.
Eigen::VectorXd oracle_phi(const ir::Model& m, const Eigen::VectorXd& q) {
  const ir::CoordinateLayout layout = ir::coordinate_layout(m);
  std::vector<double> rows;
  for (const ir::LoopConstraint& loop : m.constraints) {
    auto frame = [&](int body) {
      if (m.dimension != 3) return planar_frame(m, q, body);
      return PlanarFrame{body < 0 ? Eigen::Vector3d::Zero() : test::spatial_pose(m, layout, q).origin[body],
                         test::body_rotation(m, layout, q, body)};
    };
    const PlanarFrame a = frame(loop.a.body), b = frame(loop.b.body);
    const Eigen::Vector3d pa = a.origin + a.rotation * vec(loop.a.at), pb = b.origin + b.rotation * vec(loop.b.at);
    const Eigen::Vector3d axis = vec(loop.axis), d = pb - pa;
    if (m.dimension != 3) {
      if (loop.type != ir::LoopType::kPrismatic) {
        rows.insert(rows.end(), {pa.x() - pb.x(), pa.y() - pb.y()});
      } else {
        const Eigen::Vector3d n = Eigen::Vector3d::UnitZ().cross(axis);
        rows.insert(rows.end(), {(a.rotation * n).dot(d), (a.rotation * n).dot(b.rotation * axis)});
      }
      continue;
    }
    const auto [n1, n2] = perpendicular_pair(axis);
    if (loop.type != ir::LoopType::kPrismatic) rows.insert(rows.end(), {pa.x() - pb.x(), pa.y() - pb.y(), pa.z() - pb.z()});
    if (loop.type == ir::LoopType::kRevolute)
      rows.insert(rows.end(), {(a.rotation * axis).dot(b.rotation * n1), (a.rotation * axis).dot(b.rotation * n2)});
    if (loop.type == ir::LoopType::kPrismatic)
      rows.insert(rows.end(), {(a.rotation * n1).dot(d), (a.rotation * n2).dot(d),
                               (a.rotation * axis).dot(b.rotation * n1), (a.rotation * axis).dot(b.rotation * n2),
                               (a.rotation * n1).dot(b.rotation * n2)});
  }
  return Eigen::Map<const Eigen::VectorXd>(rows.data(), static_cast<Eigen::Index>(rows.size()));
}

void expect_close(const Eigen::MatrixXd& got, const Eigen::MatrixXd& want, double tol, const std::string& what) {
  const double scale = std::max(1.0, want.cwiseAbs().maxCoeff());
  EXPECT_LT((got - want).cwiseAbs().maxCoeff() / scale, tol) << what << "\ngot:\n" << got << "\nwant:\n" << want;
}

/// The kernels of `m` at `trials` random states against both oracles.
void check_loops(const ir::Model& m, std::mt19937& rng, int trials) {
  const ir::CoordinateLayout layout = ir::coordinate_layout(m);
  const LoadedSolver solver = load_solver(m, /*quiet=*/true);
  const mbfe_model_v1& k = *solver.model;
  const int nv = layout.num_velocities;
  const int nc = k.num_loop_rows;
  ASSERT_EQ(k.num_loops, static_cast<int>(m.constraints.size()));
  int rows = 0;
  for (int l = 0; l < k.num_loops; ++l) {
    EXPECT_EQ(k.loops[l].name, m.constraints[l].name);
    EXPECT_EQ(k.loops[l].first_row, rows);
    EXPECT_EQ(k.loops[l].rows, ir::loop_rows(m.constraints[l].type, m.dimension));
    rows += k.loops[l].rows;
  }
  ASSERT_EQ(nc, rows);
  auto phi = [&](const Eigen::VectorXd& q) {
    Eigen::VectorXd out(nc);
    k.loop_constraints(q.data(), out.data());
    return out;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int trial = 0; trial < trials; ++trial) {
    Eigen::VectorXd q, v;
    test::random_state(rng, m, layout, q, v);
    expect_close(phi(q), oracle_phi(m, q), kSameArithmeticTol, "Phi");

    RowMajor J = RowMajor::Constant(nc, nv, nan);
    k.loop_jacobian(q.data(), J.data());
    Eigen::MatrixXd J_oracle(nc, nv);
    const double h = test::kFirstStep;
    for (int j = 0; j < nv; ++j) {
      const Eigen::VectorXd e = Eigen::VectorXd::Unit(nv, j) * h;
      J_oracle.col(j) = (phi(test::step_positions(m, layout, q, e)) - phi(test::step_positions(m, layout, q, -e))) /
                        (2 * h);
    }
    expect_close(J, J_oracle, kJacobianTol, "J");

    Eigen::VectorXd gamma = Eigen::VectorXd::Constant(nc, nan);
    k.loop_gamma(q.data(), v.data(), gamma.data());
    const double s = test::kSecondStep;
    const Eigen::VectorXd second = (phi(test::step_positions(m, layout, q, s * v)) - 2 * phi(q) +
                                    phi(test::step_positions(m, layout, q, -s * v))) /
                                   (s * s);
    expect_close(gamma, -second, kGammaTol, "gamma");
  }
}

/// A random loop of each kind between random bodies (and the ground).
std::string random_constraints(std::mt19937& rng, int bodies, int dimension) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto point = [&] {
    return dimension == 3 ? test::numbers({u(rng), u(rng), u(rng)}) : test::numbers({u(rng), u(rng)});
  };
  std::ostringstream y;
  y << "constraints:\n";
  const char* types[] = {"point", "revolute", "prismatic"};
  for (int l = 0; l < 4; ++l) {
    const int a = static_cast<int>(rng() % bodies), b = (a + 1 + static_cast<int>(rng() % (bodies - 1))) % bodies;
    const char* type = types[l % 3];
    const bool axis = std::string(type) == "prismatic" || (dimension == 3 && std::string(type) == "revolute");
    y << "  - {name: loop" << l << ", type: " << type << ", a: {body: " << (l == 3 ? "ground" : "b" + std::to_string(a))
      << ", at: " << point() << "}, b: {body: b" << b << ", at: " << point() << "}"
      << (axis ? ", axis: " + point() : "") << "}\n";
  }
  return y.str();
}

std::string random_planar_tree(std::mt19937& rng, int bodies) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.1, 2.0);
  std::ostringstream y;
  y.precision(17);
  y << "model: random_planar_loops\ngravity: [0, -9.81]\nbodies:\n";
  for (int i = 0; i < bodies; ++i) {
    const int parent = i == 0 ? -1 : static_cast<int>(rng() % i);
    y << "  - {name: b" << i << ", parent: " << (parent < 0 ? "ground" : "b" + std::to_string(parent))
      << ", joint: {type: " << (rng() % 3 == 0 ? "prismatic, axis: " + test::numbers({u(rng), u(rng)}) + ", "
                                               : std::string("revolute, "))
      << "at: " << test::numbers({u(rng), u(rng)}) << "}, mass: " << pos(rng) << ", inertia: " << pos(rng) << "}\n";
  }
  return y.str();
}

TEST(GeneratedLoopConstraints, PlanarLoopsMatchOracles) {
  std::mt19937 rng(3141);
  for (int bodies : {2, 5}) {
    SCOPED_TRACE(bodies);
    const std::string yaml = random_planar_tree(rng, bodies) + random_constraints(rng, bodies, 2);
    check_loops(frontend::parse_model_text(yaml, "planar_loops.yaml"), rng, 10);
  }
}

TEST(GeneratedLoopConstraints, SpatialLoopsMatchOracles) {
  std::mt19937 rng(2718);
  for (bool quaternions : {false, true}) {
    SCOPED_TRACE(quaternions);
    const int bodies = 4;
    const std::string yaml =
        test::random_spatial_tree_yaml(rng, bodies, quaternions) + random_constraints(rng, bodies, 3);
    check_loops(frontend::parse_model_text(yaml, "spatial_loops.yaml"), rng, 10);
  }
}

}  // namespace
}  // namespace mbfe
