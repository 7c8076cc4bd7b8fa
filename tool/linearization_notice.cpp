#include "tool/linearization_notice.h"

#include <cmath>
#include <sstream>

namespace mbfe::tool {

namespace {

// Measured: the two-span catenary (1,927 coordinates, 3,854 states), one
// linearisation and its eigenvalues in 6 minutes on the 2-core machine of
// docs/performance.md; the dense eigenproblem grows as n^3.
constexpr double kMeasuredCoordinates = 1927.0;
constexpr double kMeasuredMinutes = 6.0;

}  // namespace

std::string linearization_notice(const std::string& command, int coordinates, int variants) {
  if (coordinates <= kLinearizationNoticeCoordinates) return "";
  const double minutes = variants * kMeasuredMinutes * std::pow(coordinates / kMeasuredCoordinates, 3.0);
  std::ostringstream os;
  os << "mbfe " << command << ": the coupled system has " << coordinates
     << " coordinates; its linearisation is a dense eigenproblem of " << 2 * coordinates << " states, done "
     << (variants == 1 ? "once" : "for the original and the adjusted model") << ": about ";
  if (minutes < 1.5) {
    os << "a minute";
  } else {
    os << std::lround(minutes) << " minutes";
  }
  os << " on a 2-core machine (mbfe modal MODEL.yaml --beam NAME shows one beam's modes at once)\n";
  return os.str();
}

}  // namespace mbfe::tool
