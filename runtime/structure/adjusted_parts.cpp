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
  // The kept modes: the leading ones the policy does not change (a partial
  // basis must end with a changed one: every mode beyond it is changed too).
  const auto leading_kept = [&]() {
    int kept = 0;
    while (kept < count && adjusted.change[kept] != ModeChange::kAdjusted) ++kept;
    for (int j = kept; j < count; ++j)
      if (adjusted.change[j] != ModeChange::kAdjusted)
        throw std::invalid_argument("'" + name + "': the low-rank form needs the adjusted modes to be the highest "
                                    "ones; mode " + std::to_string(j + 1) + " is kept above an adjusted one");
    if (!basis.complete && kept == count)
      throw std::invalid_argument("'" + name + "': the partial modal basis (" + std::to_string(count) +
                                  " modes) ends below the adjustment threshold; compute more modes");
    return kept;
  };
  if (adjusted.policy == ir::AdjustmentPolicy::kMass && adjusted.adjusted > 0) {
    // Policy mass: capped modes keep k_j and get modal mass k_j / k* and
    // damping c* k_j / k* (docs/damping-adjustment.md, "Policy mass"), so
    //   M_adj = K / k* + U diag(1 - k_L / k*) U^T,
    //   C_adj = (c* / k*) K + U diag(c_L - c* k_L / k*) U^T,   K_adj = K.
    const int kept = leading_kept();
    const double k_star = adjusted.k_star, c_star = adjusted.c_star;
    parts.base = LowRankStructure::Base::kStiffness;
    parts.phi = basis.phi.leftCols(kept);
    parts.k = basis.omega.head(kept).array().square().matrix();
    parts.mass = {1.0 / k_star, Eigen::VectorXd(kept)};
    parts.damping = {c_star / k_star, Eigen::VectorXd(kept)};
    parts.stiffness = {1.0, Eigen::VectorXd::Zero(kept)};
    for (int j = 0; j < kept; ++j) {
      parts.mass.d[j] = 1.0 - adjusted.modes[j].k / k_star;
      parts.damping.d[j] = adjusted.modes[j].c - c_star * adjusted.modes[j].k / k_star;
    }
    return parts;
  }
  int kept = count;
  double k_star = 0.0, c_star = 0.0;
  if (adjusted.uniform) {
    kept = leading_kept();
    if (adjusted.adjusted > 0 || !basis.complete) {
      k_star = adjusted.k_star;
      c_star = adjusted.c_star;
    }
  } else if (!basis.complete) {
    throw std::invalid_argument("'" + name + "': eq (27) needs every mode (a complete modal basis)");
  } else {
    parts.every_mode = true;
  }
  parts.truncated = adjusted.policy == ir::AdjustmentPolicy::kTruncate;
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
