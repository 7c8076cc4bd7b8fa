// The notice before a long linearisation: none for small models, the
// measured case reproduced, and the n^3 growth of the estimate.
#include <gtest/gtest.h>

#include <string>

#include "tool/linearization_notice.h"

namespace mbfe::tool {
namespace {

TEST(LinearizationNotice, SilentForSmallModels) {
  EXPECT_EQ(linearization_notice("stability", kLinearizationNoticeCoordinates, 2), "");
  EXPECT_EQ(linearization_notice("stability", 402, 1), "");
}

TEST(LinearizationNotice, EstimatesTheMeasuredTwoSpanCatenary) {
  // 1,927 coordinates, original and adjusted: 2 x 6 minutes, as measured.
  const std::string notice = linearization_notice("stability", 1927, 2);
  EXPECT_NE(notice.find("mbfe stability: the coupled system has 1927 coordinates"), std::string::npos) << notice;
  EXPECT_NE(notice.find("3854 states"), std::string::npos) << notice;
  EXPECT_NE(notice.find("for the original and the adjusted model: about 12 minutes"), std::string::npos) << notice;
}

TEST(LinearizationNotice, GrowsAsTheCubeOfTheSize) {
  // Twice the coordinates, once: 8 x 6 minutes.
  const std::string notice = linearization_notice("modal", 3854, 1);
  EXPECT_NE(notice.find("done once: about 48 minutes"), std::string::npos) << notice;
  // 1,100 coordinates: 6 (1100/1927)^3 = 1.1 minutes.
  EXPECT_NE(linearization_notice("modal", 1100, 1).find("about a minute"), std::string::npos);
}

}  // namespace
}  // namespace mbfe::tool
