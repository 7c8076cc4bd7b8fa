// The output of a simulation, as CSV or, for a path ending in .npy, as a NumPy
// array (rows x columns of doubles; the column names in the sidecar JSON).
// It never loses what it has: rows go straight to the file, which is flushed
// (and a .npy's shape rewritten) every few rows and on every exit path.
#pragma once

#include <iostream>

#include <cstdio>
#include <string>
#include <vector>

#include "runtime/simulation/simulation_types.h"

namespace mbfe {

class ResultsOutput {
 public:
  /// Opens `path` for writing, or stdout when `path` is empty; `.npy` selects
  /// the binary format.
  /// @throws runtime::InvalidInput (the tool: exit status 2) naming the path if it cannot be opened.
  explicit ResultsOutput(const std::string& path);
  ~ResultsOutput();
  ResultsOutput(const ResultsOutput&) = delete;
  ResultsOutput& operator=(const ResultsOutput&) = delete;

  void header(const std::vector<std::string>& columns);
  /// One row; each number in the shortest text that reads back as the same
  /// double (api/csv_format.h).
  void row(const double* values, std::size_t count);
  void flush();
  /// Closes and removes the file when no row has been written: bad input
  /// found after the file was opened leaves nothing behind. Only a regular
  /// file is removed: a device (/dev/null) or a pipe stays.
  void discard_if_empty();
  std::size_t rows() const { return rows_; }

 private:
  std::FILE* file_ = nullptr;
  bool owned_ = false;
  bool regular_ = false;  // a regular file (not a device or a pipe)
  std::size_t rows_ = 0;
  std::string path_;
  std::string line_;  // the row being formatted
  bool npy_ = false;
  std::size_t columns_ = 0;
};

/// The rows of a simulation into a ResultsOutput: the layout's columns as the
/// header, then one line per output row.
class ResultsObserver : public runtime::SimulationObserver {
 public:
  explicit ResultsObserver(ResultsOutput& out) : out_(out) {}
  void begin(const runtime::OutputLayout& layout) override {
    layout_ = layout;
    out_.header(layout.columns);
  }
  void row(const runtime::OutputRow& row) override { out_.row(row.values.data(), row.values.size()); }
  void notice(const std::string& text) override { std::cerr << "mbfe: " << text << "\n"; }
  /// The columns and units of the run (empty before begin()).
  const runtime::OutputLayout& layout() const { return layout_; }

 private:
  ResultsOutput& out_;
  runtime::OutputLayout layout_;
};

}  // namespace mbfe
