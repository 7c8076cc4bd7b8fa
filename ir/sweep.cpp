#include "ir/sweep.h"

namespace mbfe::ir {

long Sweep::points() const {
  if (vary.empty()) return 1;
  if (zip) return static_cast<long>(vary.front().values.size());
  long n = 1;
  for (const SweepVariable& v : vary) n *= static_cast<long>(v.values.size());
  return n;
}

std::vector<int> Sweep::indices(long i) const {
  std::vector<int> out(vary.size(), 0);
  if (zip) {
    for (int& k : out) k = static_cast<int>(i);
    return out;
  }
  for (std::size_t k = vary.size(); k-- > 0;) {
    const long count = static_cast<long>(vary[k].values.size());
    out[k] = static_cast<int>(i % count);
    i /= count;
  }
  return out;
}

}  // namespace mbfe::ir
