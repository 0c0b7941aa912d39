#include "asbuilt/dataset/checksum.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

TEST(Sha256, MatchesKnownVectors) {
  // FIPS 180-2 test vectors (also what `printf abc | sha256sum` prints).
  EXPECT_EQ(Sha256OfBytes(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256OfBytes("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST(Sha256, FileEqualsBytes) {
  fs::path p = fs::temp_directory_path() / "asbuilt_sha256_test/file.bin";
  std::string data(200000, 'x');
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<char>(i * 31 % 251);
  WriteFileAtomic(p, data);
  EXPECT_EQ(Sha256OfFile(p), Sha256OfBytes(data));
}

TEST(Sha256, MissingFileNamesIt) {
  try {
    Sha256OfFile("/nonexistent/x.png");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/x.png: cannot read: No such file or directory");
  }
}

TEST(Sha256, RecognisesHex) {
  EXPECT_TRUE(IsSha256Hex(Sha256OfBytes("abc")));
  EXPECT_FALSE(IsSha256Hex("abc"));
  EXPECT_FALSE(IsSha256Hex(std::string(64, 'G')));
  EXPECT_FALSE(IsSha256Hex(std::string(64, 'A')));
}

}  // namespace
}  // namespace asbuilt
