// The SciPy golden values of the low-pass filter
// (tests/runtime/signal/filter_golden.csv, made by
// tests/runtime/signal/make_filter_golden.py, the command in its header):
// the filter's coefficients and a signal t, x with its zero-phase filtered y.
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

}  // namespace mbfe::test
