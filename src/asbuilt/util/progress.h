#ifndef ASBUILT_UTIL_PROGRESS_H_
#define ASBUILT_UTIL_PROGRESS_H_

// Progress of long operations (STYLE.md 8): the library calls a callback; the
// CLI draws a bar (ProgressPrinter), the MCP server sends notifications.

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <string_view>

namespace asbuilt {

struct ProgressUpdate {
  std::string_view stage;   // "render", "train epoch 3", …
  std::int64_t done = 0;    // Units finished so far.
  std::int64_t total = 0;   // 0 when unknown.
  std::string_view detail;  // Optional: "loss 0.231".
};

using ProgressCallback = std::function<void(const ProgressUpdate&)>;

// Calls `callback` if set.
inline void ReportProgress(const ProgressCallback& callback, const ProgressUpdate& update) {
  if (callback) callback(update);
}

// Draws progress on a stream (stderr by default). On a terminal: one bar line
// redrawn in place, with rate and ETA. Otherwise: a plain line at most every
// `interval` and at the end of each stage, so CI logs stay readable.
class ProgressPrinter {
 public:
  explicit ProgressPrinter(std::FILE* out = stderr);
  ProgressPrinter(std::FILE* out, bool is_terminal, std::chrono::milliseconds interval);
  ~ProgressPrinter();

  void Update(const ProgressUpdate& update);
  // Ends the current bar line (if any).
  void Finish();
  // A callback that forwards to Update(); the printer must outlive it.
  ProgressCallback Callback();

  // Formats "1m05s"-style durations (exposed for tests).
  static std::string FormatDuration(double seconds);

 private:
  using Clock = std::chrono::steady_clock;
  std::FILE* out_;
  bool is_terminal_;
  std::chrono::milliseconds interval_;
  std::string stage_;
  Clock::time_point stage_start_;
  Clock::time_point last_print_;
  bool line_open_ = false;
};

// True if progress bars should be drawn on stderr (a terminal, and not
// disabled with ASBUILT_NO_PROGRESS).
bool StderrIsTerminal();

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_PROGRESS_H_
