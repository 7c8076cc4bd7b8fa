#include "runtime/coupled/coupled_tangents.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "runtime/multibody/rigid_tangents.h"

namespace mbfe::runtime {

namespace {

// Central-difference step of the force elements' Jacobians, relative to the
// coordinate's size: the cube root of machine epsilon balances truncation
// (h^2) against round-off (eps / h).
constexpr double kDifferenceStep = 6e-6;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace

CoupledTangents::CoupledTangents(CoupledDynamics& dynamics, double t, const Eigen::VectorXd& q,
                                 const Eigen::VectorXd& qd)
    : model_(dynamics.model()) {
  const int n = model_.n();
  nb_ = model_.nb();
  if (model_.m() > 0)
    throw std::invalid_argument("the tangents of a coupled model with constraint contacts (" +
                                std::to_string(model_.m()) +
                                " rows) are not its Jacobian on the constraint manifold");
  if (q.size() != n || qd.size() != n) {
    std::ostringstream os;
    os << "coupled state has " << q.size() << " / " << qd.size() << " entries, expected " << n << " ([q_b; q_c])";
    throw std::invalid_argument(os.str());
  }
  const DrivenCoordinates& driven = model_.driven();
  free_of_.assign(n, -1);
  for (int j = 0; j < n; ++j) {
    if (j < nb_ && driven.is_driven(j)) {
      ++num_driven_;
      continue;
    }
    free_of_[j] = static_cast<int>(free_.size());
    free_.push_back(j);
  }
  nf_ = static_cast<int>(free_.size());
  nfb_ = nb_ - num_driven_;

  // The state with the motion imposed, and its accelerations.
  Eigen::VectorXd qm = q, vm = qd, a, lambda;
  dynamics.impose_motion(t, qm, vm);
  dynamics.evaluate(t, qm, vm);
  dynamics.solve_augmented(t, a, lambda);
  const RowMajor mb = dynamics.data().mb_row;

  std::vector<Eigen::Triplet<double>> tm, tc, tk;
  Eigen::MatrixXd K_b, C_b;
  rigid_dynamics_tangents(model_.kernels(), t, qm.data(), vm.data(), a.data(), K_b, C_b);
  Eigen::MatrixXd mb_free(nfb_, nfb_);
  for (int i = 0; i < nfb_; ++i) {
    for (int j = 0; j < nfb_; ++j) {
      const int fi = free_[i], fj = free_[j];
      mb_free(i, j) = mb(fi, fj);
      tm.emplace_back(i, j, mb(fi, fj));
      if (C_b(fi, fj) != 0.0) tc.emplace_back(i, j, C_b(fi, fj));
      if (K_b(fi, fj) != 0.0) tk.emplace_back(i, j, K_b(fi, fj));
    }
  }
  rigid_mass_lu_.compute(mb_free);
  for (const CoupledBeam& b : model_.beams()) {
    if (b.structure >= 0) continue;
    const int off = nfb_ + b.offset;
    for (auto [mat, out] : {std::pair{&b.M, &tm}, std::pair{&b.C, &tc}, std::pair{&b.K, &tk}}) {
      for (int col = 0; col < mat->outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(*mat, col); it; ++it)
          out->emplace_back(off + static_cast<int>(it.row()), off + static_cast<int>(it.col()), it.value());
    }
  }
  element_tangents(t, qm, vm, tk, tc);
  for (auto [mat, entries] : {std::pair{&mass_, &tm}, std::pair{&damping_, &tc}, std::pair{&stiffness_, &tk}}) {
    mat->resize(nf_, nf_);
    mat->setFromTriplets(entries->begin(), entries->end());
  }
  for (const auto& s : model_.structures()) ws_.push_back(s->make_workspace());
}

void CoupledTangents::element_tangents(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                       std::vector<Eigen::Triplet<double>>& k,
                                       std::vector<Eigen::Triplet<double>>& c) const {
  const int nc = model_.nc();
  Eigen::VectorXd x = q, xd = v, fb_plus(nb_), fb_minus(nb_), fc_plus(nc), fc_minus(nc);
  std::vector<int> read;
  for (const auto& element : model_.forces()) {
    std::unique_ptr<ForceState> state = element->make_state();
    // The coordinates it reads (and loads): the free rigid ones and its beam DOFs.
    read.clear();
    element->beam_dofs_read(x.data(), read);
    std::vector<int> coords;
    for (int j = 0; j < nb_; ++j)
      if (free_of_[j] >= 0) coords.push_back(j);
    for (int dof : read) coords.push_back(nb_ + dof);
    auto force = [&](Eigen::VectorXd& fb, Eigen::VectorXd& fc) {
      fb.setZero();
      fc.setZero();
      const ForceArgs args{t, x.data(), xd.data(), x.data() + nb_, xd.data() + nb_};
      ForceSink sink{fb.data(), fc.data()};
      element->add_force(args, *state, sink);
    };
    for (int j : coords) {
      for (Eigen::VectorXd* y : {&x, &xd}) {
        const double y0 = (*y)[j];
        const double h = kDifferenceStep * (1.0 + std::abs(y0));
        (*y)[j] = y0 + h;
        force(fb_plus, fc_plus);
        (*y)[j] = y0 - h;
        force(fb_minus, fc_minus);
        (*y)[j] = y0;
        std::vector<Eigen::Triplet<double>>& out = y == &x ? k : c;
        // -df/dq: the element's force is on the right-hand side.
        for (int i : coords) {
          const double d = i < nb_ ? fb_plus[i] - fb_minus[i] : fc_plus[i - nb_] - fc_minus[i - nb_];
          if (d != 0.0) out.emplace_back(free_of_[i], free_of_[j], -d / (2.0 * h));
        }
      }
    }
  }
}

void CoupledTangents::apply(Part part, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd& y) const {
  const Eigen::SparseMatrix<double>& sparse =
      part == Part::kMass ? mass_ : (part == Part::kDamping ? damping_ : stiffness_);
  y.noalias() = sparse * x;
  const auto& structures = model_.structures();
  for (std::size_t s = 0; s < structures.size(); ++s) {
    const LowRankStructure& st = *structures[s];
    const LowRankStructure::Term& term =
        part == Part::kMass ? st.mass() : (part == Part::kDamping ? st.damping() : st.stiffness());
    st.gather(x.data() + nfb_, gx_);
    st.apply(term, gx_, gy_, ws_[s]);
    st.scatter_add(gy_, y.data() + nfb_);
  }
}

void CoupledTangents::apply_sum(Part p1, const Eigen::Ref<const Eigen::VectorXd>& x1, Part p2,
                                const Eigen::Ref<const Eigen::VectorXd>& x2, Eigen::VectorXd& y) const {
  auto sparse = [&](Part part) -> const Eigen::SparseMatrix<double>& {
    return part == Part::kMass ? mass_ : (part == Part::kDamping ? damping_ : stiffness_);
  };
  y.noalias() = sparse(p1) * x1;
  y.noalias() += sparse(p2) * x2;
  const auto& structures = model_.structures();
  for (std::size_t s = 0; s < structures.size(); ++s) {
    const LowRankStructure& st = *structures[s];
    auto term = [&](Part part) -> const LowRankStructure::Term& {
      return part == Part::kMass ? st.mass() : (part == Part::kDamping ? st.damping() : st.stiffness());
    };
    const LowRankStructure::Term &t1 = term(p1), &t2 = term(p2);
    // mu1 B x1 + mu2 B x2 + M Phi_L (d1 .* Phi_L^T M x1 + d2 .* Phi_L^T M x2).
    const int ns = st.size();
    pair_.resize(ns, 2);
    st.gather(x1.data() + nfb_, gx_);
    pair_.col(0) = gx_;
    st.gather(x2.data() + nfb_, gx_);
    pair_.col(1) = gx_;
    gy_.noalias() = t1.mu * (st.B() * pair_.col(0));
    gy_.noalias() += t2.mu * (st.B() * pair_.col(1));
    if (st.rank() > 0 && ((t1.d.array() != 0.0).any() || (t2.d.array() != 0.0).any())) {
      // Phi_L^T [M x1, M x2] row by row: Phi_L (n_s x m, row-major, often
      // hundreds of megabytes) is read once; a matrix product would copy it
      // into packed panels first, and two matrix-vector products read it twice.
      const Eigen::MatrixXd mx = st.M() * pair_;
      const LowRankStructure::RowMajorMatrix& phi = st.phi();
      modal_pair_.setZero(phi.cols(), 2);
      for (Eigen::Index i = 0; i < phi.rows(); ++i) {
        modal_pair_.col(0).noalias() += mx(i, 0) * phi.row(i).transpose();
        modal_pair_.col(1).noalias() += mx(i, 1) * phi.row(i).transpose();
      }
      const Eigen::VectorXd w = t1.d.cwiseProduct(modal_pair_.col(0)) + t2.d.cwiseProduct(modal_pair_.col(1));
      gx_.noalias() = st.phi() * w;
      gy_.noalias() += st.M() * gx_;
    }
    st.scatter_add(gy_, y.data() + nfb_);
  }
}

void CoupledTangents::apply_mass(const Eigen::VectorXd& x, Eigen::VectorXd& y) const { apply(Part::kMass, x, y); }
void CoupledTangents::apply_damping(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  apply(Part::kDamping, x, y);
}
void CoupledTangents::apply_stiffness(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  apply(Part::kStiffness, x, y);
}

void CoupledTangents::solve_mass(const Eigen::VectorXd& r, Eigen::VectorXd& x) const {
  x.resize(nf_);
  if (nfb_ > 0) x.head(nfb_) = rigid_mass_lu_.solve(r.head(nfb_));
  const auto& beams = model_.beams();
  for (std::size_t k = 0; k < beams.size(); ++k) {
    const CoupledBeam& b = beams[k];
    if (b.structure >= 0) continue;
    const int off = nfb_ + b.offset, nk = b.mesh.num_free;
    x.segment(off, nk) = model_.mass_factor(static_cast<int>(k)).solve(r.segment(off, nk));
  }
  const auto& structures = model_.structures();
  for (std::size_t s = 0; s < structures.size(); ++s) {
    const LowRankStructure& st = *structures[s];
    st.gather(r.data() + nfb_, gx_);
    st.solve_mass(gx_, gy_, ws_[s]);
    st.scatter(gy_, x.data() + nfb_);
  }
}

void CoupledTangents::apply_state_matrix(const double* in, double* out) const {
  const Eigen::Map<const Eigen::VectorXd> z(in, nf_), zd(in + nf_, nf_);
  Eigen::Map<Eigen::VectorXd>(out, nf_) = zd;
  apply_sum(Part::kStiffness, z, Part::kDamping, zd, tmp_);
  solve_mass(tmp_, sol_);
  Eigen::Map<Eigen::VectorXd>(out + nf_, nf_) = -sol_;
}

void CoupledTangents::factorize_shifted(double sigma) {
  factored_ = false;
  sigma_ = sigma;
  const double c_a = sigma * sigma, c_v = sigma;
  std::vector<Eigen::Triplet<double>> entries;
  for (auto [mat, scale] : {std::pair{&mass_, c_a}, std::pair{&damping_, c_v}, std::pair{&stiffness_, 1.0}}) {
    if (scale == 0.0) continue;
    for (int col = 0; col < mat->outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(*mat, col); it; ++it)
        entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), scale * it.value());
  }
  const auto& structures = model_.structures();
  std::vector<LowRankStructure::Term> terms;
  bool blocks = true;
  for (const auto& s : structures) {
    terms.push_back(s->combination(c_a, c_v, 1.0));
    blocks = blocks && s->ranges().size() == 1 && !s->every_mode() && terms.back().mu > 0.0;
  }
  std::ostringstream what;
  what << "the coupled linearisation's sigma^2 M + sigma C + K at sigma = " << sigma << " 1/s";
  if (blocks) {
    // Blocks of known inverse, the couplings by Woodbury over the rows they touch.
    std::vector<ModalBlock> list;
    for (std::size_t k = 0; k < structures.size(); ++k) {
      const LowRankStructure& s = *structures[k];
      list.push_back(s.modal_block(nfb_ + s.ranges().front().offset, terms[k]));
    }
    try {
      block_solver_.factorize(nf_, entries, std::move(list));
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(what.str() + ": " + e.what());
    }
    blocks_ = true;
    factored_ = true;
    return;
  }
  // The structures' sparse part mu B joins the matrix, their low rank by Woodbury.
  int width = 0;
  for (std::size_t k = 0; k < structures.size(); ++k) {
    const LowRankStructure& s = *structures[k];
    std::vector<int> global;
    for (const LowRankStructure::Range& r : s.ranges())
      for (int i = 0; i < r.size; ++i) global.push_back(nfb_ + r.offset + i);
    const Eigen::SparseMatrix<double>& B = s.B();
    for (int col = 0; col < B.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(B, col); it; ++it)
        entries.emplace_back(global[it.row()], global[it.col()], terms[k].mu * it.value());
    width += s.rank();
  }
  Eigen::SparseMatrix<double> matrix(nf_, nf_);
  matrix.setFromTriplets(entries.begin(), entries.end());
  lu_.analyzePattern(matrix);
  lu_.factorize(matrix);
  if (lu_.info() != Eigen::Success) throw std::runtime_error(what.str() + " is singular (" + lu_.lastErrorMessage() + ")");
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(nf_, width);
  Eigen::VectorXd D(width);
  std::vector<WoodburyCorrection::Block> wblocks;
  int col = 0;
  for (std::size_t k = 0; k < structures.size(); ++k) {
    const LowRankStructure& s = *structures[k];
    const Eigen::MatrixXd u = s.mass_times_phi();
    Eigen::Index row = 0;
    for (const LowRankStructure::Range& r : s.ranges()) {
      W.block(nfb_ + r.offset, col, r.size, s.rank()) = u.middleRows(row, r.size);
      wblocks.push_back({nfb_ + r.offset, r.size, col, s.rank()});
      row += r.size;
    }
    D.segment(col, s.rank()) = terms[k].d;
    col += s.rank();
  }
  Eigen::MatrixXd Z = width > 0 ? Eigen::MatrixXd(lu_.solve(W)) : Eigen::MatrixXd(nf_, 0);
  woodbury_.factorize(std::move(W), std::move(D), std::move(Z), wblocks, what.str());
  blocks_ = false;
  factored_ = true;
}

