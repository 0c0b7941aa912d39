#include "asbuilt/seg/communicator.h"

#include <chrono>
#include <cstdlib>

#include <fmt/format.h>

#if ASBUILT_SEG_HAS_GLOO
#include <torch/csrc/distributed/c10d/PrefixStore.hpp>
#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>
#endif

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

#if ASBUILT_SEG_HAS_GLOO
// An exception's message; c10's without the stack trace it carries.
std::string MessageOf(const std::exception& e) {
  if (const auto* c10_error = dynamic_cast<const c10::Error*>(&e)) return c10_error->what_without_backtrace();
  return e.what();
}

bool IsLoopback(const std::string& host) { return host == "localhost" || host.rfind("127.", 0) == 0 || host == "::1"; }

class GlooCommunicator : public Communicator {
 public:
  GlooCommunicator(const DistributedOptions& o, c10::intrusive_ptr<c10d::ProcessGroupGloo> group)
      : options_(o), group_(std::move(group)) {}
  int rank() const override { return options_.rank; }
  int world_size() const override { return options_.world_size; }
  void AllReduceSum(torch::Tensor& t) override {
    std::vector<torch::Tensor> ts{t};
    Wait("all-reduce", [&] { return group_->allreduce(ts); });
  }
  void Broadcast(torch::Tensor& t, int root) override {
    std::vector<torch::Tensor> ts{t};
    c10d::BroadcastOptions b;
    b.rootRank = root;
    Wait("broadcast", [&] { return group_->broadcast(ts, b); });
  }
  void Barrier() override {
    Wait("barrier", [&] { return group_->barrier(); });
  }

 private:
  // Runs one collective to its end; Gloo's own message (which names the
  // peer's address) is kept in ours.
  template <class Start>
  void Wait(const char* what, Start&& start) {
    try {
      start()->wait();
    } catch (const std::exception& e) {
      throw Error(
          fmt::format("lost contact with the other ranks during {} (a rank died, or did not answer within the {} s of "
                      "--dist-timeout): {}; re-run every rank to resume from the last checkpoint",
                      what, options_.timeout_s, MessageOf(e)));
    }
  }

  DistributedOptions options_;
  c10::intrusive_ptr<c10d::ProcessGroupGloo> group_;
};
#endif

}  // namespace

std::shared_ptr<Communicator> ConnectGloo(const DistributedOptions& o) {
  o.Check();
  CheckArgument(o.enabled(), "ConnectGloo: world size 1 needs no process group");
#if ASBUILT_SEG_HAS_GLOO
  const auto timeout = std::chrono::milliseconds(static_cast<std::int64_t>(o.timeout_s * 1000));
  try {
    c10d::TCPStoreOptions store_options;
    store_options.port = static_cast<std::uint16_t>(o.master_port);
    store_options.isServer = o.rank == 0;
    store_options.numWorkers = o.world_size;
    store_options.timeout = timeout;
    auto store = c10::make_intrusive<c10d::TCPStore>(o.master_addr, store_options);
    auto prefixed = c10::make_intrusive<c10d::PrefixStore>("asbuilt-train", store);
    auto gloo = c10d::ProcessGroupGloo::Options::create(timeout);
    if (const char* interface = std::getenv("GLOO_SOCKET_IFNAME"); interface != nullptr && *interface != '\0') {
      gloo->devices.push_back(c10d::ProcessGroupGloo::createDeviceForInterface(interface));
    } else if (IsLoopback(o.master_addr)) {
      gloo->devices.push_back(c10d::ProcessGroupGloo::createDeviceForHostname("127.0.0.1"));
    } else {
      gloo->devices.push_back(c10d::ProcessGroupGloo::createDefaultDevice());
    }
    auto group = c10::make_intrusive<c10d::ProcessGroupGloo>(prefixed, o.rank, o.world_size, gloo);
    return std::make_shared<GlooCommunicator>(o, std::move(group));
  } catch (const std::exception& e) {
    throw Error(fmt::format("could not meet the other {} rank(s) at {}:{} within {} s (--dist-timeout): {}",
                            o.world_size - 1, o.master_addr, o.master_port, o.timeout_s, MessageOf(e)));
  }
#else
  throw Error("--distributed: this build has no Gloo headers (Debian package libgloo-dev); install it and rebuild");
#endif
}

void AllReduceSumEach(Communicator& comm, const std::vector<torch::Tensor>& tensors) {
  std::vector<torch::Tensor> defined;
  for (const torch::Tensor& t : tensors) {
    if (t.defined()) defined.push_back(t);
  }
  if (defined.empty()) return;
  std::vector<torch::Tensor> flat;
  for (const torch::Tensor& t : defined) flat.push_back(t.reshape({-1}));
  torch::Tensor buffer = torch::cat(flat);
  comm.AllReduceSum(buffer);
  torch::NoGradGuard no_grad;
  std::int64_t at = 0;
  for (const torch::Tensor& t : defined) {
    t.copy_(buffer.narrow(0, at, t.numel()).view(t.sizes()));
    at += t.numel();
  }
}

void BroadcastEach(Communicator& comm, const std::vector<torch::Tensor>& tensors, int root) {
  if (tensors.empty()) return;
  std::vector<torch::Tensor> flat;
  for (const torch::Tensor& t : tensors) flat.push_back(t.detach().reshape({-1}).to(torch::kDouble));
  torch::Tensor buffer = torch::cat(flat);
  comm.Broadcast(buffer, root);
  torch::NoGradGuard no_grad;
  std::int64_t at = 0;
  for (const torch::Tensor& t : tensors) {
    t.copy_(buffer.narrow(0, at, t.numel()).view(t.sizes()));
    at += t.numel();
  }
}

void CheckSameOnEveryRank(Communicator& comm, std::int64_t value, const std::string& what) {
  // Each rank writes its value in its own slot; the sum is every rank's value.
  torch::Tensor all = torch::zeros({comm.world_size()}, torch::kInt64);
  all[comm.rank()] = value;
  comm.AllReduceSum(all);
  for (int r = 1; r < comm.world_size(); ++r) {
    if (all[r].item<std::int64_t>() != all[0].item<std::int64_t>()) {
      throw Error(fmt::format("rank {}'s {} differs from rank 0's ({} vs {})", r, what, all[r].item<std::int64_t>(),
                              all[0].item<std::int64_t>()));
    }
  }
}

}  // namespace asbuilt
