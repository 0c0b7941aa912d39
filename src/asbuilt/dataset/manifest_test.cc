#include "asbuilt/dataset/manifest.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/dataset/checksum.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

class ManifestTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("asbuilt_manifest_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    for (const char* f : {"data/images/a.jpg", "data/labels/a.png", "data/images/b.jpg", "data/labels/b.png",
                          "data/images/t.jpg", "data/labels/t.png"}) {
      WriteFileAtomic(dir_ / f, std::string("bytes of ") + f);
    }
  }
  std::vector<std::string> Errors(const std::string& text) {
    WriteFileAtomic(dir_ / "manifest.json", text);
    std::vector<std::string> out;
    for (const Problem& p : CheckManifestFile(dir_ / "manifest.json").errors) {
      out.push_back(p.field_path + ": " + p.message);
    }
    return out;
  }
  Manifest Sample() {
    Manifest m;
    m.config = "RS5050";
    m.seed = 7;
    m.root = "data";
    m.base_dir = dir_;
    m.train = {{"images/a.jpg", "labels/a.png", PairSource::kReal, Sha256OfFile(dir_ / "data/images/a.jpg"),
                Sha256OfFile(dir_ / "data/labels/a.png")}};
    m.val = {{"images/b.jpg", "labels/b.png", PairSource::kSynthetic, "", ""}};
    m.test = {{"images/t.jpg", "labels/t.png", PairSource::kReal, "", ""}};
    return m;
  }
  fs::path dir_;
};

TEST_F(ManifestTest, WritesAndReadsBack) {
  Manifest m = Sample();
  WriteManifest(m, dir_ / "manifest.json");
  Manifest r = ReadManifest(dir_ / "manifest.json", {.verify_checksums = true});
  EXPECT_EQ(ManifestToJson(r), ManifestToJson(m));
  EXPECT_EQ(r.train, m.train);
  EXPECT_EQ(r.Resolve(r.train[0].image), dir_ / "data/images/a.jpg");
  EXPECT_EQ(r.ToString(), "Manifest(RS5050, seed 7: 1 train, 1 val, 1 test)");
  EXPECT_TRUE(CheckManifestFile(dir_ / "manifest.json").errors.empty());
}

TEST_F(ManifestTest, MissingFileIsNamedWithItsField) {
  auto errors = Errors(R"({"version": 1, "config": "R100", "seed": 1, "root": "data",
    "train": [{"image": "images/a.jpg", "label": "labels/zz.png", "source": "real"}], "val": []})");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "train[0].label: file not found: " + (dir_ / "data/labels/zz.png").string());
}

TEST_F(ManifestTest, ReportsEveryProblem) {
  auto errors = Errors(R"({"version": 2, "config": "R100",
    "train": [{"image": "data/images/a.jpg", "label": "data/labels/a.png", "source": "photo",
               "sha256": "xyz"},
              {"image": "data/images/a.jpg", "label": "data/labels/a.png", "source": "real"}],
    "val": [],
    "test": [{"image": "data/images/a.jpg", "label": "data/labels/a.png", "source": "real"},
             {"image": "data/images/t.jpg", "label": "data/labels/t.png", "source": "synthetic"}]})");
  ASSERT_EQ(errors.size(), 6u) << ::testing::PrintToString(errors);
  EXPECT_EQ(errors[0], "version: unsupported version 2, expected 1");
  EXPECT_EQ(errors[1], "train[0].sha256: expected 64 lowercase hex digits, got \"xyz\"");
  EXPECT_EQ(errors[2], "train[0].source: expected \"real\" or \"synthetic\", got \"photo\"");
  EXPECT_EQ(errors[3], "train[1]: pair data/images/a.jpg is listed twice (also train[0])");
  EXPECT_EQ(errors[4], "test[0]: test pair data/images/a.jpg is also listed in train[0] (test must stay held out)");
  EXPECT_EQ(errors[5], "test[1].source: the test list holds real pairs only, got a synthetic pair");
}

TEST_F(ManifestTest, ChecksumMismatchIsReported) {
  Manifest m = Sample();
  WriteManifest(m, dir_ / "manifest.json");
  WriteFileAtomic(dir_ / "data/images/a.jpg", "changed");
  auto report = CheckManifestFile(dir_ / "manifest.json");
  ASSERT_EQ(report.errors.size(), 1u);
  EXPECT_EQ(report.errors[0].field_path, "train[0].sha256");
  EXPECT_NE(report.errors[0].message.find("checksum mismatch for " + (dir_ / "data/images/a.jpg").string()),
            std::string::npos);
  // Reading without verification still succeeds.
  EXPECT_NO_THROW(ReadManifest(dir_ / "manifest.json"));
  EXPECT_THROW(ReadManifest(dir_ / "manifest.json", {.verify_checksums = true}), InputError);
}

TEST_F(ManifestTest, MissingRootFolderIsAnError) {
  auto errors = Errors(R"({"version": 1, "config": "R100", "root": "nope", "train": [], "val": []})");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "root: folder not found: " + (dir_ / "nope").string());
}

TEST(ManifestPaths, RelativeToBaseWithDotDotOutside) {
  EXPECT_EQ(RelativePathForManifest("/a/b/c/x.png", "/a/b"), "c/x.png");
  EXPECT_EQ(RelativePathForManifest("/a/y/x.png", "/a/b"), "../y/x.png");
}

}  // namespace
}  // namespace asbuilt
