#include "asbuilt/dataset/pairs.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path PairsTestDir() {
  fs::path dir = fs::temp_directory_path() /
                 ("asbuilt_pairs_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  return dir;
}

TEST(ListPairs, MatchesByStemAndReportsOrphans) {
  fs::path dir = PairsTestDir();
  for (const char* f : {"images/a.jpg", "images/b.PNG", "images/c.jpg", "images/notes.txt", "labels/a.png",
                        "labels/b.png", "labels/d.png", "labels/.hidden.png"}) {
    WriteFileAtomic(dir / f, "x");
  }
  PairListing l = ListPairs(dir / "images", dir / "labels");
  ASSERT_EQ(l.pairs.size(), 2u);
  EXPECT_EQ(l.pairs[0].name, "a");
  EXPECT_EQ(l.pairs[0].image, dir / "images/a.jpg");
  EXPECT_EQ(l.pairs[0].label, dir / "labels/a.png");
  EXPECT_EQ(l.pairs[1].image, dir / "images/b.PNG");
  ASSERT_EQ(l.images_without_label.size(), 1u);
  EXPECT_EQ(l.images_without_label[0], dir / "images/c.jpg");
  ASSERT_EQ(l.labels_without_image.size(), 1u);
  EXPECT_EQ(l.labels_without_image[0], dir / "labels/d.png");
  EXPECT_EQ(l.ToString(), "2 pairs (1 image without label, 1 label without image)");
}

TEST(ListPairs, DuplicateStemNamesBothFiles) {
  fs::path dir = PairsTestDir();
  for (const char* f : {"images/a.jpg", "images/a.png", "labels/a.png"}) WriteFileAtomic(dir / f, "x");
  try {
    ListPairs(dir / "images", dir / "labels");
    FAIL();
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("two files share the stem 'a'"), std::string::npos) << msg;
  }
}

TEST(ListPairs, MissingFolderIsNamed) {
  fs::path dir = PairsTestDir();
  WriteFileAtomic(dir / "labels/a.png", "x");
  try {
    ListPairs(dir / "images", dir / "labels");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "images").string() + ": not a folder");
  }
}

TEST(ListDatasetPairs, FindsNestedCaptureFolders) {
  fs::path dir = PairsTestDir();
  for (const char* f : {"room1/left/000.png", "room1/labels/000.png", "room1/right/000.png", "room2/left/000.png",
                        "room2/labels/000.png", "room2/left/001.png", "room2/labels/001.png"}) {
    WriteFileAtomic(dir / f, "x");
  }
  PairListing l = ListDatasetPairs(dir);
  ASSERT_EQ(l.pairs.size(), 3u);
  EXPECT_EQ(l.pairs[0].name, "room1/000");
  EXPECT_EQ(l.pairs[2].name, "room2/001");
  EXPECT_EQ(l.pairs[2].label, dir / "room2/labels/001.png");
}

TEST(ListDatasetPairs, EmptyFolderIsAnError) {
  fs::path dir = PairsTestDir();
  fs::create_directories(dir / "x");
  EXPECT_THROW(ListDatasetPairs(dir), InputError);
}

TEST(ListDatasetPairs, ReadsTheBlenderRooms) {
  fs::path rooms = fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public";
  if (!fs::exists(rooms)) GTEST_SKIP() << "shared data not present";
  PairListing l = ListDatasetPairs(rooms);
  EXPECT_EQ(l.pairs.size(), 24u);
  EXPECT_EQ(l.pairs[0].name, "p01_rect_1door_2win/000");
}

}  // namespace
}  // namespace asbuilt
