// Modal adjustment of damping (Section 6 of the paper, eqs (24)-(27);
// docs/damping-adjustment.md says why a cap, and why mass is the default).
//
// Per mass-normalised mode j (K Phi = M Phi Omega^2) the model obeys
// q'' + c_j q' + k_j q = p_j, with k_j = omega_j^2 and Rayleigh c_j = alpha +
// beta omega_j^2. Its roots r1 r2 = k_j, r1 + r2 = -c_j. A policy rewrites
// (k_j, c_j) of the modes whose fastest root |r_fast| exceeds omega_limit:
//
//   cap        k_j = omega_l^2, c_j = (2 + margin) omega_l: a mode at omega_l
//              with damping ratio 1 + margin/2; fastest root
//              r_cap = (zeta + sqrt(zeta^2 - 1)) omega_l (1.370156e5 for
//              omega_l = 1e5, margin 0.1). Reproduces Table 1 (right half).
//   mass       the modes cap changes keep k_j = omega_j^2 and get a modal
//              mass m_j = k_j / omega_l^2 and damping c_j = m_j (2 + margin)
//              omega_l: m_j r^2 + c_j r + k_j has the cap's roots, and the
//              static compliance 1 / k_j is the original one.
//   paper_eq25 eq (25) literally: modes with omega_j > omega_l get
//              c_j = (2 + margin) omega_j, k_j kept (selection by omega_j, as
//              the paper writes it).
//   keep_slow  keep the mode's slow real root r_s, move the fast one to r_cap:
//              k_j = |r_s| r_cap, c_j = |r_s| + r_cap (falls back to cap when
//              the mode is oscillatory or |r_s| >= r_cap).
//   none       nothing.
// and, for every policy but none, raises oscillatory modes (damping ratio
// c / (2 sqrt k) < 1) below zeta_min to zeta_min (c_j = 2 zeta_min omega_j).
//
// |r_fast| grows with omega_j for Rayleigh damping, so the adjusted modes of
// `cap` (and `mass`) are a tail of the ascending spectrum: the low-rank form
// (docs/damping-adjustment.md, "Back to nodal coordinates";
// runtime/structure/low_rank_structure.h) needs only the modes below it.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "runtime/modal/modal_basis.h"
#include "runtime/modal/state_spectrum.h"
#include "ir/model.h"

namespace mbfe::runtime {

enum class ModeChange : unsigned char { kKept, kFloored, kAdjusted };

struct AdjustedModes {
  ir::AdjustmentPolicy policy = ir::AdjustmentPolicy::kNone;  // the policy applied
  std::vector<ModalDynamics> modes;  // one per input mode, same order
  std::vector<ModeChange> change;    // what happened to each
  int adjusted = 0;                  // modes with ModeChange::kAdjusted
  int floored = 0;                   // modes raised to zeta_min
  /// Every adjusted mode got the same (k_star, c_star) with a unit modal mass
  /// (policy cap): the cap's low-rank form (runtime/structure/adjusted_parts.h) applies. False
  /// for policy mass as soon as it changes a mode: its adjusted modes share
  /// (k_star, c_star) per unit of their modal mass, k_j = k_star m_j and
  /// c_j = c_star m_j, a low-rank update of M rather than of K and C
  /// (docs/damping-adjustment.md, "Policy mass").
  bool uniform = true;
  double k_star = 0.0;  // 1/s^2, omega_l^2 (cap and mass; 0 for none)
  double c_star = 0.0;  // 1/s, (2 + margin) omega_l (cap and mass; 0 for none)
  double r_cap = 0.0;   // 1/s, modulus of the capped fast root (0 for none/paper_eq25)
};

/// Modulus of the fastest root of r^2 + c r + k = 0 (sqrt(k) for a complex pair).
double fastest_root(double c, double k);

/// The same for m r^2 + c r + k = 0 (the mode's own modal mass).
double fastest_root(const ModalDynamics& mode);

/// Applies `adjustment` (policy, omega_limit rad/s, margin, zeta_min) to the
/// modes. @throws std::invalid_argument if omega_limit <= 0 (any policy but
/// none), margin < 0 or zeta_min outside [0, 1).
AdjustedModes adjust_modes(const std::vector<ModalDynamics>& modes, const ir::Adjustment& adjustment);

}  // namespace mbfe::runtime
