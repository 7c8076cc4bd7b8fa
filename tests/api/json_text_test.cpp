// api/json_text.h: JSON text never fails on bytes that are not UTF-8; they
// come out as U+FFFD, everything else as nlohmann::json writes it.
#include <gtest/gtest.h>

#include <string>

#include "api/json_text.h"

namespace mbfe::tool {
namespace {

TEST(JsonText, InvalidUtf8IsReplacedNotThrown) {
  nlohmann::json j;
  j["file"] = std::string("model_\xFF.yaml");
  j["cut"] = std::string("\xE2\x82");  // a 3-byte sequence cut after 2
  EXPECT_THROW(j.dump(), nlohmann::json::type_error);  // what every writer did
  EXPECT_EQ(json_text(j), "{\"cut\":\"\xEF\xBF\xBD\",\"file\":\"model_\xEF\xBF\xBD.yaml\"}");
  EXPECT_EQ(json_text({{"a", 1}}, 2), "{\n  \"a\": 1\n}");
}

}  // namespace
}  // namespace mbfe::tool
