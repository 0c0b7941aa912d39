#ifndef ASBUILT_UTIL_HASH_H_
#define ASBUILT_UTIL_HASH_H_

// SplitMix64 (Steele, Lea and Flood 2014): a 64-bit mixer for seeding and
// per-pixel hashing, so that random draws depend on a key, not on thread
// order.

#include <cstdint>

namespace asbuilt {

inline std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_HASH_H_
