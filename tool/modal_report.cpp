#include "tool/modal_report.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <ostream>


namespace mbfe::tool {

namespace {

constexpr const char* kHeaderFormat = "%6s  %14s  %16s  %14s  %9s  %16s";
constexpr const char* kPairFormat = "%6d  %14.6e  %16s  %14.4f  %9.3f  %16.4f";
constexpr const char* kRealFormat = "%6d  %14.6e  %16s  %14s  %9s  %16s";

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char buf[256];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  return buf;
}

std::string row_line(const runtime::SpectrumRow& r) {
  if (r.pair) {
    return format(kPairFormat, r.index, r.real, format("+-%.6e", r.imag).c_str(), r.f_damped_hz,
                  100.0 * r.zeta,
                  r.f_undamped_hz);
  }
  return format(kRealFormat, r.index, r.real, "0", "-", "-", "-");
}

}  // namespace

nlohmann::json spectrum_json(const runtime::StateSpectrum& spectrum) {
  nlohmann::json ev = nlohmann::json::array();
  for (const auto& l : spectrum.eigenvalues) ev.push_back({l.real(), l.imag()});
  const double h = spectrum.h_max_forward_euler;
  nlohmann::json block;
  block["eigenvalues"] = std::move(ev);
  block["oscillatory_pairs"] = spectrum.oscillatory_pairs;
  block["h_max"] = {{"forward_euler",
                     spectrum.complete && std::isfinite(h) ? nlohmann::json(h) : nlohmann::json()}};
  block["complete"] = spectrum.complete;
  return block;
}

int spectrum_table_width() {
  return static_cast<int>(format(kHeaderFormat, "#", "real", "imaginary", "f damped [Hz]",
                                 "zeta [%]", "f undamped [Hz]")
                              .size());
}

std::vector<std::string> spectrum_table_lines(const runtime::StateSpectrum& spectrum, bool all,
                                              int edge_rows) {
  const int width = spectrum_table_width();
  const auto pad = [width](std::string s) {
    s.resize(std::max<size_t>(s.size(), width), ' ');
    return s;
  };
  std::vector<std::string> lines;
  lines.push_back(pad(format(kHeaderFormat, "#", "real", "imaginary", "f damped [Hz]", "zeta [%]",
                             "f undamped [Hz]")));
  const std::vector<runtime::SpectrumRow> rows = runtime::spectrum_rows(spectrum);
  const size_t n = rows.size();
  const size_t edge = static_cast<size_t>(std::max(edge_rows, 1));
  for (size_t i = 0; i < n; ++i) {
    if (!all && n > 2 * edge + 1 && i == edge) {
      lines.push_back(pad(format(kHeaderFormat, "...", "...", "...", "...", "...", "...")));
      i = n - edge - 1;
      continue;
    }
    lines.push_back(pad(row_line(rows[i])));
  }
  return lines;
}

std::string spectrum_summary(const runtime::StateSpectrum& spectrum, int dof, const std::string& partial) {
  std::string s = std::to_string(dof) + " DOF, " + std::to_string(spectrum.oscillatory_pairs) +
                  " oscillatory pairs";
  if (!spectrum.eigenvalues.empty()) {
    const auto& fastest = spectrum.eigenvalues.back();
    s += format(", fastest eigenvalue %.6e", fastest.real());
    if (fastest.imag() != 0.0) s += format(" +- %.6ei", std::abs(fastest.imag()));
    s += " 1/s";
  }
  const double h = spectrum.h_max_forward_euler;
  if (!spectrum.complete) {
    s += ", forward-Euler h_max unknown (partial spectrum: " + partial + ")";
  } else if (std::isinf(h)) {
    s += ", forward-Euler h_max unlimited (no nonzero eigenvalue)";
  } else if (h == 0.0) {
    s += ", forward-Euler h_max = 0 (an undamped or unstable mode: no stable step)";
  } else {
    s += format(", forward-Euler h_max = %.6g s", h);
  }
  return s;
}

