#ifndef ASBUILT_CLI_CLI_TEST_UTIL_H_
#define ASBUILT_CLI_CLI_TEST_UTIL_H_

// For CLI tests (`cli/*_command_test.cc`): runs the real `asbuilt` binary.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace asbuilt::testing_util {

struct RunResult {
  int exit_code = -1;
  std::string out;  // stdout and stderr together.
};

// Runs `asbuilt <args>` through the shell (quote arguments yourself). With
// timeout_s > 0 the run is killed after that long (exit_code 137). A run
// ended by signal n gives exit_code 128 + n, as the shell reports it.
inline RunResult RunAsbuilt(const std::string& args, int timeout_s = 0) {
  std::string cmd = (timeout_s > 0 ? "timeout -s KILL " + std::to_string(timeout_s) + " " : std::string()) +
                    std::string(ASBUILT_CLI) + " " + args + " 2>&1 </dev/null";
  RunResult r;
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

// ../shared/data (the tests' real third-party data).
inline const std::filesystem::path kData = ASBUILT_SHARED_DATA_DIR;

// An empty folder for the running test: <tmp>/<prefix><test name>.
inline std::filesystem::path FreshTestDir(const std::string& prefix) {
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              (prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace asbuilt::testing_util

#endif  // ASBUILT_CLI_CLI_TEST_UTIL_H_
