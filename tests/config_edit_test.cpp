// Edits of the site config by key (the console's settings): values replaced
// where they are written, comments and layout kept; a new key added by
// rewriting; paths through a value that is not a map refused.
#include <gtest/gtest.h>

#include "app/config_edit.h"
#include "app/site_config.h"
#include "core/error.h"

namespace dv::app {
namespace {

const std::string kText = R"(# the site of field A
cameras:
  - {id: 0, source: synthetic://two_cameras_overlap/0}
network:
  vision: {group: 224.5.23.2, port: 10006}
robot_heights:
  default: 140             # a team not in the table
  yellow: null
  teams:
    "ER-Force": 150
detector:
  tracking: true
)";

TEST(ConfigEdit, ReplacesValuesWhereTheyAreWritten) {
  const ConfigEditResult r = editConfigText(
      kText,
      {{"robot_heights.default", "132.5"}, {"robot_heights.yellow", "150"}, {"network.vision.port", "10010"},
       {"robot_heights.teams.ER-Force", "148"}, {"detector.tracking", "false"}},
      "site.yaml");
  EXPECT_TRUE(r.layout_kept);
  std::string want = kText;
  auto replace = [&](const std::string& a, const std::string& b) { want.replace(want.find(a), a.size(), b); };
  replace("default: 140 ", "default: 132.5 ");
  replace("yellow: null", "yellow: 150");
  replace("port: 10006", "port: 10010");
  replace("\"ER-Force\": 150", "\"ER-Force\": 148");
  replace("tracking: true", "tracking: false");
  EXPECT_EQ(r.text, want);
  const SiteConfig c = parseSiteConfig(r.text, "site.yaml");
  EXPECT_EQ(c.robot_heights.default_mm, 132.5);
  EXPECT_EQ(c.robot_heights.yellow_mm, 150);
  EXPECT_EQ(c.network.vision_port, 10010);
  EXPECT_EQ(c.robot_heights.teams.at("er-force"), 148);
  EXPECT_FALSE(c.detector.tracking);
}

TEST(ConfigEdit, QuotedValuesAndNewKeys) {
  ConfigEditResult r = editConfigText("a: \"x # y\"  # comment\n", {{"a", "\"z\""}}, "t.yaml");
  EXPECT_EQ(r.text, "a: \"z\"  # comment\n");
  r = editConfigText(kText, {{"detector.ball_radius", "22"}, {"record.ssl_log", "\"a.log\""}}, "site.yaml");
  EXPECT_FALSE(r.layout_kept);  // added keys: the document is rewritten
  const SiteConfig c = parseSiteConfig(r.text, "site.yaml");
  EXPECT_EQ(c.detector.ball_radius, 22);
  EXPECT_TRUE(c.detector.tracking);
  EXPECT_EQ(c.record.ssl_log, "a.log");
  EXPECT_EQ(c.robot_heights.default_mm, 140);
}

TEST(ConfigEdit, PathsThroughValuesAreRefused) {
  try {
    editConfigText(kText, {{"robot_heights.default.x", "1"}}, "site.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "site.yaml");
    EXPECT_NE(std::string(e.what()).find("key 'robot_heights.default.x'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(editConfigText("a: [\n", {{"a", "1"}}, "t.yaml"), InputError);
  EXPECT_THROW(editConfigText(kText, {{"", "1"}}, "t.yaml"), InputError);
}

}  // namespace
}  // namespace dv::app
