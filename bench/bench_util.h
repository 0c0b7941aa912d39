#ifndef ASBUILT_BENCH_BENCH_UTIL_H_
#define ASBUILT_BENCH_BENCH_UTIL_H_

// Small helpers shared by the benchmark programs: repeated timing with
// medians, peak RSS, and the Markdown section each program writes.

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include "asbuilt/util/file.h"

namespace asbuilt::bench {

// Runs `fn` `repeats` times and returns the median wall time in seconds.
inline double MedianSeconds(int repeats, const std::function<void()>& fn) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    auto start = std::chrono::steady_clock::now();
    fn();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

inline double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Peak resident set size of this process so far, MiB.
inline double PeakRssMiB() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

// A positive integer from the environment, or `fallback` when it is unset
// or not a positive integer.
inline int EnvPositiveInt(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && std::atoi(v) > 0 ? std::atoi(v) : fallback;
}

// Where a program writes its section: argv[1] if given, else
// bench/results/<name>.md under the source tree.
inline std::string ResultsPath(int argc, char** argv, const std::string& name) {
  if (argc > 1) return argv[1];
  return std::string(ASBUILT_SOURCE_DIR) + "/bench/results/" + name + ".md";
}

// The 1-minute load average (NaN when the system does not say).
inline double LoadAverage1() {
  double load[1] = {0};
  return ::getloadavg(load, 1) == 1 ? load[0] : NAN;
}

// Today's date, YYYY-MM-DD (local time), for "measured on" lines.
inline std::string Today() {
  const std::time_t now = std::time(nullptr);
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", std::localtime(&now));
  return buf;
}

inline void WriteSection(const std::string& path, const std::string& markdown) {
  WriteFileAtomic(path, markdown);
  std::fputs(markdown.c_str(), stdout);
}

}  // namespace asbuilt::bench

#endif  // ASBUILT_BENCH_BENCH_UTIL_H_
