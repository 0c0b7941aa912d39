// How fast `asbuilt mcp` is ready: spawn the server, send `initialize`, time
// until its reply arrives (then `tools/list`), median of N runs; compared
// with spawning `asbuilt version` to exit (the process start-up floor: the
// dynamic loader, OpenCV/Embree/TBB libraries). Target: well under a second
// (issue 3). LibTorch is a plugin loaded on first use (seg/torch_plugin.h);
// "before" = the same binary with LibTorch's libraries preloaded
// (LD_PRELOAD), i.e. what start-up cost while the binary linked LibTorch.
// Each session also checks /proc/PID/maps: no libtorch after tools/list.
//
//   bench_mcp [results.md]

#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
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

Child Spawn(const std::vector<std::string>& args, const std::vector<std::string>& extra_env = {}) {
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
  std::vector<char*> envp;
  for (char** e = environ; *e; ++e) envp.push_back(*e);
  for (const std::string& e : extra_env) envp.push_back(const_cast<char*>(e.c_str()));
  envp.push_back(nullptr);
  Child c;
  if (posix_spawn(&c.pid, argv[0], &actions, nullptr, argv.data(), envp.data()) != 0) {
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

// Waits for the child; returns its exit code and adds its CPU seconds.
int Wait(pid_t pid, double* cpu_s = nullptr) {
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  if (cpu_s) {
    *cpu_s =
        usage.ru_utime.tv_sec + usage.ru_utime.tv_usec * 1e-6 + usage.ru_stime.tv_sec + usage.ru_stime.tv_usec * 1e-6;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Session {
  std::vector<double> init_s, list_s, exit_s, cpu_s;
  std::size_t tool_count = 0, list_bytes = 0;
  int torch_mapped = 0;  // Sessions with libtorch mapped after tools/list.
};

// Shared objects mapped into process `pid` ("self" for this one) whose file
// name contains `needle`.
std::set<std::string> MappedLibraries(const std::string& pid, const std::string& needle) {
  std::set<std::string> out;
  std::ifstream maps("/proc/" + pid + "/maps");
  std::string line;
  while (std::getline(maps, line)) {
    auto slash = line.find('/');
    if (slash == std::string::npos) continue;
    std::string path = line.substr(slash);
    if (fs::path(path).filename().string().find(needle) != std::string::npos) out.insert(path);
  }
  return out;
}

const std::string kInit = R"({"jsonrpc":"2.0","id":1,"method":"initialize","params":{"protocolVersion":"2025-06-18",)"
                          R"("capabilities":{},"clientInfo":{"name":"bench","version":"1"}}})"
                          "\n";
const std::string kList = R"({"jsonrpc":"2.0","method":"notifications/initialized"})"
                          "\n"
                          R"({"jsonrpc":"2.0","id":2,"method":"tools/list"})"
                          "\n";

// One MCP session: spawn, initialize, tools/list, close stdin, wait.
void RunSession(const std::vector<std::string>& args, Session& s, const std::vector<std::string>& extra_env = {}) {
  auto start = Clock::now();
  Child c = Spawn(args, extra_env);
  std::string buffer;
  WriteAll(c.in, kInit);
  std::string reply = ReadLine(c.out, buffer);
  auto t_init = Clock::now();
  if (reply.find("\"protocolVersion\"") == std::string::npos) {
    throw std::runtime_error("unexpected initialize reply: " + reply.substr(0, 200));
  }
  WriteAll(c.in, kList);
  std::string tools = ReadLine(c.out, buffer);
  auto t_list = Clock::now();
  s.list_bytes = tools.size();
  s.tool_count = 0;
  for (auto p = tools.find("\"inputSchema\""); p != std::string::npos; p = tools.find("\"inputSchema\"", p + 1)) {
    ++s.tool_count;
  }
  if (!MappedLibraries(std::to_string(c.pid), "libtorch").empty()) ++s.torch_mapped;
  ::close(c.in);  // Shutdown: the client closes the server's stdin.
  double cpu = 0;
  int code = Wait(c.pid, &cpu);
  auto t_end = Clock::now();
  ::close(c.out);
  if (code != 0) throw std::runtime_error(fmt::format("server exited with {}", code));
  s.init_s.push_back(std::chrono::duration<double>(t_init - start).count());
  s.list_s.push_back(std::chrono::duration<double>(t_list - start).count());
  s.exit_s.push_back(std::chrono::duration<double>(t_end - start).count());
  s.cpu_s.push_back(cpu);
}

double LoadAverage() {
  double load = -1;
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = -1;
    std::fclose(f);
  }
  return load;
}

}  // namespace

int main(int argc, char** argv) try {
  const std::string cli = ASBUILT_CLI;
  const std::string lean = ASBUILT_LEAN_SERVER;
  const std::string plugin = ASBUILT_TORCH_PLUGIN_PATH;
  const int runs = 21;
  const fs::path workspace = fs::temp_directory_path() / fmt::format("asbuilt_bench_mcp_{}", ::getpid());

  // LibTorch's libraries, as the plugin maps them: loaded here once (this
  // process only) to learn the paths, then preloaded into the "before" runs.
  const std::set<std::string> mapped_before_dlopen = MappedLibraries("self", "libtorch");
  if (::dlopen(plugin.c_str(), RTLD_NOW | RTLD_LOCAL) == nullptr) {
    throw std::runtime_error(fmt::format("cannot load {}: {}", plugin, ::dlerror()));
  }
  std::set<std::string> torch_libs = MappedLibraries("self", "libtorch");
  for (const std::string& c10 : MappedLibraries("self", "libc10")) torch_libs.insert(c10);
  if (torch_libs.empty() || !mapped_before_dlopen.empty()) {
    throw std::runtime_error("the plugin did not map libtorch (or this bench already had it)");
  }
  std::string preload;
  for (const std::string& lib : torch_libs) preload += (preload.empty() ? "" : ":") + lib;
  const std::vector<std::string> before_env = {"LD_PRELOAD=" + preload};

  const double load_before = LoadAverage();
  Session full, before, lean_session;
  std::vector<double> version_s, version_cpu_s;
  const std::vector<std::string> mcp_args = {cli, "mcp", "--workspace", workspace.string(), "--quiet"};
  for (int i = 0; i < runs; ++i) {
    RunSession(mcp_args, full);
    RunSession(mcp_args, before, before_env);
    RunSession({lean, "--workspace", workspace.string()}, lean_session);
    auto start = Clock::now();
    Child v = Spawn({cli, "version"});
    ::close(v.in);
    double cpu = 0;
    Wait(v.pid, &cpu);
    ::close(v.out);
    version_s.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    version_cpu_s.push_back(cpu);
  }
  fs::remove_all(workspace);
  const double load_after = LoadAverage();

  using asbuilt::bench::Median;
  auto ms = [](const std::vector<double>& v) { return Median(v) * 1e3; };
  const double version_ms = ms(version_s);
  auto row = [&](std::string_view what, const Session& s) {
    return fmt::format("| {} | {:.0f} ms | {:.0f} ms | {:.0f} ms | {:.0f} ms | {:.2f}× | {} of {} |\n", what,
                       ms(s.init_s), ms(s.list_s), ms(s.exit_s), ms(s.cpu_s), ms(s.init_s) / version_ms, s.torch_mapped,
                       s.init_s.size());
  };
  const double init_ms = ms(full.init_s), before_ms = ms(before.init_s);
  std::string md = fmt::format(
      "## mcp — `asbuilt mcp` start-up\n\n"
      "Spawn the server, send `initialize` and time to its reply; then `tools/list` ({} tools, "
      "{} bytes of JSON); then close stdin and wait for a clean exit. CPU = the server process's "
      "user + system time for the whole session. LibTorch is a plugin (`libasbuilt_torch.so`, "
      "seg/torch_plugin.h) that `asbuilt` loads only when a command segments or trains; "
      "\"before\" = the same binary with LibTorch's libraries ({} files) preloaded with "
      "`LD_PRELOAD`, which is what every start-up cost while the binary linked LibTorch. "
      "\"libtorch mapped\" = sessions whose /proc/PID/maps listed libtorch after `tools/list`. "
      "Reference: `asbuilt version` (spawn → exit: the binary's start-up alone). \"Lean server\" "
      "= the MCP library in a binary of its own (bench/mcp/lean_server.cc). Median of {} runs "
      "each, interleaved; load average {:.1f} → {:.1f} on {} cores during the run (wall times "
      "grow with load; CPU times do not).\n\n"
      "| program | → `initialize` reply | → `tools/list` reply | → exit | CPU | init vs "
      "`asbuilt version` | libtorch mapped |\n|---|---|---|---|---|---|---|\n"
      "{}{}{}| `asbuilt version` | — | — | {:.0f} ms | {:.0f} ms | 1.00× | — |\n\n"
      "Verdict: {}\n",
      full.tool_count, full.list_bytes, torch_libs.size(), runs, load_before, load_after,
      std::thread::hardware_concurrency(), row("`asbuilt mcp`", full),
      row("`asbuilt mcp` before (LibTorch loaded at start)", before), row("lean server", lean_session), version_ms,
      ms(version_cpu_s),
      fmt::format("`asbuilt mcp` answers `initialize` in {:.0f} ms ({}), {:.1f}× faster than "
                  "with LibTorch loaded at start-up ({:.0f} ms, CPU {:.0f} → {:.0f} ms); "
                  "libtorch was mapped in {} of {} sessions.",
                  init_ms, init_ms < 1000 ? "under a second" : "NOT under a second on this loaded machine",
                  before_ms / init_ms, before_ms, ms(before.cpu_s), ms(full.cpu_s), full.torch_mapped, runs));
  asbuilt::bench::WriteSection(asbuilt::bench::ResultsPath(argc, argv, "mcp"), md);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "bench_mcp: %s\n", e.what());
  return 1;
}
