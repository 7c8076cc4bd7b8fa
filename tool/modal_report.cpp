#include "tool/modal_report.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>


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

std::string spectrum_summary(const runtime::StateSpectrum& spectrum, int dof) {
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
    s += ", forward-Euler h_max unknown (partial spectrum: lowest modes only)";
  } else if (std::isinf(h)) {
    s += ", forward-Euler h_max unlimited (no nonzero eigenvalue)";
  } else if (h == 0.0) {
    s += ", forward-Euler h_max = 0 (an undamped or unstable mode: no stable step)";
  } else {
    s += format(", forward-Euler h_max = %.6g s", h);
  }
  return s;
}

}  // namespace mbfe::tool
