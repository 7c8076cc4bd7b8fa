#include "runtime/structure/adjusted_parts.h"

#include <stdexcept>

namespace mbfe::runtime {

LowRankStructure::Parts adjusted_parts(const std::string& name, std::vector<LowRankStructure::Range> ranges,
                                       const Eigen::SparseMatrix<double>& M, const Eigen::SparseMatrix<double>& K,
                                       const Eigen::VectorXd& P, const ModalBasis& basis,
                                       const AdjustedModes& adjusted) {
  const int count = static_cast<int>(basis.omega.size());
  if (static_cast<int>(adjusted.modes.size()) != count)
    throw std::invalid_argument("'" + name + "': " + std::to_string(adjusted.modes.size()) +
                                " adjusted modes, expected " + std::to_string(count) + " (one per basis mode)");
  LowRankStructure::Parts parts;
  parts.name = name;
  parts.ranges = std::move(ranges);
  parts.M = M;
  parts.K = K;
  parts.P = P;
  parts.base = LowRankStructure::Base::kMass;
  int kept = count;
  double k_star = 0.0, c_star = 0.0;
  if (adjusted.uniform) {
    kept = 0;
    while (kept < count && adjusted.change[kept] != ModeChange::kAdjusted) ++kept;
    for (int j = kept; j < count; ++j)
      if (adjusted.change[j] != ModeChange::kAdjusted)
        throw std::invalid_argument("'" + name + "': the low-rank form needs the adjusted modes to be the highest "
                                    "ones; mode " + std::to_string(j + 1) + " is kept above an adjusted one");
    if (!basis.complete && kept == count)
      throw std::invalid_argument("'" + name + "': the partial modal basis (" + std::to_string(count) +
                                  " modes) ends below the adjustment threshold; compute more modes");
    if (adjusted.adjusted > 0 || !basis.complete) {
      k_star = adjusted.k_star;
      c_star = adjusted.c_star;
    }
  } else if (!basis.complete) {
    throw std::invalid_argument("'" + name + "': eq (27) needs every mode (a complete modal basis)");
  } else {
    parts.every_mode = true;
  }
  parts.phi = basis.phi.leftCols(kept);
  parts.k = basis.omega.head(kept).array().square().matrix();
  parts.mass = {1.0, Eigen::VectorXd::Zero(kept)};
  parts.damping = {c_star, Eigen::VectorXd(kept)};
  parts.stiffness = {k_star, Eigen::VectorXd(kept)};
  for (int j = 0; j < kept; ++j) {
    parts.damping.d[j] = adjusted.modes[j].c - c_star;
    parts.stiffness.d[j] = adjusted.modes[j].k - k_star;
  }
  return parts;
}

}  // namespace mbfe::runtime
