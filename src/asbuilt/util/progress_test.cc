#include "asbuilt/util/progress.h"

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

namespace asbuilt {
namespace {

std::string Captured(std::FILE* f) {
  std::rewind(f);
  std::string out;
  int c;
  while ((c = std::fgetc(f)) != EOF) out.push_back(static_cast<char>(c));
  return out;
}

TEST(ProgressPrinter, PlainModePrintsFirstAndLastLine) {
  std::FILE* f = std::tmpfile();
  {
    ProgressPrinter printer(f, /*is_terminal=*/false, std::chrono::hours(1));
    for (int i = 1; i <= 10; ++i) printer.Update({.stage = "render", .done = i, .total = 10});
  }
  std::string out = Captured(f);
  std::fclose(f);
  EXPECT_NE(out.find("render: 1/10 (10%)"), std::string::npos) << out;
  EXPECT_NE(out.find("render: 10/10 (100%) in"), std::string::npos) << out;
  EXPECT_EQ(out.find("render: 5/10"), std::string::npos) << out;
}

TEST(ProgressPrinter, TerminalModeDrawsBarAndEndsLine) {
  std::FILE* f = std::tmpfile();
  {
    ProgressPrinter printer(f, /*is_terminal=*/true, std::chrono::seconds(1));
    printer.Update({.stage = "train", .done = 4, .total = 4, .detail = "loss 0.1"});
  }
  std::string out = Captured(f);
  std::fclose(f);
  EXPECT_NE(out.find("[############################] 4/4"), std::string::npos) << out;
  EXPECT_NE(out.find("loss 0.1"), std::string::npos);
  EXPECT_EQ(out.back(), '\n');
}

TEST(ProgressPrinter, FormatsDurations) {
  EXPECT_EQ(ProgressPrinter::FormatDuration(5.2), "5s");
  EXPECT_EQ(ProgressPrinter::FormatDuration(65), "1m05s");
  EXPECT_EQ(ProgressPrinter::FormatDuration(3 * 3600 + 120), "3h02m");
}

}  // namespace
}  // namespace asbuilt