namespace {

void print_adjusted_text(std::ostream& out, const ir::Beam& b, const runtime::BeamPart& r, bool all) {
  if (!r.has_adjustment) return;
  const int dof = static_cast<int>(r.system.M.rows());
  out << "adjusted (policy " << policy_name(b.adjustment.policy) << ", omega_limit " << b.adjustment.omega_limit
      << " rad/s, margin " << b.adjustment.margin << ", zeta_min " << b.adjustment.zeta_min << "): "
      << r.adjusted.adjusted
      << (b.adjustment.policy == ir::AdjustmentPolicy::kTruncate ? " modes removed (the right half lists the kept ones), "
                                                                 : " modes adjusted, ")
      << r.adjusted.floored << " raised to zeta_min\n";
  if (b.adjustment.policy == ir::AdjustmentPolicy::kMass && r.adjusted.adjusted > 0) {
    double largest = 1.0;
    for (const runtime::ModalDynamics& m : r.adjusted.modes) largest = std::max(largest, m.m);
    out << "(policy mass: the adjusted modes keep their stiffness, so the static deflection is the original "
           "one; their modal masses rise to omega_j^2 / omega_limit^2, up to "
        << largest << ")\n";
  }
  const auto left = spectrum_table_lines(r.original_spectrum, all);
  const auto right = spectrum_table_lines(r.adjusted_spectrum, all);
  const std::string blank(spectrum_table_width(), ' ');
  const std::string gap = "  |";
  std::string title_left = "original (Table 1, left half)";
  title_left.resize(spectrum_table_width(), ' ');
  out << title_left << gap << "adjusted (Table 1, right half)\n";
  for (std::size_t i = 0; i < std::max(left.size(), right.size()); ++i)
    out << (i < left.size() ? left[i] : blank) << gap << (i < right.size() ? right[i] : "") << "\n";
  out << "summary (adjusted): " << spectrum_summary(r.adjusted_spectrum, dof) << "\n";
  if (r.adjusted_spectrum.complete && r.original_spectrum.h_max_forward_euler > 0.0) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "forward-Euler h_max gain: %.0fx\n",
                  r.adjusted_spectrum.h_max_forward_euler / r.original_spectrum.h_max_forward_euler);
    out << buf;
  }
}

}  // namespace

const char* policy_name(ir::AdjustmentPolicy p) {
  switch (p) {
    case ir::AdjustmentPolicy::kNone:
      return "none";
    case ir::AdjustmentPolicy::kCap:
      return "cap";
    case ir::AdjustmentPolicy::kPaperEq25:
      return "paper_eq25";
    case ir::AdjustmentPolicy::kKeepSlow:
      return "keep_slow";
    case ir::AdjustmentPolicy::kMass:
      return "mass";
    case ir::AdjustmentPolicy::kTruncate:
      return "truncate";
  }
  return "?";
}

/// The JSON of one beam; an "adjusted" block goes next to "original".
nlohmann::json beam_json(const runtime::BeamPart& r) {
  nlohmann::json omega = nlohmann::json::array();
  for (Eigen::Index j = 0; j < r.basis.omega.size(); ++j) omega.push_back(r.basis.omega[j]);
  nlohmann::json beam;
  beam["name"] = r.system.name;
  beam["dof"] = r.system.M.rows();
  beam["modal_path"] = r.dense ? "dense" : "sparse";
  beam["natural_frequencies_rad_s"] = std::move(omega);
  beam["original"] = spectrum_json(r.original_spectrum);
  return beam;
}

void add_adjusted_json(nlohmann::json& beam, const ir::Beam& b, const runtime::BeamPart& a) {
  if (!a.has_adjustment) return;
  if (b.adjustment.scope == ir::AdjustmentScope::kJoined) {
    beam["adjusted"] = {{"scope", "joined"}};  // the structure's modes are capped, not the beam's own
    return;
  }
  nlohmann::json block = spectrum_json(a.adjusted_spectrum);
  block["policy"] = policy_name(b.adjustment.policy);
  block["omega_limit"] = b.adjustment.omega_limit;
  block["margin"] = b.adjustment.margin;
  block["zeta_min"] = b.adjustment.zeta_min;
  block["adjusted_modes"] = a.adjusted.adjusted;
  block["floored_modes"] = a.adjusted.floored;
  if (b.adjustment.policy == ir::AdjustmentPolicy::kMass) {
    nlohmann::json masses = nlohmann::json::array();
    for (const runtime::ModalDynamics& m : a.adjusted.modes) masses.push_back(m.m);
    block["modal_masses"] = std::move(masses);
  }
  beam["adjusted"] = std::move(block);
}

void print_beam_text(std::ostream& out, const ir::Beam& b, const runtime::BeamPart& r, bool all) {
  const int dof = static_cast<int>(r.system.M.rows());
  out << "beam '" << r.system.name << "': " << dof << " DOF, Rayleigh alpha = " << r.system.rayleigh_alpha
      << " 1/s, beta = " << r.system.rayleigh_beta << " s ("
      << (r.dense ? "dense modal analysis, every mode"
                  : "sparse Lanczos, lowest " + std::to_string(r.basis.omega.size()) + " modes")
      << ")\n";
  out << "state-space eigenvalues of eq (28), sorted by modulus (the paper's Table 1):\n";
  // A joined beam's own modes are not the ones capped: its structure's are,
  // which the coupled spectrum shows.
  const bool joined = r.has_adjustment && b.adjustment.scope == ir::AdjustmentScope::kJoined;
  if (joined)
    out << "(adjusted with the beams linked to it, as one structure (scope 'joined'): its own adjusted "
           "spectrum, not the one capped, is not shown; the coupled spectrum includes the structure's)\n";
  if (r.has_adjustment && !joined) {
    out << "summary (original): " << spectrum_summary(r.original_spectrum, dof) << "\n";
    print_adjusted_text(out, b, r, all);
    return;
  }
  for (const std::string& line : spectrum_table_lines(r.original_spectrum, all)) out << line << "\n";
  out << "summary: " << spectrum_summary(r.original_spectrum, dof) << "\n";
}

}  // namespace mbfe::tool
