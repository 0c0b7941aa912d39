#include "asbuilt/util/file.h"

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path TempDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("asbuilt_util_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(WriteFileAtomic, WritesContentsAndCreatesFolders) {
  fs::path dir = TempDir("write");
  WriteFileAtomic(dir / "a" / "b.txt", "hello");
  EXPECT_EQ(ReadFile(dir / "a" / "b.txt"), "hello");
  // No temp files remain.
  int entries = 0;
  for ([[maybe_unused]] auto& e : fs::directory_iterator(dir / "a")) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST(AtomicFile, UncommittedLeavesNothingAndKeepsOldFile) {
  fs::path dir = TempDir("uncommitted");
  WriteFileAtomic(dir / "out.json", "old");
  {
    AtomicFile f(dir / "out.json");
    EXPECT_EQ(f.temp_path().extension(), ".json");
    EXPECT_TRUE(IsAtomicTempName(f.temp_path()));
    WriteFileAtomic(f.temp_path(), "half");  // Simulates a partial write.
  }                                          // Destroyed without Commit().
  EXPECT_EQ(ReadFile(dir / "out.json"), "old");
  int entries = 0;
  for ([[maybe_unused]] auto& e : fs::directory_iterator(dir)) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST(AtomicFile, CommitWithoutDataThrows) {
  fs::path dir = TempDir("nodata");
  AtomicFile f(dir / "x.png");
  EXPECT_THROW(f.Commit(), Error);
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

TEST(RemoveDeadAtomicTemps, RemovesOnlyTempsOfProcessesThatAreGone) {
  fs::path dir = TempDir("dead_temps");
  // A pid that is certainly gone: a child that has exited and been reaped.
  pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ASSERT_GT(dead, 0);
  ::waitpid(dead, nullptr, 0);
  const std::string dead_name = ".last.tmp-" + std::to_string(dead) + "-0.pt";
  const std::string live_name = ".last.tmp-" + std::to_string(::getppid()) + "-3.pt";  // A live writer.
  for (const std::string& name : {dead_name, live_name, std::string("last.pt"), std::string(".hidden")}) {
    WriteFileAtomic(dir / name, "x");
  }
  EXPECT_EQ(RemoveDeadAtomicTemps(dir), 1);
  EXPECT_FALSE(fs::exists(dir / dead_name));
  EXPECT_TRUE(fs::exists(dir / live_name));
  EXPECT_TRUE(fs::exists(dir / "last.pt"));
  EXPECT_TRUE(fs::exists(dir / ".hidden"));
  EXPECT_EQ(RemoveDeadAtomicTemps(dir / "missing"), 0);
}

TEST(ReadFile, MissingFileNamesTheFile) {
  try {
    ReadFile("/nonexistent/asbuilt.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/asbuilt.json: cannot read: No such file or directory");
  }
}

}  // namespace
}  // namespace asbuilt
