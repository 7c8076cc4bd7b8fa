#include "runtime/structure/joined_structures.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>

#include "runtime/modal/modal_analysis.h"
#include "runtime/structure/adjusted_parts.h"
#include "runtime/structure/beam_links.h"
#include "runtime/structure/coupled_beam.h"

namespace mbfe::runtime {

namespace {

bool joined_scope(const ir::Beam& b) {
  return b.adjustment.active() && b.adjustment.scope == ir::AdjustmentScope::kJoined;
}

int root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

void add_block(const Eigen::SparseMatrix<double>& A, int offset, double scale,
               std::vector<Eigen::Triplet<double>>& out) {
  for (int col = 0; col < A.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it)
      out.emplace_back(offset + static_cast<int>(it.row()), offset + static_cast<int>(it.col()), scale * it.value());
}

// The slack links inside a structure act as forces that take away their
// exact linear part k g g^T from the adjusted K. With the slack links in a
// set S slack, K_adj - sum_S k g g^T is positive definite exactly when the
// eigenvalues of [sqrt(k_a k_b) g_a^T K_adj^-1 g_b] over S lie below 1, and
// every subset's lie below the whole set's largest (interlacing): that one
// number decides for every combination. With every mode,
// K^-1 = Phi diag(1 / k_j) Phi^T; with the modes up to the cap and the first
// beyond (the sliced path), every mode left out has k* and
// K_adj^-1 = M^-1 / k* + sum over the basis of (1 / k_j - 1 / k*) phi_j phi_j^T,
// and the original K^-1 is a sparse solve.
double slack_stiffness_ratio(const ir::Model& model, const JoinedStructure& s, const std::vector<BeamMesh>& meshes,
                             const std::vector<int>& offsets, const Eigen::SparseMatrix<double>& M,
                             const Eigen::SparseMatrix<double>& K, bool adjusted) {
  std::vector<int> slack;
  for (int l : s.links)
    if (model.links[l].slack) slack.push_back(l);
  if (slack.empty()) return 0.0;
  const int ns = static_cast<int>(slack.size());
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(s.dof, ns);  // sqrt(k) g per slack link
  for (int a = 0; a < ns; ++a) {
    const ir::Link& link = model.links[slack[a]];
    const LinkGradient grad = link_gradient(link, meshes, offsets);
    for (int i = 0; i < grad.size; ++i) g(grad.cols[i], a) += std::sqrt(link.stiffness) * grad.values[i];
  }
  const Eigen::Index nb = s.basis.omega.size();
  const auto modal_k = [&](Eigen::Index j) { return adjusted ? s.adjusted.modes[j].k : s.original[j].k; };
  Eigen::MatrixXd ratio;
  if (s.basis.complete) {
    Eigen::MatrixXd pg = s.basis.phi.transpose() * g;  // Phi^T g sqrt(k) / sqrt(k_j)
    for (Eigen::Index j = 0; j < nb; ++j) {
      if (!(modal_k(j) > 0.0)) return std::numeric_limits<double>::infinity();  // no stiffness along mode j
      pg.row(j) /= std::sqrt(modal_k(j));
    }
    ratio = pg.transpose() * pg;
  } else if (adjusted) {
    const double k_star = s.adjusted.k_star;
    if (!(k_star > 0.0)) return std::numeric_limits<double>::infinity();
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> mass(M);
    if (mass.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
    const Eigen::MatrixXd minv_g = mass.solve(g);
    ratio = (g.transpose() * minv_g) / k_star;
    const Eigen::MatrixXd pg = s.basis.phi.transpose() * g;
    for (Eigen::Index j = 0; j < nb; ++j) {
      if (!(modal_k(j) > 0.0)) return std::numeric_limits<double>::infinity();
      const double w = 1.0 / modal_k(j) - 1.0 / k_star;
      if (w != 0.0) ratio.noalias() += w * pg.row(j).transpose() * pg.row(j);
    }
  } else {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> stiffness(K);
    if (stiffness.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
    ratio = g.transpose() * stiffness.solve(g);
  }
  if (!ratio.allFinite()) return std::numeric_limits<double>::infinity();
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(ratio, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
}

JoinedStructure analyse(const ir::Model& model, const BeamModel& beams, std::vector<int> members,
                        int dense_limit) {
  JoinedStructure s;
  s.beams = std::move(members);
  std::vector<int> offsets(beams.beams.size(), 0);
  std::vector<BeamMesh> meshes;
  for (const BeamPart& b : beams.beams) meshes.push_back(beam_mesh(b.system));
  for (int b : s.beams) {
    offsets[b] = s.dof;
    s.dof += static_cast<int>(beams.beams[b].system.M.rows());
  }
  const std::string name = joined_name(model, s.beams);
  const auto member = [&](int b) { return std::find(s.beams.begin(), s.beams.end(), b) != s.beams.end(); };
  std::vector<Eigen::Triplet<double>> tm, tk, tc;
  for (int b : s.beams) {
    const BeamSystem& sys = beams.beams[b].system;
    add_block(sys.M, offsets[b], 1.0, tm);
    add_block(sys.K, offsets[b], 1.0, tk);
    add_block(sys.C, offsets[b], 1.0, tc);
  }
  // The links inside, taut: k g g^T in K_s. Their dampers stay out of C_s
  // and act as exact forces: a slack link takes its damper away, and C_adj,
  // which holds only the diagonal of Phi^T C_s Phi, could not give it back
  // without going indefinite.
  for (int l = 0; l < static_cast<int>(model.links.size()); ++l) {
    const ir::Link& link = model.links[l];
    if (!member(link.a.beam) || !member(link.b.beam)) continue;
    s.links.push_back(l);
    const LinkGradient g = link_gradient(link, meshes, offsets);
    for (int i = 0; i < g.size; ++i)
      for (int j = 0; j < g.size; ++j)
        tk.emplace_back(g.cols[i], g.cols[j], link.stiffness * g.values[i] * g.values[j]);
  }
  Eigen::SparseMatrix<double> M(s.dof, s.dof), K(s.dof, s.dof), C(s.dof, s.dof);
  M.setFromTriplets(tm.begin(), tm.end());
  K.setFromTriplets(tk.begin(), tk.end());
  C.setFromTriplets(tc.begin(), tc.end());
  const ir::Adjustment& adjustment = model.beams[s.beams.front()].adjustment;
  if (s.dof <= dense_limit) {
    s.basis = modal_dense(M, K);
  } else {
    // Beyond the dense path: every mode the cap keeps and the first it
    // changes (a kept mode has |r_fast| <= omega_limit, so omega <= omega_limit).
    // Links only add stiffness, so the members' lowest eigenvalues bound the
    // structure's from below.
    SlicedModalOptions sliced;
    sliced.lower = 0.0;
    for (int b : s.beams) sliced.lower = std::min(sliced.lower, shift_below_lowest(beams.beams[b].system));
    try {
      s.basis = modal_below(M, K, adjustment.omega_limit, sliced);
    } catch (const std::exception& e) {
      throw JoinedStructureError(s.beams.front(), "the joined structure " + name + " has " + std::to_string(s.dof) +
                                                      " DOFs, beyond the dense modal analysis (" +
                                                      std::to_string(dense_limit) + "), and the modes its cap keeps "
                                                      "could not be found (" + e.what() +
                                                      "); run the original model (adjust off)");
    }
  }
  const int k = static_cast<int>(s.basis.omega.size());
  // Modal damping: the diagonal of Phi^T C_s Phi. The beams' Rayleigh C is
  // not alpha M_s + beta K_s once links join them (beta k g g^T is missing),
  // so Phi^T C_s Phi has off-diagonal entries, not small next to its
  // diagonal; the modal form drops them (docs/catenary.md).
  const Eigen::MatrixXd c_phi = C * s.basis.phi;
  s.original.resize(k);
  for (int j = 0; j < k; ++j) {
    const double w = s.basis.omega[j];
    s.original[j] = {w, s.basis.phi.col(j).dot(c_phi.col(j)), w * w};
  }
  try {
    s.adjusted = adjust_modes(s.original, adjustment);
    if (!s.adjusted.uniform)
      throw std::invalid_argument("its policy changes every mode on its own; a joined structure takes a cap");
    s.slack_stiffness_ratio = slack_stiffness_ratio(model, s, meshes, offsets, M, K, true);
    if (!(s.slack_stiffness_ratio < 1.0)) {
      std::ostringstream os;
      os << "with its slack links slack, the adjusted structure would have no stiffness left where they act: ";
      if (std::isfinite(s.slack_stiffness_ratio)) {
        os << "the largest eigenvalue of [sqrt(k_a k_b) g_a^T K_adj^-1 g_b] over them is " << s.slack_stiffness_ratio
           << " (it must be below 1; the original structure's is "
           << slack_stiffness_ratio(model, s, meshes, offsets, M, K, false)
           << "). The cap softens the modes that carry the links' own stiffness, and a slack link takes all of it "
              "away";
      } else {
        os << "the structure has a mode of zero frequency";
      }
      os << " (docs/catenary.md, \"The joined structure\"). Give the beams scope 'beam' (the links then act as "
            "exact forces), or raise omega_limit";
      throw std::invalid_argument(os.str());
    }
    std::vector<LowRankStructure::Range> ranges;
    for (int b : s.beams) ranges.push_back({beams.beams[b].offset, static_cast<int>(beams.beams[b].system.M.rows())});
    Eigen::VectorXd P(s.dof);
    for (int b : s.beams) P.segment(offsets[b], beams.beams[b].system.M.rows()) = beams.beams[b].system.P;
    s.structure =
        std::make_shared<const LowRankStructure>(adjusted_parts(name, std::move(ranges), M, K, P, s.basis, s.adjusted));
    s.k_star = s.structure->stiffness().mu;
    s.c_star = s.structure->damping().mu;
  } catch (const std::invalid_argument& e) {
    throw JoinedStructureError(s.beams.front(), "the joined structure " + name + ": " + e.what());
  }
  return s;
}

}  // namespace

std::vector<JoinedStructure> joined_structures(const ir::Model& model, const BeamModel& beams, int dense_limit) {
  const int nbeams = static_cast<int>(model.beams.size());
  std::vector<int> parent(nbeams);
  std::iota(parent.begin(), parent.end(), 0);
  for (const ir::Link& link : model.links) {
    if (joined_scope(model.beams[link.a.beam]) && joined_scope(model.beams[link.b.beam]))
      parent[root(parent, link.b.beam)] = root(parent, link.a.beam);
  }
  std::vector<JoinedStructure> out;
  std::vector<bool> done(nbeams, false);
  for (int b = 0; b < nbeams; ++b) {
    if (done[b] || !joined_scope(model.beams[b])) continue;
    std::vector<int> members;
    for (int c = b; c < nbeams; ++c)
      if (joined_scope(model.beams[c]) && root(parent, c) == root(parent, b)) {
        members.push_back(c);
        done[c] = true;
      }
    out.push_back(analyse(model, beams, std::move(members), dense_limit));
  }
  return out;
}

std::string joined_name(const ir::Model& model, const std::vector<int>& beams) {
  std::string name;
  for (int b : beams) name += (name.empty() ? "" : "+") + model.beams[b].name;
  return "'" + name + "'";
}

}  // namespace mbfe::runtime
