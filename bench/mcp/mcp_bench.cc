// How fast `asbuilt mcp` is ready: spawn the server, send `initialize`, time
// until its reply arrives (then `tools/list`), median of N runs; compared
// with spawning `asbuilt version` to exit (the process start-up floor: the
// dynamic loader, OpenCV/Embree/TBB/LibTorch libraries). Target: well under
// a second (issue 3).
//
//   bench_mcp [results.md]

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bench/bench_util.h"

extern char** environ;

namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Child {
  pid_t pid = -1;
  int in = -1;   // Its stdin (we write).
  int out = -1;  // Its stdout (we read).
};

Child Spawn(const std::vector<std::string>& args) {
  int to_child[2], from_child[2];
  if (::pipe(to_child) != 0 || ::pipe(from_child) != 0) throw std::runtime_error("pipe failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, to_child[0], 0);
  posix_spawn_file_actions_adddup2(&actions, from_child[1], 1);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addclose(&actions, to_child[1]);
  posix_spawn_file_actions_addclose(&actions, from_child[0]);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  Child c;
  if (posix_spawn(&c.pid, argv[0], &actions, nullptr, argv.data(), environ) != 0) {
    throw std::runtime_error("cannot spawn " + args[0]);
  }
  posix_spawn_file_actions_destroy(&actions);
  ::close(to_child[0]);
  ::close(from_child[1]);
  c.in = to_child[1];
  c.out = from_child[0];
  return c;
}

// Reads until a full line arrives (5 s timeout).
std::string ReadLine(int fd, std::string& buffer) {
  auto deadline = Clock::now() + std::chrono::seconds(5);
  while (true) {
    auto nl = buffer.find('\n');
    if (nl != std::string::npos) {
      std::string line = buffer.substr(0, nl);
      buffer.erase(0, nl + 1);
      return line;
    }
    pollfd p{fd, POLLIN, 0};
    int ms = static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count());
    if (ms <= 0 || ::poll(&p, 1, ms) <= 0) throw std::runtime_error("no reply within 5 s");
    char chunk[65536];
    ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n <= 0) throw std::runtime_error("server closed its output");
    buffer.append(chunk, n);
  }
}

void WriteAll(int fd, const std::string& s) {
  if (::write(fd, s.data(), s.size()) != static_cast<ssize_t>(s.size())) {
    throw std::runtime_error("write failed");
  }
}

int Wait(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string cli = ASBUILT_CLI;
  const int runs = 21;
  const fs::path workspace = fs::temp_directory_path() / fmt::format("asbuilt_bench_mcp_{}", ::getpid());
  const std::string init =
      R"({"jsonrpc":"2.0","id":1,"method":"initialize","params":{"protocolVersion":"2025-06-18",)"
      R"("capabilities":{},"clientInfo":{"name":"bench","version":"1"}}})" "\n";
  const std::string list = R"({"jsonrpc":"2.0","id":2,"method":"tools/list"})" "\n";

  std::vector<double> to_init, to_list, session, version;
  std::size_t list_bytes = 0, tool_count = 0;
  for (int i = 0; i < runs; ++i) {
    auto start = Clock::now();
    Child c = Spawn({cli, "mcp", "--workspace", workspace.string(), "--quiet"});
    std::string buffer;
    WriteAll(c.in, init);
    std::string reply = ReadLine(c.out, buffer);
    auto t_init = Clock::now();
    if (reply.find("\"protocolVersion\"") == std::string::npos) {
      std::fprintf(stderr, "bench_mcp: unexpected reply: %s\n", reply.c_str());
      return 1;
    }
    WriteAll(c.in, R"({"jsonrpc":"2.0","method":"notifications/initialized"})" "\n" + list);
    std::string tools = ReadLine(c.out, buffer);
    auto t_list = Clock::now();
    list_bytes = tools.size();
    tool_count = 0;
    for (auto p = tools.find("\"inputSchema\""); p != std::string::npos; p = tools.find("\"inputSchema\"", p + 1)) {
      ++tool_count;
    }
    ::close(c.in);  // Shutdown: the client closes the server's stdin.
    int code = Wait(c.pid);
    auto t_end = Clock::now();
    ::close(c.out);
    if (code != 0) {
      std::fprintf(stderr, "bench_mcp: server exited with %d\n", code);
      return 1;
    }
    to_init.push_back(std::chrono::duration<double>(t_init - start).count());
    to_list.push_back(std::chrono::duration<double>(t_list - start).count());
    session.push_back(std::chrono::duration<double>(t_end - start).count());

    start = Clock::now();
    Child v = Spawn({cli, "version"});
    ::close(v.in);
    Wait(v.pid);
    ::close(v.out);
    version.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  fs::remove_all(workspace);

  using asbuilt::bench::Median;
  const double init_ms = Median(to_init) * 1e3, version_ms = Median(version) * 1e3;
  std::string md = fmt::format(
      "## mcp — `asbuilt mcp` start-up\n\n"
      "Spawn `asbuilt mcp --workspace TMP`, send `initialize`, time to its reply (then "
      "`tools/list`, then close stdin and wait for exit); reference: spawn `asbuilt version` to "
      "exit. Median of {} runs each, interleaved. Target: `initialize` answered well under 1 s.\n\n"
      "| measure | median | vs `asbuilt version` |\n|---|---|---|\n"
      "| spawn → `initialize` reply | {:.1f} ms | {:.2f}× |\n"
      "| spawn → `tools/list` reply ({} tools JSON, {} bytes) | {:.1f} ms | {:.2f}× |\n"
      "| spawn → clean exit after stdin closes | {:.1f} ms | {:.2f}× |\n"
      "| `asbuilt version` (spawn → exit) | {:.1f} ms | 1.00× |\n\n"
      "Verdict: {}.\n",
      runs, init_ms, init_ms / version_ms, tool_count, list_bytes, Median(to_list) * 1e3,
      Median(to_list) * 1e3 / version_ms, Median(session) * 1e3, Median(session) * 1e3 / version_ms,
      version_ms,
      init_ms < 1000 ? fmt::format("initialize answered in {:.0f} ms — well under a second; almost "
                                   "all of it is process start-up shared with `asbuilt version`",
                                   init_ms)
                     : "initialize is NOT answered within a second");
  asbuilt::bench::WriteSection(asbuilt::bench::ResultsPath(argc, argv, "mcp"), md);
  return 0;
}
