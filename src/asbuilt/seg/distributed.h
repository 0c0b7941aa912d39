#ifndef ASBUILT_SEG_DISTRIBUTED_H_
#define ASBUILT_SEG_DISTRIBUTED_H_

// Data-parallel training across processes (`asbuilt train --distributed`,
// docs/seg.md "Distributed training"): who this process is among K and where
// the K processes meet. No LibTorch here: the collectives themselves (c10d's
// Gloo process group) live in the plugin, in communicator.h.
//
//   srun -n 4 asbuilt train --distributed …        rank, size, host from Slurm
//   RANK=1 WORLD_SIZE=2 MASTER_ADDR=10.0.0.5 MASTER_PORT=29500 asbuilt train --distributed …

#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace asbuilt {

struct DistributedOptions {
  int rank = 0;             // This process, 0 … world_size − 1; rank 0 writes every file.
  int world_size = 1;       // Processes training together; 1 = plain training.
  std::string master_addr;  // Host of the rendezvous (rank 0 serves a TCPStore there).
  int master_port = 0;      // Its TCP port, 1 … 65535.
  double timeout_s = 300;   // How long a rank waits for the others (rendezvous and every
                            // collective) before it fails; a killed peer is usually
                            // noticed at once (its connections close).

  bool enabled() const { return world_size > 1; }
  void Check() const;
  nlohmann::json ToJson() const;
};

// Reads a variable of the environment; nullopt when it is not set.
using EnvironmentLookup = std::function<std::optional<std::string>(const std::string& name)>;
// The process environment (std::getenv); an empty value counts as not set.
std::optional<std::string> ProcessEnvironment(const std::string& name);

// This process's place in a distributed run, from the environment. Each value
// comes from the torchrun-style variable when it is set, else from Slurm's:
//   rank         RANK         else SLURM_PROCID
//   world_size   WORLD_SIZE   else SLURM_NTASKS
//   master_addr  MASTER_ADDR  else the first host of SLURM_STEP_NODELIST
//                             (else SLURM_JOB_NODELIST), e.g. node[01-04],gpu3 → node01
//   master_port  MASTER_PORT  else 20000 + (SLURM_JOB_ID mod 2000)·10 + SLURM_STEP_ID mod 10,
//                             the same for every task of a step, different for
//                             the steps of a job and for most concurrent jobs
// World size 1 needs no address or port. Throws InvalidArgument naming the
// variable for a missing or malformed value (RANK = 'x' is not an integer;
// SLURM_PROCID = 4 with SLURM_NTASKS = 4). timeout_s is left at its default.
DistributedOptions DistributedOptionsFromEnvironment(const EnvironmentLookup& env = ProcessEnvironment);

// The first host of a Slurm hostlist ("node[01-04,07],gpu3" → "node01",
// "rack[2-3]-n[5-6]" → "rack2-n5", zero padding kept). Throws InvalidArgument
// for an empty list or unbalanced brackets; `variable` names the source in
// the message.
std::string FirstHostOfHostlist(std::string_view hostlist, std::string_view variable = "hostlist");

}  // namespace asbuilt

#endif  // ASBUILT_SEG_DISTRIBUTED_H_
