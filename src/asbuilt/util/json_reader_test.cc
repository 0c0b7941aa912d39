#include "asbuilt/util/json_reader.h"

#include <gtest/gtest.h>

namespace asbuilt {
namespace {

TEST(JsonField, WrongTypeNamesPathAndValue) {
  JsonDiagnostics diag("capture.json");
  auto root = ParseJsonText(R"({"frames": [{}, {}, {}, {"yaw_deg": "abc"}]})", diag);
  JsonField doc(root, diag);
  EXPECT_FALSE(doc.Required("frames").At(3).Required("yaw_deg").Number());
  ASSERT_EQ(diag.errors().size(), 1u);
  EXPECT_EQ(diag.errors()[0].ToString(), "capture.json: frames[3].yaw_deg: expected a number, got \"abc\"");
}

TEST(JsonField, MissingFieldReportedOnceAndChildrenSilent) {
  JsonDiagnostics diag("plan.json");
  auto root = ParseJsonText(R"({"version": 1})", diag);
  JsonField doc(root, diag);
  EXPECT_FALSE(doc.Required("camera").Required("fx").Positive());
  ASSERT_EQ(diag.errors().size(), 1u);
  EXPECT_EQ(diag.errors()[0].ToString(), "plan.json: camera: missing required field");
}

TEST(JsonField, RejectsNonPositiveAndNonFinite) {
  JsonDiagnostics diag("f.json");
  auto root = ParseJsonText(R"({"a": 0, "b": -1, "d": 2})", diag);
  JsonField doc(root, diag);
  EXPECT_FALSE(doc.Required("a").Positive());
  EXPECT_FALSE(doc.Required("b").NonNegative());
  EXPECT_EQ(doc.Required("d").Positive(), 2.0);
  ASSERT_EQ(diag.errors().size(), 2u);
  EXPECT_EQ(diag.errors()[0].ToString(), "f.json: a: must be > 0, got 0");
  EXPECT_EQ(diag.errors()[1].ToString(), "f.json: b: must be >= 0, got -1");
  // JSON has no NaN/inf literals; an overflowing number is reported, not inf.
  JsonDiagnostics overflow("g.json");
  ParseJsonText(R"({"c": 1e999})", overflow);
  ASSERT_EQ(overflow.errors().size(), 1u);
  EXPECT_NE(overflow.errors()[0].message.find("finite"), std::string::npos);
  JsonDiagnostics nan("h.json");
  ParseJsonText(R"({"c": NaN})", nan);
  EXPECT_EQ(nan.errors().size(), 1u);
}

TEST(JsonField, UnknownKeysAreWarnings) {
  JsonDiagnostics diag("f.json");
  auto root = ParseJsonText(R"({"a": 1, "zz": 2})", diag);
  JsonField doc(root, diag);
  EXPECT_TRUE(doc.Object({"a"}));
  EXPECT_TRUE(diag.ok());
  ASSERT_EQ(diag.warnings().size(), 1u);
  EXPECT_EQ(diag.warnings()[0].ToString(), "f.json: zz: unknown key, ignored");
}

TEST(ParseJsonText, SyntaxErrorGivesLineAndColumn) {
  JsonDiagnostics diag("bad.json");
  ParseJsonText("{\n  \"a\": 1,\n  oops\n}", diag);
  ASSERT_EQ(diag.errors().size(), 1u);
  EXPECT_NE(diag.errors()[0].message.find("invalid JSON at line 3"), std::string::npos) << diag.errors()[0].message;
}

TEST(JsonDiagnostics, ThrowIfErrorsCarriesEveryProblem) {
  JsonDiagnostics diag("x.json");
  diag.AddError("a", "one");
  diag.AddError("b", "two");
  try {
    diag.ThrowIfErrors();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems().size(), 2u);
    EXPECT_EQ(std::string(e.what()), "x.json: a: one\nx.json: b: two");
  }
}

}  // namespace
}  // namespace asbuilt
