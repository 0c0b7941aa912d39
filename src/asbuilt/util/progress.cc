#include "asbuilt/util/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdlib>

#include <fmt/format.h>

namespace asbuilt {

bool StderrIsTerminal() { return ::isatty(STDERR_FILENO) != 0 && std::getenv("ASBUILT_NO_PROGRESS") == nullptr; }

ProgressPrinter::ProgressPrinter(std::FILE* out)
    : ProgressPrinter(out, out == stderr && StderrIsTerminal(), std::chrono::seconds(5)) {}

ProgressPrinter::ProgressPrinter(std::FILE* out, bool is_terminal, std::chrono::milliseconds interval)
    : out_(out), is_terminal_(is_terminal), interval_(interval) {}

ProgressPrinter::~ProgressPrinter() { Finish(); }

std::string ProgressPrinter::FormatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  long s = std::lround(seconds);
  if (s < 60) return fmt::format("{}s", s);
  if (s < 3600) return fmt::format("{}m{:02}s", s / 60, s % 60);
  return fmt::format("{}h{:02}m", s / 3600, (s % 3600) / 60);
}

void ProgressPrinter::Update(const ProgressUpdate& update) {
  Clock::time_point now = Clock::now();
  if (update.stage != stage_) {
    Finish();
    stage_ = std::string(update.stage);
    stage_start_ = now;
    last_print_ = Clock::time_point{};
  }
  bool finished = update.total > 0 && update.done >= update.total;
  double elapsed = std::chrono::duration<double>(now - stage_start_).count();
  std::string eta;
  if (update.total > 0 && update.done > 0 && !finished) {
    double remaining = elapsed * double(update.total - update.done) / double(update.done);
    eta = " ETA " + FormatDuration(remaining);
  } else if (finished) {
    eta = " in " + FormatDuration(elapsed);
  }
  std::string detail = update.detail.empty() ? "" : fmt::format("  {}", update.detail);

  if (is_terminal_) {
    if (now - last_print_ < std::chrono::milliseconds(100) && !finished) return;
    last_print_ = now;
    std::string bar;
    if (update.total > 0) {
      constexpr int kWidth = 28;
      double f = std::min(1.0, double(update.done) / double(update.total));
      int filled = static_cast<int>(f * kWidth);
      bar = fmt::format("[{}{}] {}/{}", std::string(filled, '#'), std::string(kWidth - filled, '.'), update.done,
                        update.total);
    } else {
      bar = fmt::format("{}", update.done);
    }
    fmt::print(out_, "\r\033[K{} {}{}{}", stage_, bar, eta, detail);
    line_open_ = true;
    if (finished) Finish();
    std::fflush(out_);
    return;
  }
  if (!finished && last_print_ != Clock::time_point{} && now - last_print_ < interval_) {
    return;
  }
  last_print_ = now;
  if (update.total > 0) {
    fmt::print(out_, "{}: {}/{} ({:.0f}%){}{}\n", stage_, update.done, update.total,
               100.0 * double(update.done) / double(update.total), eta, detail);
  } else {
    fmt::print(out_, "{}: {}{}\n", stage_, update.done, detail);
  }
  std::fflush(out_);
}

void ProgressPrinter::Finish() {
  if (line_open_) {
    fmt::print(out_, "\n");
    std::fflush(out_);
    line_open_ = false;
  }
}

ProgressCallback ProgressPrinter::Callback() {
  return [this](const ProgressUpdate& u) { Update(u); };
}

}  // namespace asbuilt
