#include "asbuilt/dataset/mix.h"

#include <unistd.h>

#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/labels/label_io.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path MixTestDir() {
  fs::path dir = fs::temp_directory_path() /
                 ("asbuilt_mix_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  return dir;
}

// n distinct small pairs under dir/images + dir/labels (`tag` makes the
// bytes differ between datasets). Plain imwrite: fixtures need no fsync.
void MakeDataset(const fs::path& dir, int n, int tag) {
  fs::create_directories(dir / "images");
  fs::create_directories(dir / "labels");
  for (int i = 0; i < n; ++i) {
    cv::Mat image(6, 8, CV_8UC3, cv::Scalar(i % 256, i / 256, tag));
    cv::Mat label(6, 8, CV_8UC1, cv::Scalar(i % 4));
    cv::imwrite((dir / fmt::format("images/{:04d}.png", i)).string(), image);
    cv::imwrite((dir / fmt::format("labels/{:04d}.png", i)).string(), label);
  }
}

std::set<std::string> Images(const std::vector<ManifestEntry>& list) {
  std::set<std::string> out;
  for (const ManifestEntry& e : list) out.insert(e.image);
  return out;
}

int Count(const std::vector<ManifestEntry>& list, PairSource s) {
  return static_cast<int>(
      std::count_if(list.begin(), list.end(), [&](const ManifestEntry& e) { return e.source == s; }));
}

TEST(MixConfig, ParsesNamedAndAnyRsRatio) {
  EXPECT_EQ(MixConfig::Parse("R100")->real_percent, 100);
  EXPECT_EQ(MixConfig::Parse("S100")->synthetic_percent, 100);
  EXPECT_EQ(MixConfig::Parse("rs8020")->Name(), "RS8020");
  EXPECT_EQ(MixConfig::Parse("RS2080")->real_percent, 20);
  EXPECT_EQ(MixConfig::Parse("RS3070")->ToString(), "RS3070 (30 % real, 70 % synthetic)");
  EXPECT_FALSE(MixConfig::Parse("RS10000"));  // R100 is the pure form.
}

TEST(MixConfig, RejectsBadNames) {
  for (const char* bad : {"RS5060", "RS50", "R50", "S", "RSabcd", ""}) EXPECT_FALSE(MixConfig::Parse(bad)) << bad;
  try {
    MixOptions{.config = "RS5060"}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("MixOptions.config = \"RS5060\""), std::string::npos);
  }
}

class MixTest : public ::testing::Test {
 protected:
  // One folder per process: ctest runs each test in its own process, in
  // parallel, and a shared fixed name would be rebuilt under a sibling's feet.
  static fs::path Sources() {
    return fs::temp_directory_path() / ("asbuilt_mix_sources_" + std::to_string(::getpid()));
  }
  static void SetUpTestSuite() {
    fs::path dir = Sources();
    fs::remove_all(dir);
    MakeDataset(dir / "real", 120, 1);
    MakeDataset(dir / "synth", 400, 2);
  }
  void SetUp() override {
    dir_ = MixTestDir();
    fs::create_directories(dir_);
  }
  MixSummary Mix(const MixOptions& o) {
    return MixDataset(o, sources_ / "real", sources_ / "synth", {}, dir_ / "out/manifest.json");
  }
  const fs::path sources_ = Sources();
  fs::path dir_;
};

TEST_F(MixTest, Rs5050UsesTheRatioAndSplitsNineToOne) {
  MixSummary s = Mix({.config = "RS5050", .total = 200, .seed = 7});
  const Manifest& m = s.manifest;
  EXPECT_EQ(m.config, "RS5050");
  EXPECT_EQ(m.train.size() + m.val.size(), 200u);
  EXPECT_EQ(m.val.size(), 20u);
  EXPECT_EQ(Count(m.train, PairSource::kReal) + Count(m.val, PairSource::kReal), 100);
  EXPECT_EQ(Count(m.val, PairSource::kReal), 10);  // Val has the mix's ratio too.
  EXPECT_EQ(m.test.size(), 12u);                   // 10 % of 120 real.
  EXPECT_EQ(Count(m.test, PairSource::kReal), 12);
  // The manifest on disk reads back, checksums verified.
  Manifest r = ReadManifest(dir_ / "out/manifest.json", {.verify_checksums = true});
  EXPECT_EQ(ManifestToJson(r), ManifestToJson(m));
  EXPECT_EQ(r.train[0].image.rfind("../../", 0), 0u) << r.train[0].image;
  EXPECT_FALSE(r.train[0].sha256.empty());
}

TEST_F(MixTest, TestSetIsHeldOutAndTheSameForEveryConfig) {
  std::set<std::string> first_test;
  for (const char* config : {"R100", "RS8020", "RS5050", "RS2080", "S100"}) {
    MixSummary s = Mix({.config = config, .seed = 3, .checksums = false});
    const Manifest& m = s.manifest;
    std::set<std::string> test = Images(m.test), train = Images(m.train), val = Images(m.val);
    for (const std::string& t : test) {
      EXPECT_FALSE(train.count(t)) << config << " " << t;
      EXPECT_FALSE(val.count(t)) << config << " " << t;
    }
    if (first_test.empty()) first_test = test;
    EXPECT_EQ(test, first_test) << config;
    EXPECT_EQ(test.size(), 12u);
  }
}

