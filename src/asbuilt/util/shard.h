#ifndef ASBUILT_UTIL_SHARD_H_
#define ASBUILT_UTIL_SHARD_H_

// One shard scheme for every job split over processes (dataset synth, eval
// seg, a Slurm array): shard i of N takes the contiguous block of items
// [count·i/N, count·(i+1)/N), so shards never overlap and their union is the
// whole run, whatever N.

#include <string>
#include <string_view>
#include <utility>

namespace asbuilt {

struct Shard {
  int index = 0;  // 0-based.
  int count = 1;

  // Throws InvalidArgument unless 1 ≤ count and 0 ≤ index < count.
  void Check() const;
  std::string ToString() const;  // "i/N"
  bool operator==(const Shard&) const = default;
};

// "i/N" (0-based), e.g. "0/4". Throws InvalidArgument naming `flag` and the text.
Shard ParseShard(std::string_view text, std::string_view flag = "--shard");

// The items [begin, end) of shard `shard_index` of `shard_count` over `count`.
std::pair<int, int> ShardRange(int count, int shard_index, int shard_count);
inline std::pair<int, int> ShardRange(int count, const Shard& shard) {
  return ShardRange(count, shard.index, shard.count);
}

// Throws InvalidArgument when N shards over `count` items would leave a shard
// empty (N > count), naming both.
void CheckShardCount(int shard_count, int count);

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_SHARD_H_