void CoupledTangents::solve_shifted(const double* in, double* out) const {
  if (!factored_) throw std::logic_error("CoupledTangents::solve_shifted before factorize_shifted");
  // (A - sigma I) [x1; x2] = [b1; b2]:  x2 = b1 + sigma x1,
  // (sigma^2 M + sigma C + K) x1 = -(M (b2 + sigma b1) + C b1).
  const Eigen::Map<const Eigen::VectorXd> b1(in, nf_), b2(in + nf_, nf_);
  tmp2_ = b2 + sigma_ * b1;
  apply_sum(Part::kMass, tmp2_, Part::kDamping, b1, rhs_);
  rhs_ = -rhs_;
  if (blocks_) {
    block_solver_.solve(rhs_, sol_);
  } else {
    sol_ = lu_.solve(rhs_);
    woodbury_.correct(sol_);
  }
  Eigen::Map<Eigen::VectorXd>(out, nf_) = sol_;
  Eigen::Map<Eigen::VectorXd>(out + nf_, nf_) = b1 + sigma_ * sol_;
}

Eigen::MatrixXd CoupledTangents::dense_state_matrix() const {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * nf_, 2 * nf_);
  a.topRightCorner(nf_, nf_).setIdentity();
  Eigen::VectorXd e = Eigen::VectorXd::Zero(nf_), y, x;
  for (int j = 0; j < nf_; ++j) {
    e[j] = 1.0;
    apply(Part::kStiffness, e, y);
    solve_mass(y, x);
    a.col(j).tail(nf_) = -x;
    apply(Part::kDamping, e, y);
    solve_mass(y, x);
    a.col(nf_ + j).tail(nf_) = -x;
    e[j] = 0.0;
  }
  return a;
}

}  // namespace mbfe::runtime
