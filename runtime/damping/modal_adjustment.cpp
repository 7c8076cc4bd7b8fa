#include "runtime/damping/modal_adjustment.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mbfe::runtime {

double fastest_root(double c, double k) {
  const auto roots = modal_roots(c, k);
  return std::max(std::abs(roots.first), std::abs(roots.second));
}

double fastest_root(const ModalDynamics& mode) {
  const auto roots = modal_roots(mode);
  return std::max(std::abs(roots.first), std::abs(roots.second));
}

AdjustedModes adjust_modes(const std::vector<ModalDynamics>& modes, const ir::Adjustment& a) {
  AdjustedModes out;
  out.policy = a.policy;
  out.modes = modes;
  out.change.assign(modes.size(), ModeChange::kKept);
  if (a.policy == ir::AdjustmentPolicy::kNone) return out;
  if (!(a.omega_limit > 0.0))
    throw std::invalid_argument("adjustment: omega_limit must be > 0 rad/s (got " + std::to_string(a.omega_limit) +
                                ")");
  if (!(a.margin >= 0.0))
    throw std::invalid_argument("adjustment: margin must be >= 0 (got " + std::to_string(a.margin) + ")");
  if (!(a.zeta_min >= 0.0 && a.zeta_min < 1.0))
    throw std::invalid_argument("adjustment: zeta_min must be in [0, 1) (got " + std::to_string(a.zeta_min) + ")");

  const double wl = a.omega_limit;
  const double zeta_cap = 1.0 + 0.5 * a.margin;
  const double r_cap = (zeta_cap + std::sqrt(zeta_cap * zeta_cap - 1.0)) * wl;
  out.k_star = wl * wl;
  out.c_star = (2.0 + a.margin) * wl;
  out.r_cap = a.policy == ir::AdjustmentPolicy::kPaperEq25 ? 0.0 : r_cap;
  // Truncation removes its modes; they are given the cap's values only so
  // that the low-rank parts (adjusted_parts) have a uniform tail to build.
  const bool truncate = a.policy == ir::AdjustmentPolicy::kTruncate;
  out.uniform = a.policy == ir::AdjustmentPolicy::kCap || truncate;

  for (std::size_t j = 0; j < modes.size(); ++j) {
    ModalDynamics& m = out.modes[j];
    bool adjust = false;
    if (a.policy == ir::AdjustmentPolicy::kPaperEq25) {
      adjust = m.omega > wl;
      if (adjust) m.c = (2.0 + a.margin) * m.omega;
    } else if (truncate) {
      // Selected by omega_j, the frequency a truncation is stated in.
      adjust = m.omega > wl;
      if (adjust) {
        m.k = out.k_star;
        m.c = out.c_star;
      }
    } else {
      adjust = fastest_root(m) > wl;
      if (adjust) {
        const auto roots = modal_roots(m);
        const bool real_roots = roots.first.imag() == 0.0;
        const double slow = std::abs(roots.first);
        if (a.policy == ir::AdjustmentPolicy::kMass) {
          // Stiffness kept: m r^2 + c r + k = m (r^2 + c_star r + k_star).
          m.m = m.k / out.k_star;
          m.c = m.m * out.c_star;
          out.uniform = false;
        } else if (a.policy == ir::AdjustmentPolicy::kKeepSlow && real_roots && slow < r_cap) {
          m.k = slow * r_cap;
          m.c = slow + r_cap;
          out.uniform = false;
        } else {
          m.k = out.k_star;
          m.c = out.c_star;
        }
      }
    }
    if (adjust) {
      out.change[j] = ModeChange::kAdjusted;
      ++out.adjusted;
      continue;
    }
    // The floor on c / (2 sqrt(k m)); m is 1 unless the input modes carry
    // their own modal masses.
    const double w = std::sqrt(m.k * m.m);
    if (w > 0.0 && m.c < 2.0 * w && m.c < 2.0 * a.zeta_min * w) {
      m.c = 2.0 * a.zeta_min * w;
      out.change[j] = ModeChange::kFloored;
      ++out.floored;
    }
  }
  if (out.adjusted == 0) out.uniform = true;
  return out;
}

}  // namespace mbfe::runtime
