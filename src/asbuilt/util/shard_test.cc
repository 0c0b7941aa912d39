#include "asbuilt/util/shard.h"

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

TEST(ShardRange, ShardsTileTheItemsWithoutOverlap) {
  for (int shards : {1, 3, 7}) {
    int next = 0;
    for (int k = 0; k < shards; ++k) {
      auto [b, e] = ShardRange(20, k, shards);
      EXPECT_EQ(b, next);
      EXPECT_GE(e, b);
      next = e;
    }
    EXPECT_EQ(next, 20);
  }
}

TEST(ParseShard, ReadsIOverNAndNamesTheFlagOnBadText) {
  EXPECT_EQ(ParseShard("2/5"), (Shard{2, 5}));
  EXPECT_EQ(ParseShard("0/1").ToString(), "0/1");
  for (const char* bad : {"", "3", "a/b", "1/0", "4/4", "-1/4", "1/4x"}) {
    try {
      ParseShard(bad, "--shard");
      FAIL() << bad;
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find("--shard"), std::string::npos) << e.what();
    }
  }
}

TEST(CheckShardCount, RefusesMoreShardsThanItems) {
  EXPECT_NO_THROW(CheckShardCount(4, 4));
  EXPECT_THROW(CheckShardCount(5, 4), InvalidArgument);
  EXPECT_THROW(CheckShardCount(0, 4), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
