#include "asbuilt/util/shard.h"

#include <cstdint>
#include <cstdio>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {

void Shard::Check() const {
  CheckArgument(count >= 1, fmt::format("shard count = {}, must be >= 1", count));
  CheckArgument(index >= 0 && index < count, fmt::format("shard index = {}, must be in [0, {})", index, count));
}

std::string Shard::ToString() const { return fmt::format("{}/{}", index, count); }

Shard ParseShard(std::string_view text, std::string_view flag) {
  Shard shard;
  const std::string s(text);
  char tail = 0;
  if (std::sscanf(s.c_str(), "%d/%d%c", &shard.index, &shard.count, &tail) != 2) {
    throw InvalidArgument(fmt::format("{}: '{}' is not i/N (e.g. 0/4)", flag, s));
  }
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count) {
    throw InvalidArgument(fmt::format("{}: '{}' needs N >= 1 and 0 <= i < N", flag, s));
  }
  return shard;
}

std::pair<int, int> ShardRange(int count, int shard_index, int shard_count) {
  auto at = [&](int k) { return static_cast<int>(static_cast<std::int64_t>(count) * k / shard_count); };
  return {at(shard_index), at(shard_index + 1)};
}

void CheckShardCount(int shard_count, int count) {
  CheckArgument(shard_count >= 1, fmt::format("{} shards: need at least 1", shard_count));
  CheckArgument(shard_count <= count, fmt::format("{} shards over {} items: at most one shard per item ({} here)",
                                                  shard_count, count, count));
}

}  // namespace asbuilt
