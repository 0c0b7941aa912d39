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
  r.plan.openings.push_back(
      {.kind = OpeningKind::kDoor, .wall = 0, .start = {1, 0}, .end = {2, 0}, .width = 1.0, .width_sigma_m = 0.01});
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

TEST(SurveyReportHtml, StartsWithTheVerdictAndTheWallsToCheck) {
  SurveyReport r;
  r.summary.verdict.verdict = Verdict::kCheck;
  r.summary.verdict.confidence = 0.62;
  r.summary.verdict.reasons = {"walls were found in only 45 % of the directions around the camera"};
  r.summary.verdict.walls.resize(2);
  r.summary.verdict.walls[1] = {.verdict = Verdict::kUnreliable, .reasons = {"inferred: no point of it was seen"}};
  const std::string html = SurveyReportHtml(r);
  const std::size_t verdict = html.find("id=\"verdict\""), summary = html.find("<h2>Summary</h2>");
  ASSERT_NE(verdict, std::string::npos);
  EXPECT_LT(verdict, summary);
  EXPECT_NE(html.find("Check before use"), std::string::npos);
  EXPECT_NE(html.find("confidence 0.62"), std::string::npos);
  EXPECT_NE(html.find("only 45 % of the directions"), std::string::npos);
  EXPECT_NE(html.find("<td>1</td><td class=\"l bad\">unreliable</td>"), std::string::npos);
  EXPECT_EQ(html.find("<td>0</td><td class=\"l"), std::string::npos);  // A good wall is not listed.
}

}  // namespace
}  // namespace asbuilt
