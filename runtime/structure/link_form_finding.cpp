#include "runtime/structure/link_form_finding.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <sstream>

#include "runtime/fem/beam_system.h"
#include "runtime/errors/invalid_input.h"

namespace mbfe::runtime {

namespace {

/// N(s) of beam `b` as a sparse row over the model's beam DOFs.
Eigen::SparseVector<double> point_row(const BeamModel& beams, int b, double s) {
  const BeamPart& part = beams.beams[static_cast<std::size_t>(b)];
  const BeamPointWeights pw = point_weights(part.system, s);
  Eigen::SparseVector<double> row(beams.dof);
  for (int j = 0; j < 4; ++j)
    if (pw.free_index[j] >= 0 && pw.w[j] != 0.0) row.coeffRef(part.offset + pw.free_index[j]) += pw.w[j];
  return row;
}

}  // namespace

LinkFormFinding find_link_rest_offsets(const ir::Model& model, const BeamModel& beams) {
  const int n = beams.dof;
  const std::size_t nl = model.links.size();
  LinkFormFinding out;
  out.rest.resize(nl);
  out.tension.resize(nl);
  // A = K + sum k g g^T (every link taut), P the constant loads.
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
  for (const BeamPart& part : beams.beams) {
    const Eigen::SparseMatrix<double>& K = part.system.K;
    for (int c = 0; c < K.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it)
        t.emplace_back(part.offset + static_cast<int>(it.row()), part.offset + static_cast<int>(it.col()), it.value());
    p.segment(part.offset, part.system.P.size()) = part.system.P;
  }
  std::vector<Eigen::SparseVector<double>> ga(nl), g(nl);
  for (std::size_t l = 0; l < nl; ++l) {
    const ir::Link& link = model.links[l];
    ga[l] = point_row(beams, link.a.beam, link.a.at);
    g[l] = point_row(beams, link.b.beam, link.b.at) - ga[l];
    for (Eigen::SparseVector<double>::InnerIterator i(g[l]); i; ++i)
      for (Eigen::SparseVector<double>::InnerIterator j(g[l]); j; ++j)
        t.emplace_back(static_cast<int>(i.index()), static_cast<int>(j.index()), link.stiffness * i.value() * j.value());
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0.0))
    throw InvalidInput(model.source_path + ": the beams and their links have no static equilibrium (a beam or a "
                                           "span held by nothing); support every beam");
  // u = u0 + sum over held links of U_h rest_h.
  Eigen::VectorXd rhs = p;
  std::vector<std::size_t> held;
  for (std::size_t l = 0; l < nl; ++l) {
    if (model.links[l].hold) held.push_back(l);
    else rhs += model.links[l].stiffness * model.links[l].rest * Eigen::VectorXd(g[l]);
  }
  const Eigen::VectorXd u0 = ldlt.solve(rhs);
  const std::size_t m = held.size();
  Eigen::MatrixXd U(n, static_cast<Eigen::Index>(m));
  for (std::size_t h = 0; h < m; ++h)
    U.col(static_cast<Eigen::Index>(h)) = ldlt.solve(Eigen::VectorXd(model.links[held[h]].stiffness * g[held[h]]));
  Eigen::MatrixXd B(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
  Eigen::VectorXd target(static_cast<Eigen::Index>(m));
  for (std::size_t i = 0; i < m; ++i) {
    const Eigen::VectorXd row = Eigen::VectorXd(ga[held[i]]);
    target[static_cast<Eigen::Index>(i)] = *model.links[held[i]].hold - row.dot(u0);
    for (std::size_t h = 0; h < m; ++h) B(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(h)) = row.dot(U.col(static_cast<Eigen::Index>(h)));
  }
  Eigen::VectorXd rest_h = m > 0 ? Eigen::VectorXd(B.fullPivLu().solve(target)) : Eigen::VectorXd();
  for (std::size_t l = 0; l < nl; ++l) out.rest[l] = model.links[l].rest;
  for (std::size_t h = 0; h < m; ++h) out.rest[held[h]] = rest_h[static_cast<Eigen::Index>(h)];
  out.deflection = u0 + (m > 0 ? Eigen::VectorXd(U * rest_h) : Eigen::VectorXd::Zero(n));
  for (std::size_t l = 0; l < nl; ++l) {
    const ir::Link& link = model.links[l];
    out.tension[l] = link.stiffness * (Eigen::VectorXd(g[l]).dot(out.deflection) - out.rest[l]);
    if (link.slack && out.tension[l] < 0.0) {
      // The equilibrium above assumes every link taut: a slack one in
      // compression makes it wrong.
      std::ostringstream os;
      os << model.source_path << ":" << link.loc.line << ":" << link.loc.column << ": link '" << link.name
         << "' would have to push (tension " << out.tension[l] << " N)";
      if (link.hold) os << " to hold its point at " << *link.hold << " m";
      else os << " in the static equilibrium of the beams and links";
      os << "; a slack link only pulls";
      throw InvalidInput(os.str());
    }
  }
  return out;
}

}  // namespace mbfe::runtime
