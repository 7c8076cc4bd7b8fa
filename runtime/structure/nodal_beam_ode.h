// A beam M q'' + C q' + K q = P in nodal coordinates as an OdeSystem the
// integrators step: the original beam (sparse M, C, K) or its adjusted
// operators as a LowRankStructure (low_rank_structure.h: the low-rank form or
// eq (27) over every mode). The cross-check of the modal form
// (runtime/damping/beam_ode.h), and the form the coupled models step.
//
// The original beam solves with its factored M at every right-hand side and
// factorises a M + b C + c K once per distinct (a, b, c); the adjusted one
// needs no factorisation beyond its base matrix: its free acceleration and
// the inverse of any combination are closed forms over the kept modes.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <string>

#include "runtime/integrators/linear_second_order_system.h"
#include "runtime/structure/low_rank_structure.h"

namespace mbfe::runtime {

class NodalBeamOde final : public LinearSecondOrderSystem {
 public:
  /// Original model: M, K, C sparse (n x n), P (n). @throws std::invalid_argument
  /// on mismatched sizes, std::runtime_error if M is not positive definite.
  NodalBeamOde(const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
               const Eigen::SparseMatrix<double>& C, const Eigen::VectorXd& P);
  /// Adjusted model over a structure of one range starting at 0, under its
  /// constant load.
  explicit NodalBeamOde(std::shared_ptr<const LowRankStructure> adjusted);

  int dof() const override { return static_cast<int>(P_.size()); }
  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& ydot) override;
  void load(double, Eigen::VectorXd& out) override { out = P_; }
  void mult_m(const Eigen::VectorXd& x, Eigen::VectorXd& out) override;
  void mult_c(const Eigen::VectorXd& x, Eigen::VectorXd& out) override;
  void mult_k(const Eigen::VectorXd& x, Eigen::VectorXd& out) override;
  void solve_combination(double a, double b, double c, const Eigen::VectorXd& r, Eigen::VectorXd& x) override;
  std::string name(int i) const override;

 private:
  std::shared_ptr<const LowRankStructure> adjusted_;  // null: the original beam
  Eigen::SparseMatrix<double> M_, K_, C_;
  Eigen::VectorXd P_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> m_factor_;
  // The last (a, b, c) factorised (the original beam).
  double ca_ = 0.0, cb_ = 0.0, cc_ = 0.0;
  bool cached_ = false;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> a_factor_;
  LowRankStructure::Workspace ws_;
  Eigen::VectorXd w1_, w2_;
};

}  // namespace mbfe::runtime
