#include "tool/sweep_stats.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "runtime/errors/invalid_input.h"
#include "runtime/signal/force_statistics.h"

namespace mbfe::tool {

namespace {
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
}  // namespace

bool is_beam_coordinate(const ir::Model& model, const std::string& column) {
  for (const ir::Beam& b : model.beams) {
    for (const char* kind : {"_w", "_dw"}) {
      const std::string head = b.name + kind;
      if (column.size() <= head.size() || column.compare(0, head.size(), head) != 0) continue;
      std::size_t k = head.size();
      while (k < column.size() && std::isdigit(static_cast<unsigned char>(column[k]))) ++k;
      if (k > head.size() && (k == column.size() || column.compare(k, std::string::npos, "_dot") == 0)) return true;
    }
  }
  return false;
}

void SweepStatsObserver::begin(const runtime::OutputLayout& layout) {
  std::vector<std::string> kept_names;
  for (std::size_t k = 0; k < layout.columns.size(); ++k)
    if (sweep_.simulation.full_state || !is_beam_coordinate(model_, layout.columns[k])) {
      kept_.push_back(k);
      kept_names.push_back(layout.columns[k]);
    }
  csv_.header(kept_names);
  kept_values_.resize(kept_.size());
  for (const ir::SweepCollect& c : sweep_.collect) {
    int index = -1;
    for (std::size_t k = 0; k < layout.columns.size(); ++k)
      if (layout.columns[k] == c.column) index = static_cast<int>(k);
    if (index < 0) {
      std::string names;
      for (const std::string& n : layout.columns) names += (names.empty() ? "" : ", ") + n;
      throw runtime::InvalidInput("collect '" + c.name + "': the run has no column '" + c.column +
                                  "' (its columns: " + names + ")");
    }
    columns_.push_back(index);
  }
  acc_.assign(columns_.size(), Acc{});
  samples_.assign(columns_.size(), {});
  any_samples_ =
      std::any_of(sweep_.collect.begin(), sweep_.collect.end(), [](const ir::SweepCollect& c) { return c.as_stats(); });
}

void SweepStatsObserver::row(const runtime::OutputRow& row) {
  if (kept_.size() == row.values.size()) {
    csv_.row(row.values.data(), row.values.size());
  } else {
    for (std::size_t k = 0; k < kept_.size(); ++k) kept_values_[k] = row.values[kept_[k]];
    csv_.row(kept_values_.data(), kept_values_.size());
  }
  if (any_samples_) times_.push_back(row.values[0]);  // column 0 is t
  for (std::size_t k = 0; k < columns_.size(); ++k) {
    const double v = row.values[static_cast<std::size_t>(columns_[k])];
    if (sweep_.collect[k].as_stats()) samples_[k].push_back(v);
    Acc& a = acc_[k];
    a.max = std::max(a.max, v);
    a.min = std::min(a.min, v);
    a.absmax = std::max(a.absmax, std::abs(v));
    a.sum += v;
    a.sum2 += v * v;
    if (a.n == 0) a.first = v;
    a.last = v;
    ++a.n;
  }
}

std::vector<double> SweepStatsObserver::stats(std::vector<std::string>* errors) const {
  std::vector<double> out;
  for (std::size_t k = 0; k < sweep_.collect.size(); ++k) {
    const ir::SweepCollect& c = sweep_.collect[k];
    if (k >= acc_.size() || acc_[k].n == 0) {
      out.push_back(kNan);
      continue;
    }
    if (c.as_stats()) {
      runtime::ForceStatisticsOptions options;
      options.lowpass_hz = c.lowpass_hz;
      options.order = c.order;
      if (c.from) options.from = *c.from;
      if (c.to) options.to = *c.to;
      try {
        const runtime::ForceStatistics s = runtime::force_statistics(times_, samples_[k], options);
        switch (c.stat) {
          case ir::SweepStat::kMax:
            out.push_back(s.max);
            break;
          case ir::SweepStat::kMin:
            out.push_back(s.min);
            break;
          case ir::SweepStat::kAbsMax:
            out.push_back(std::max(std::abs(s.max), std::abs(s.min)));
            break;
          case ir::SweepStat::kMean:
            out.push_back(s.mean);
            break;
          // The population std over the same samples: rms^2 = mean^2 + std^2.
          case ir::SweepStat::kRms:
            out.push_back(std::hypot(s.mean, s.std));
            break;
          case ir::SweepStat::kStd:
            out.push_back(s.std);
            break;
          case ir::SweepStat::kStatisticalMax:
            out.push_back(s.statistical_max);
            break;
          case ir::SweepStat::kStatisticalMin:
            out.push_back(s.statistical_min);
            break;
          case ir::SweepStat::kLossPercent:
            out.push_back(s.loss_percent);
            break;
          case ir::SweepStat::kInitial:
          case ir::SweepStat::kFinal:
            out.push_back(kNan);
            break;  // refused with a filter or window
        }
      } catch (const std::invalid_argument& e) {  // BadSample is one too
        out.push_back(kNan);
        if (errors) errors->push_back("collect '" + c.name + "': " + e.what());
      }
      continue;
    }
    const Acc& a = acc_[k];
    switch (c.stat) {
      case ir::SweepStat::kMax: out.push_back(a.max); break;
      case ir::SweepStat::kMin: out.push_back(a.min); break;
      case ir::SweepStat::kAbsMax: out.push_back(a.absmax); break;
      case ir::SweepStat::kMean: out.push_back(a.sum / a.n); break;
      case ir::SweepStat::kRms: out.push_back(std::sqrt(a.sum2 / a.n)); break;
      case ir::SweepStat::kInitial: out.push_back(a.first); break;
      case ir::SweepStat::kFinal: out.push_back(a.last); break;
      default:
        out.push_back(kNan);
        break;  // the EN 50318 statistics are as_stats()
    }
  }
  return out;
}

}  // namespace mbfe::tool
