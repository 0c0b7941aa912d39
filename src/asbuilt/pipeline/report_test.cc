#include "asbuilt/pipeline/report.h"

#include <gtest/gtest.h>

namespace asbuilt {
namespace {

TEST(HtmlEscape, EscapesMarkupCharacters) {
  EXPECT_EQ(HtmlEscape("<a href=\"x\">&'"), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;");
}

TEST(SurveyReportHtml, IsSelfContainedAndListsWallsWithSigmas) {
  SurveyReport r;
  r.title = "Survey of <test>";
  r.plan.walls.push_back({.start = {0, 0}, .end = {4, 0}, .length_sigma_m = 0.012});
  r.plan.openings.push_back({.kind = OpeningKind::kDoor, .wall = 0, .start = {1, 0}, .end = {2, 0}, .width = 1.0,
                             .width_sigma_m = 0.01});
  r.summary.frames = 1;
  r.summary.stages = {{"plan", 0.5}};
  r.summary.seconds = 1.0;
  r.points_plot_png = "\x89PNG";
  std::string html = SurveyReportHtml(r);
  EXPECT_NE(html.find("<title>Survey of &lt;test&gt;</title>"), std::string::npos);
  EXPECT_NE(html.find("<b>4.000</b> ± 0.012"), std::string::npos);
  EXPECT_NE(html.find("door 0"), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
  // Nothing is fetched from the network.
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
}

}  // namespace
}  // namespace asbuilt
