#include "asbuilt/seg/learn.h"

#include <filesystem>
#include <functional>

#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/seg/model_io.h"
#include "asbuilt/seg/toy_rooms.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// Four corrected "surveys" of toy rooms (6 views each) and a small starting
// model, shared by the tests of this file.
struct LearnFixture {
  fs::path dir, surveys, model;
};

const LearnFixture& Fixture() {
  static const LearnFixture f = [] {
    LearnFixture x;
    x.dir = fs::temp_directory_path() / fmt::format("asbuilt_learn_test_{}", ::getpid());
    x.surveys = x.dir / "surveys";
    for (int room = 0; room < 4; ++room) {
      const fs::path survey = x.surveys / fmt::format("room{}", room);
      WriteToyRoomSet(survey / "review" / "training", 6,
                      {.width_px = 64, .height_px = 48, .seed = static_cast<std::uint64_t>(20 + room)});
      WriteFileAtomic(survey / "summary.json", "{}\n");
    }
    SegformerConfig config = SegformerConfigFor("tiny", 4);
    torch::manual_seed(1);
    Segformer model(config);
    x.model = x.dir / "start.pt";
    SaveCheckpoint(x.model, *model, nullptr,
                   {{"format", kCheckpointFormat},
                    {"config", ConfigToJson(config)},
                    {"scale", {64, 48}},
                    {"crop", {64, 48}},
                    {"epoch", 1}});
    return x;
  }();
  return f;
}

// A learn run on the fixture's rooms, R100, a few steps on one thread.
LearnOptions QuickOptions(const std::string& out, int epochs, int steps_per_epoch) {
  const LearnFixture& f = Fixture();
  LearnOptions o;
  o.reviews = {f.surveys};
  o.model = f.model;
  o.config = "R100";
  o.out_dir = f.dir / out;
  o.epochs = epochs;
  o.steps_per_epoch = steps_per_epoch;
  o.threads = 1;
  return o;
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(FindReviewExamples, TakesSurveysTheirTrainingFoldersAndFoldersOfSurveys) {
  const LearnFixture& f = Fixture();
  const auto all = FindReviewExamples({f.surveys});
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all[0], f.surveys / "room0" / "review" / "training");
  EXPECT_EQ(FindReviewExamples({f.surveys / "room1"}).at(0), f.surveys / "room1" / "review" / "training");
  EXPECT_EQ(FindReviewExamples({f.surveys / "room2" / "review" / "training"}).size(), 1u);
}

TEST(FindReviewExamples, SaysWhatToRunForASurveyWithoutASavedReview) {
  const LearnFixture& f = Fixture();
  const fs::path unreviewed = f.dir / "unreviewed";
  WriteFileAtomic(unreviewed / "summary.json", "{}\n");
  EXPECT_NE(ErrorOf([&] { FindReviewExamples({unreviewed}); }).find("asbuilt review"), std::string::npos);
  WriteFileAtomic(unreviewed / "review" / "corrections.json", "{}\n");
  EXPECT_NE(ErrorOf([&] { FindReviewExamples({unreviewed}); }).find("--export-training"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { FindReviewExamples({f.dir / "missing"}); }).find("not found"), std::string::npos);
}

TEST(LearnFromReviews, FineTunesJudgesOnHeldOutRoomsAndKeepsOnlyABetterModel) {
  const LearnOptions o = QuickOptions("run", 2, 3);
  const LearnSummary s = LearnFromReviews(o);
  EXPECT_EQ(s.examples.size(), 4u);
  EXPECT_EQ(s.test_pairs, 6);  // One whole room of four (25 %), never single views.
  EXPECT_GT(s.train_pairs, 0);
  EXPECT_EQ(s.before.images, 6);
  EXPECT_EQ(s.after.images, 6);
  EXPECT_EQ(s.improved, s.after.miou > s.before.miou);
  EXPECT_EQ(fs::exists(o.out_dir / "model.pt"), s.improved);
  EXPECT_TRUE(fs::exists(o.out_dir / "train" / "best.pt"));
  const std::string report = ReadFile(o.out_dir / "report.md");
  EXPECT_NE(report.find("| wall |"), std::string::npos) << report;
  EXPECT_NE(report.find("mIoU"), std::string::npos);
}

TEST(LearnFromReviews, LeavesTheNamedRoomOut) {
  LearnOptions o = QuickOptions("loo", 1, 1);
  o.hold_out = Fixture().surveys / "room2";
  const LearnSummary s = LearnFromReviews(o);
  EXPECT_EQ(s.examples.size(), 3u);
  EXPECT_EQ(s.test_pairs, 6);
  EXPECT_EQ(s.train_pairs + s.val_pairs, 18);
  const nlohmann::json mix = nlohmann::json::parse(ReadFile(o.out_dir / "mix.json"));
  for (const auto& e : mix.at("test")) EXPECT_NE(e.at("image").get<std::string>().find("room2"), std::string::npos);
  for (const char* list : {"train", "val"}) {
    for (const auto& e : mix.at(list)) EXPECT_EQ(e.at("image").get<std::string>().find("room2"), std::string::npos);
  }
}

TEST(LearnFromReviews, RefusesBadInputWithOneMessage) {
  const LearnFixture& f = Fixture();
  LearnOptions o;
  o.reviews = {f.surveys};
  o.model = f.model;
  o.out_dir = f.dir / "bad";
  // RS5050 (the default) needs renders.
  EXPECT_NE(ErrorOf([&] { LearnFromReviews(o); }).find("--synthetic"), std::string::npos);
  // One room: none left to judge on.
  o.config = "R100";
  o.reviews = {f.surveys / "room0"};
  EXPECT_NE(ErrorOf([&] { LearnFromReviews(o); }), "");
  // A model file that is not a model.
  o.reviews = {f.surveys};
  o.model = f.surveys / "room0" / "summary.json";
  EXPECT_NE(ErrorOf([&] { LearnFromReviews(o); }).find("summary.json"), std::string::npos);
  EXPECT_FALSE(fs::exists(o.out_dir / "model.pt"));
}

}  // namespace
}  // namespace asbuilt
