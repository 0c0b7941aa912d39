#include "asbuilt/cluster/slurm.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;

// scripts/slurm/*.sbatch, compiled in by cmake/embed_text.cmake.
extern const char kSynthSbatch[];
extern const char kSynthMergeSbatch[];
extern const char kEvalSbatch[];
extern const char kEvalMergeSbatch[];
extern const char kTrainSbatch[];

namespace {

struct CommandResult {
  int exit_code = -1;
  std::string out;  // stdout and stderr together.
};

CommandResult RunCommand(const std::string& command) {
  CommandResult result;
  std::FILE* pipe = ::popen((command + " 2>&1 </dev/null").c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

std::string Trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ' || text.back() == '\r')) text.pop_back();
  return text;
}

}  // namespace

void SlurmOptions::Check() const {
  CheckArgument(cpus_per_task >= 0, fmt::format("SlurmOptions.cpus_per_task = {}, must be >= 0", cpus_per_task));
  for (const std::string* value : {&partition, &time, &account, &mem}) {
    CheckArgument(value->find_first_of(" \t\n'\"\\$`") == std::string::npos,
                  fmt::format("Slurm option '{}' has a space or a quote", *value));
  }
}

std::string_view SlurmTemplate(std::string_view name) {
  if (name == "synth") return kSynthSbatch;
  if (name == "synth-merge") return kSynthMergeSbatch;
  if (name == "eval") return kEvalSbatch;
  if (name == "eval-merge") return kEvalMergeSbatch;
  if (name == "train") return kTrainSbatch;
  throw InvalidArgument(
      fmt::format("no Slurm batch script named '{}' (synth, synth-merge, eval, eval-merge, train)", name));
}

std::string ShellQuote(std::string_view text) {
  const bool plain = !text.empty() && text.find_first_not_of(
                                          "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789_./:=,+-@%") == std::string_view::npos;
  if (plain) return std::string(text);
  std::string quoted = "'";
  for (char c : text) {
    if (c == '\'') {
      quoted.append("'\\''");
    } else {
      quoted.push_back(c);
    }
  }
  quoted.push_back('\'');
  return quoted;
}

std::string MakeBatchScript(std::string_view template_text, const std::vector<std::string>& directives,
                            const std::vector<std::pair<std::string, std::string>>& variables) {
  std::istringstream in{std::string(template_text)};
  std::string line, head, body;
  bool first = true;
  while (std::getline(in, line)) {
    if (first && line.rfind("#!", 0) == 0) {
      head = line + "\n";
    } else if (line.rfind("#SBATCH", 0) != 0) {
      body += line + "\n";
    }
    first = false;
  }
  std::string script = head.empty() ? "#!/bin/bash\n" : head;
  for (const std::string& d : directives) script += "#SBATCH " + d + "\n";
  script += "# Written by asbuilt cluster from its copy of scripts/slurm/ (docs/cluster.md).\n";
  for (const auto& [name, value] : variables) script += fmt::format("export {}={}\n", name, ShellQuote(value));
  return script + body;
}

std::vector<std::string> SlurmDirectives(const SlurmOptions& options, std::string_view job_name,
                                         const fs::path& output_pattern) {
  std::vector<std::string> d = {fmt::format("--job-name={}", job_name),
                                fmt::format("--output={}", output_pattern.string())};
  if (!options.partition.empty()) d.push_back("--partition=" + options.partition);
  if (!options.time.empty()) d.push_back("--time=" + options.time);
  if (!options.account.empty()) d.push_back("--account=" + options.account);
  if (!options.mem.empty()) d.push_back("--mem=" + options.mem);
  if (options.cpus_per_task > 0) d.push_back(fmt::format("--cpus-per-task={}", options.cpus_per_task));
  return d;
}

fs::path FindProgram(std::string_view program) {
  if (program.find('/') != std::string_view::npos) {
    return ::access(std::string(program).c_str(), X_OK) == 0 ? fs::path(program) : fs::path();
  }
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

std::string SubmitBatch(const SlurmOptions& options, const std::vector<std::string>& args, const fs::path& script) {
  const fs::path sbatch = FindProgram(options.sbatch);
  if (sbatch.empty()) {
    throw Error(fmt::format(
        "{}: not found on PATH. Run this where Slurm's client is installed (Debian: apt install slurm-client; "
        "a one-node test cluster: scripts/slurm/local-cluster.sh up), or add --dry-run to print the batch "
        "scripts without submitting",
        options.sbatch));
  }
  std::vector<std::string> words = {ShellQuote(sbatch.string()), "--parsable"};
  for (const std::string& a : args) words.push_back(ShellQuote(a));
  words.push_back(ShellQuote(script.string()));
  const std::string command = fmt::format("{}", fmt::join(words, " "));
  const CommandResult r = RunCommand(command);
  std::string out = Trimmed(r.out);
  if (r.exit_code != 0 || out.empty()) {
    throw Error(fmt::format("sbatch refused {} (exit {}): {}", script.string(), r.exit_code, out));
  }
  // "123" or "123;cluster", possibly after warnings on earlier lines.
  out = out.substr(out.find_last_of('\n') == std::string::npos ? 0 : out.find_last_of('\n') + 1);
  return out.substr(0, out.find(';'));
}

std::string JobState(const SlurmOptions& options, std::string_view job_id) {
  const fs::path squeue = FindProgram(options.squeue);
  if (squeue.empty() || job_id.empty()) return "";
  const CommandResult r = RunCommand(fmt::format("{} -h -j {} -o %T", ShellQuote(squeue.string()), ShellQuote(job_id)));
  return r.exit_code == 0 ? Trimmed(r.out.substr(0, r.out.find('\n'))) : "";
}

std::map<int, std::string> ArrayTaskStates(const SlurmOptions& options, std::string_view job_id) {
  std::map<int, std::string> states;
  const fs::path squeue = FindProgram(options.squeue);
  if (squeue.empty() || job_id.empty()) return states;
  const CommandResult r =
      RunCommand(fmt::format("{} -h -r -j {} -o '%i %T'", ShellQuote(squeue.string()), ShellQuote(job_id)));
  if (r.exit_code != 0) return states;
  std::istringstream lines(r.out);
  std::string id, state;
  while (lines >> id >> state) {
    const std::size_t underscore = id.find('_');
    if (underscore == std::string::npos) continue;
    char* end = nullptr;
    const long task = std::strtol(id.c_str() + underscore + 1, &end, 10);
    if (end != id.c_str() + underscore + 1) states[static_cast<int>(task)] = state;
  }
  return states;
}

}  // namespace asbuilt
