#include "asbuilt/dataset/synth_merge.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/formats/synth_dataset.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// A synth folder of `count` items as dataset synth leaves it (tiny images).
fs::path MakeSynthDir(const std::string& name, int count) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("asbuilt_merge_{}_{}", name, ::getpid());
  fs::remove_all(dir);
  ClaimSynthDir(dir, {{"count", count}, {"seed", 3}});
  for (int i = 0; i < count; ++i) {
    const auto files = SynthItemFiles(dir, i);
    for (std::size_t k = 0; k + 1 < files.size(); ++k) {
      fs::create_directories(files[k].parent_path());
      cv::imwrite(files[k].string(), cv::Mat(4, 6, CV_8UC1, cv::Scalar(i * 10 + static_cast<int>(k))));
    }
    fs::create_directories(files.back().parent_path());
    std::ofstream(files.back()) << fmt::format("{{\"version\": 1, \"index\": {}}}\n", i);
  }
  return dir;
}

std::string ErrorOf(const fs::path& dir, const SynthMergeOptions& options) {
  try {
    MergeSynthDataset(dir, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MergeSynthDataset, WritesOneManifestThatVerifiesAndIsTheSameEachTime) {
  const fs::path dir = MakeSynthDir("whole", 6);
  SynthMergeSummary s = MergeSynthDataset(dir);
  EXPECT_EQ(s.items, 6);
  EXPECT_EQ(s.files, 30);
  const std::string manifest = ReadFile(SynthManifestPath(dir));
  EXPECT_NE(manifest.find("\"images/000005.png\":\""), std::string::npos) << manifest.substr(0, 400);
  EXPECT_EQ(MergeSynthDataset(dir, {.shard_count = 3, .num_threads = 1}).items, 6);
  EXPECT_EQ(ReadFile(SynthManifestPath(dir)), manifest) << "no shard count, thread count or time in it";

  SynthVerifySummary v = VerifySynthDataset(dir);
  EXPECT_TRUE(v.ok()) << v.BriefReport();
  EXPECT_EQ(v.files, 30);
  cv::imwrite((dir / "labels" / "000002.png").string(), cv::Mat(4, 6, CV_8UC1, cv::Scalar(99)));
  fs::remove(dir / "depth" / "000004.png");
  v = VerifySynthDataset(dir);
  ASSERT_EQ(v.problems.size(), 2u) << v.BriefReport();
  EXPECT_NE(v.problems[0].ToString().find("depth/000004.png: missing"), std::string::npos) << v.problems[0].ToString();
  EXPECT_NE(v.problems[1].ToString().find("labels/000002.png: changed since the merge"), std::string::npos)
      << v.problems[1].ToString();
}

TEST(MergeSynthDataset, NamesTheShardsWithMissingItemsAndWritesNothing) {
  const fs::path dir = MakeSynthDir("missing", 8);
  fs::remove(dir / "meta" / "000002.json");
  fs::remove(dir / "images" / "000003.png");
  fs::remove(dir / "meta" / "000007.json");
  const std::string error = ErrorOf(dir, {.shard_count = 4});
  EXPECT_NE(error.find("shard 1/4 (items 2-3): 2 of its 2 items missing or incomplete: 2-3"), std::string::npos)
      << error;
  EXPECT_NE(error.find("shard 3/4 (items 6-7): 1 of its 2 items missing or incomplete: 7"), std::string::npos) << error;
  EXPECT_EQ(ErrorOf(dir, {}).find("shard"), std::string::npos);
  EXPECT_FALSE(fs::exists(SynthManifestPath(dir)));
  EXPECT_THROW(MergeSynthDataset(dir, {.shard_count = 9}), InvalidArgument);
}

TEST(MergeSynthDataset, NamesADamagedFile) {
  const fs::path dir = MakeSynthDir("damaged", 3);
  const fs::path image = dir / "images" / "000001.png";
  const std::string bytes = ReadFile(image);
  std::ofstream(image, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
  std::ofstream(dir / "meta" / "000002.json", std::ios::trunc) << "{\"index\": 5}";
  const std::string error = ErrorOf(dir, {});
  EXPECT_NE(error.find("images/000001.png: damaged (a PNG cut short"), std::string::npos) << error;
  EXPECT_NE(error.find("meta/000002.json: damaged (does not name index 2)"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(SynthManifestPath(dir)));
}

TEST(MergeSynthDataset, RefusesAFolderThatIsNotASynthDataset) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("asbuilt_merge_none_{}", ::getpid());
  fs::create_directories(dir);
  EXPECT_THROW(MergeSynthDataset(dir), InputError);
  EXPECT_THROW(VerifySynthDataset(dir), InputError);
}

}  // namespace
}  // namespace asbuilt
