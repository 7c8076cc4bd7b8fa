// A small Euler-Bernoulli beam assembled here, independently of runtime/fem
// (textbook Hermite element matrices), for the coupled-system tests.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "runtime/coupled/augmented_system.h"
#include "runtime/coupled/coordinate_partitioning.h"

namespace mbfe::testing {

struct TestBeam {
  runtime::CoupledBeam beam;
  Eigen::SparseMatrix<double> K;  // N/m, free DOFs
  Eigen::SparseMatrix<double> C;  // N s/m
};

/// Pinned-pinned beam of `elements` Hermite elements: w = 0 at both ends.
/// q_gravity: transverse own-weight load per length (N/m). Rayleigh alpha, beta.
inline TestBeam pinned_pinned_beam(const std::string& name, double length, int elements,
                                   double EI, double rhoA, double q_gravity, double alpha,
                                   double beta) {
  const int nfull = 2 * (elements + 1);
  const double l = length / elements;
  Eigen::Matrix4d ke, me;
  ke << 12, 6 * l, -12, 6 * l, 6 * l, 4 * l * l, -6 * l, 2 * l * l, -12, -6 * l, 12, -6 * l,
      6 * l, 2 * l * l, -6 * l, 4 * l * l;
  ke *= EI / (l * l * l);
  me << 156, 22 * l, 54, -13 * l, 22 * l, 4 * l * l, 13 * l, -3 * l * l, 54, 13 * l, 156,
      -22 * l, -13 * l, -3 * l * l, -22 * l, 4 * l * l;
  me *= rhoA * l / 420.0;
  const Eigen::Vector4d fe = q_gravity * l * Eigen::Vector4d(0.5, l / 12, 0.5, -l / 12);
  std::vector<int> full_to_free(nfull);
  int nfree = 0;
  for (int i = 0; i < nfull; ++i) {
    const bool fixed = i == 0 || i == 2 * elements;
    full_to_free[i] = fixed ? -1 : nfree++;
  }
  Eigen::MatrixXd Md = Eigen::MatrixXd::Zero(nfree, nfree), Kd = Md;
  Eigen::VectorXd P = Eigen::VectorXd::Zero(nfree);
  for (int e = 0; e < elements; ++e) {
    for (int a = 0; a < 4; ++a) {
      const int ia = full_to_free[2 * e + a];
      if (ia < 0) continue;
      P(ia) += fe(a);
      for (int b = 0; b < 4; ++b) {
        const int ib = full_to_free[2 * e + b];
        if (ib < 0) continue;
        Md(ia, ib) += me(a, b);
        Kd(ia, ib) += ke(a, b);
      }
    }
  }
  TestBeam out;
  out.beam.mesh.name = name;
  out.beam.mesh.num_elements = elements;
  out.beam.mesh.element_length = l;
  out.beam.mesh.full_to_free = full_to_free;
  out.beam.mesh.num_free = nfree;
  out.beam.M = Md.sparseView();
  out.K = Kd.sparseView();
  out.C = (alpha * Md + beta * Kd).sparseView();
  out.beam.P = P;
  out.beam.C = out.C;
  out.beam.K = out.K;
  return out;
}

}  // namespace mbfe::testing
