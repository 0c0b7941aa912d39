#include "asbuilt/seg/distributed.h"

#include <charconv>
#include <cstdlib>
#include <limits>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

// `text` as a whole decimal integer in [min, max]; throws naming `variable`.
long long ParseInteger(const std::string& variable, const std::string& text, long long min, long long max) {
  long long value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  CheckArgument(ec == std::errc() && ptr == end && !text.empty(),
                fmt::format("{} = '{}': not an integer", variable, text));
  CheckArgument(value >= min && value <= max, fmt::format("{} = {}: must be in [{}, {}]", variable, value, min, max));
  return value;
}

// The variable `preferred` when set, else `fallback`: (name, value), or nullopt.
std::optional<std::pair<std::string, std::string>> First(const EnvironmentLookup& env, const std::string& preferred,
                                                         const std::string& fallback) {
  for (const std::string& name : {preferred, fallback}) {
    if (name.empty()) continue;
    if (std::optional<std::string> v = env(name)) return std::make_pair(name, *v);
  }
  return std::nullopt;
}

// The Slurm port of a step (see the header): steps 0-9 of a job differ, as do
// jobs whose ids differ mod 2000.
int SlurmPort(const EnvironmentLookup& env) {
  const std::optional<std::string> job = env("SLURM_JOB_ID");
  CheckArgument(job.has_value(),
                "--distributed: no rendezvous port: set MASTER_PORT, or run under srun (SLURM_JOB_ID)");
  const long long job_id = ParseInteger("SLURM_JOB_ID", *job, 0, std::numeric_limits<long long>::max());
  long long step_id = 0;
  if (std::optional<std::string> step = env("SLURM_STEP_ID")) {
    step_id = ParseInteger("SLURM_STEP_ID", *step, 0, std::numeric_limits<long long>::max());
  }
  return static_cast<int>(20000 + (job_id % 2000) * 10 + step_id % 10);
}

}  // namespace

void DistributedOptions::Check() const {
  CheckArgument(world_size >= 1, fmt::format("DistributedOptions.world_size = {}, must be >= 1", world_size));
  CheckArgument(rank >= 0 && rank < world_size,
                fmt::format("DistributedOptions.rank = {}, must be in [0, {}]", rank, world_size - 1));
  CheckArgument(timeout_s > 0, fmt::format("DistributedOptions.timeout_s = {}, must be > 0", timeout_s));
  if (!enabled()) return;
  CheckArgument(!master_addr.empty(), "DistributedOptions.master_addr is empty: name the rendezvous host");
  CheckArgument(master_port >= 1 && master_port <= 65535,
                fmt::format("DistributedOptions.master_port = {}, must be in [1, 65535]", master_port));
}

nlohmann::json DistributedOptions::ToJson() const {
  return {{"rank", rank},
          {"world_size", world_size},
          {"master_addr", master_addr},
          {"master_port", master_port},
          {"timeout_s", timeout_s}};
}

std::optional<std::string> ProcessEnvironment(const std::string& name) {
  const char* v = std::getenv(name.c_str());
  if (v == nullptr || *v == '\0') return std::nullopt;
  return std::string(v);
}

std::string FirstHostOfHostlist(std::string_view hostlist, std::string_view variable) {
  // The first host expression ends at the first comma outside brackets; in
  // it, each bracket group "[a-b,c]" stands for its first number, kept as written.
  std::string host;
  int depth = 0;
  bool group_done = false;  // Inside a group, past its first number.
  for (char c : hostlist) {
    if (c == '[') {
      CheckArgument(depth == 0, fmt::format("{} = '{}': nested '['", variable, hostlist));
      depth = 1;
      group_done = false;
    } else if (c == ']') {
      CheckArgument(depth == 1, fmt::format("{} = '{}': ']' without '['", variable, hostlist));
      depth = 0;
    } else if (depth == 1) {
      if (c == '-' || c == ',') group_done = true;
      if (!group_done) host += c;
    } else if (c == ',') {
      break;
    } else if (c != ' ') {
      host += c;
    }
  }
  CheckArgument(depth == 0, fmt::format("{} = '{}': '[' without ']'", variable, hostlist));
  CheckArgument(!host.empty(), fmt::format("{} = '{}': no host", variable, hostlist));
  return host;
}

DistributedOptions DistributedOptionsFromEnvironment(const EnvironmentLookup& env) {
  DistributedOptions d;
  const auto rank = First(env, "RANK", "SLURM_PROCID");
  const auto size = First(env, "WORLD_SIZE", "SLURM_NTASKS");
  CheckArgument(rank && size,
                "--distributed needs this process's rank and the number of processes: run it under "
                "`srun -n K` (SLURM_PROCID, SLURM_NTASKS) or set RANK and WORLD_SIZE (and MASTER_ADDR, MASTER_PORT)");
  d.world_size = static_cast<int>(ParseInteger(size->first, size->second, 1, 1 << 20));
  d.rank = static_cast<int>(ParseInteger(rank->first, rank->second, 0, d.world_size - 1));
  if (d.world_size == 1) return d;

  if (std::optional<std::string> addr = env("MASTER_ADDR")) {
    d.master_addr = *addr;
  } else if (const auto nodes = First(env, "SLURM_STEP_NODELIST", "SLURM_JOB_NODELIST")) {
    d.master_addr = FirstHostOfHostlist(nodes->second, nodes->first);
  } else {
    throw InvalidArgument(
        "--distributed: no rendezvous host: set MASTER_ADDR, or run under srun (SLURM_STEP_NODELIST)");
  }
  if (std::optional<std::string> port = env("MASTER_PORT")) {
    d.master_port = static_cast<int>(ParseInteger("MASTER_PORT", *port, 1, 65535));
  } else {
    d.master_port = SlurmPort(env);
  }
  return d;
}

}  // namespace asbuilt
