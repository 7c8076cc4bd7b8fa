// The SciPy golden values of the low-pass filter:
// - tests/runtime/signal/filter_golden.csv (made by
//   tests/runtime/signal/make_filter_golden.py, the command in its header):
//   the 4th-order filter's transfer function and a force-like signal t, x with
//   its zero-phase filtered y (scipy.signal.filtfilt);
// - tests/runtime/signal/sos_golden.csv (made by
//   tests/runtime/signal/make_sos_golden.py, the command in its header): for
//   orders 1..8 and cut-offs 0.4 to 1e-4 of the sample rate, the sections of
//   scipy.signal.butter(..., output='sos') and scipy.signal.sosfiltfilt of one
//   signal x.
#pragma once

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mbfe::test {

struct FilterGolden {
  std::vector<double> b, a;  // numerator and denominator of the filter
  std::vector<double> t, x, y;
};

inline FilterGolden read_filter_golden() {
  std::ifstream in(std::string(MBFE_SOURCE_DIR) + "/tests/runtime/signal/filter_golden.csv");
  FilterGolden g;
  std::string line;
  auto numbers = [](const std::string& text) {
    std::vector<double> out;
    std::istringstream ss(text);
    double v;
    while (ss >> v) out.push_back(v);
    return out;
  };
  while (std::getline(in, line)) {
    if (line.rfind("# b = ", 0) == 0) {
      g.b = numbers(line.substr(6));
    } else if (line.rfind("# a = ", 0) == 0) {
      g.a = numbers(line.substr(6));
    } else if (!line.empty() && line[0] != '#' && line[0] != 't') {
      std::replace(line.begin(), line.end(), ',', ' ');
      const std::vector<double> v = numbers(line);
      g.t.push_back(v.at(0));
      g.x.push_back(v.at(1));
      g.y.push_back(v.at(2));
    }
  }
  return g;
}

/// One filter of sos_golden.csv: its order, cut-off (fraction of the sample
/// rate), sections (6 numbers each, scipy's rows) and sosfiltfilt(x).
struct SosGoldenCase {
  int order = 0;
  double cutoff = 0.0;
  std::vector<double> sections;
  std::vector<double> y;
};

struct SosGolden {
  std::vector<double> x;
  std::vector<SosGoldenCase> cases;
};

inline SosGolden read_sos_golden() {
  std::ifstream in(std::string(MBFE_SOURCE_DIR) + "/tests/runtime/signal/sos_golden.csv");
  SosGolden g;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# sos ", 0) == 0) {
      std::istringstream ss(line.substr(6));
      SosGoldenCase c;
      ss >> c.order >> c.cutoff;
      double v;
      while (ss >> v) c.sections.push_back(v);
      g.cases.push_back(c);
    } else if (!line.empty() && line[0] != '#' && line[0] != 'x') {
      std::replace(line.begin(), line.end(), ',', ' ');
      std::istringstream ss(line);
      double v;
      ss >> v;
      g.x.push_back(v);
      for (SosGoldenCase& c : g.cases) {
        ss >> v;
        c.y.push_back(v);
      }
    }
  }
  return g;
}

}  // namespace mbfe::test