TEST_F(MixTest, ReviewedRoomsAreHeldOutWholeNeverByView) {
  // Five survey folders whose reviews were saved, 12 views each, given one
  // by one as a surveyor would: every test room's views are all in test.
  std::vector<fs::path> rooms;
  for (const char* room : {"kitchen", "hall", "bedroom", "bath", "attic"}) {
    rooms.push_back(dir_ / "surveys" / room);
    MakeDataset(rooms.back() / "review" / "training", 12, 3);
  }
  for (int seed = 1; seed <= 5; ++seed) {
    const MixSummary s = MixDataset(
        {.config = "RS5050", .test_fraction = 0.25, .seed = static_cast<std::uint64_t>(seed), .checksums = false},
        rooms, sources_ / "synth", {}, dir_ / "out/rooms.json");
    auto room_of = [](const ManifestEntry& e) {
      const std::string tail = e.image.substr(e.image.find("surveys/") + 8);
      return tail.substr(0, tail.find('/'));
    };
    std::set<std::string> test_rooms, train_rooms;
    for (const ManifestEntry& e : s.manifest.test) test_rooms.insert(room_of(e));
    for (const auto* list : {&s.manifest.train, &s.manifest.val}) {
      for (const ManifestEntry& e : *list) {
        if (e.source == PairSource::kReal) train_rooms.insert(room_of(e));
      }
    }
    EXPECT_EQ(s.manifest.test.size() % 12, 0u) << "seed " << seed;
    EXPECT_EQ(test_rooms.size(), 2u) << "seed " << seed;  // 25 % of 60 views: 15, so two rooms of 12.
    for (const std::string& r : test_rooms) EXPECT_FALSE(train_rooms.count(r)) << r << ", seed " << seed;
  }
}

TEST_F(MixTest, OneReviewedRoomCannotBeItsOwnTest) {
  MakeDataset(dir_ / "one" / "review" / "training", 12, 3);
  try {
    MixDataset({.config = "R100", .checksums = false}, std::vector<fs::path>{dir_ / "one"}, {}, {},
               dir_ / "out/one.json");
    FAIL() << "a one-room mix was built";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("all of one room (review/training)"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "out/one.json"));
}

TEST_F(MixTest, ReviewTrainingFoldersAreNamedByTheirSurveys) {
  // Given as OUT/review/training rather than OUT, each is still its own room.
  std::vector<fs::path> folders;
  for (const char* room : {"kitchen", "hall"}) {
    folders.push_back(dir_ / "direct" / room / "review" / "training");
    MakeDataset(folders.back(), 6, 3);
  }
  const MixSummary s = MixDataset({.config = "R100", .test_fraction = 0.4, .checksums = false}, folders, {}, {},
                                  dir_ / "out/direct.json");
  ASSERT_EQ(s.manifest.test.size(), 6u);  // One whole room.
  const std::string room = s.manifest.test[0].image.find("/kitchen/") != std::string::npos ? "/kitchen/" : "/hall/";
  for (const ManifestEntry& e : s.manifest.test) EXPECT_NE(e.image.find(room), std::string::npos) << e.image;
  // One such folder alone is one room: nothing left to test on.
  EXPECT_THROW(MixDataset({.config = "R100", .checksums = false}, std::vector<fs::path>{folders[0]}, {}, {},
                          dir_ / "out/direct1.json"),
               Error);
}

TEST_F(MixTest, DefaultTotalIsTheLargestMixTheSourcesAllow) {
  // 108 real after the hold-out, 400 synthetic.
  MixSummary r100 = Mix({.config = "R100", .checksums = false});
  EXPECT_EQ(r100.manifest.train.size() + r100.manifest.val.size(), 108u);
  MixSummary s5050 = Mix({.config = "RS5050", .checksums = false});
  EXPECT_EQ(s5050.real_used, 108);
  EXPECT_EQ(s5050.synthetic_used, 108);
  MixSummary s2080 = Mix({.config = "RS2080", .checksums = false});
  // min(108 / 0.2, 400 / 0.8) = 500 pairs: 100 real, 400 synthetic.
  EXPECT_EQ(s2080.real_used, 100);
  EXPECT_EQ(s2080.synthetic_used, 400);
  EXPECT_EQ(Mix({.config = "S100", .checksums = false}).synthetic_used, 400);
}

TEST_F(MixTest, SeedsAreReproducibleAndMatter) {
  MixSummary a = Mix({.config = "RS5050", .seed = 11});
  MixSummary b = Mix({.config = "RS5050", .seed = 11});
  MixSummary c = Mix({.config = "RS5050", .seed = 12});
  EXPECT_EQ(ManifestToJson(a.manifest), ManifestToJson(b.manifest));
  EXPECT_NE(ManifestToJson(a.manifest), ManifestToJson(c.manifest));
}

TEST_F(MixTest, TooSmallSourcesGiveAClearError) {
  try {
    Mix({.config = "RS5050", .total = 1000});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "RS5050 with total 1000 needs 500 real pairs (after holding out 12 for test) and 500 synthetic, "
              "have 108 and 400");
  }
  EXPECT_FALSE(fs::exists(dir_ / "out/manifest.json"));
}

TEST_F(MixTest, ExplicitTestSetMustNotDuplicateTrainingImages) {
  MakeDataset(dir_ / "test", 5, 3);
  MixSummary s = MixDataset({.config = "R100"}, sources_ / "real", {}, dir_ / "test", dir_ / "m.json");
  EXPECT_EQ(s.manifest.test.size(), 5u);
  EXPECT_EQ(s.real_available, 120);
  // A copy of a training photo under another name in the test set is caught.
  MakeDataset(dir_ / "leak", 1, 1);  // Same bytes as real/0000.
  try {
    MixDataset({.config = "R100"}, sources_ / "real", {}, dir_ / "leak", dir_ / "m2.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is byte-identical to training image"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace asbuilt
