// A simulation observer that keeps every row in memory, for tests that run
// the API and look at columns by name.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "runtime/simulation/simulate.h"

namespace mbfe::test {

class RecordedRows : public runtime::SimulationObserver {
 public:
  void begin(const runtime::OutputLayout& layout) override {
    columns = layout.columns;
    units = layout.units;
  }
  void row(const runtime::OutputRow& row) override { values.push_back(row.values); }

  /// Index of column `name`; a test failure (and column 0) when there is none.
  int column(const std::string& name) const {
    const auto it = std::find(columns.begin(), columns.end(), name);
    if (it == columns.end()) {
      ADD_FAILURE() << "no column " << name;
      return 0;
    }
    return static_cast<int>(it - columns.begin());
  }

  /// Column `name` over every row.
  std::vector<double> series(const std::string& name) const {
    const int c = column(name);
    std::vector<double> out;
    out.reserve(values.size());
    for (const std::vector<double>& v : values) out.push_back(v[c]);
    return out;
  }

  std::vector<std::string> columns, units;
  std::vector<std::vector<double>> values;
};

}  // namespace mbfe::test
