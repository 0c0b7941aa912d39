#ifndef ASBUILT_SEG_COMMUNICATOR_H_
#define ASBUILT_SEG_COMMUNICATOR_H_

// The collectives of data-parallel training between K processes (ranks).
// INTERNAL to seg/: it includes torch. ConnectGloo() gives LibTorch's c10d
// Gloo process group (TCP), which is all `asbuilt train --distributed` uses;
// the interface lets tests run K ranks as threads of one process.

#include <torch/torch.h>

#include <memory>
#include <string>
#include <vector>

#include "asbuilt/seg/distributed.h"

namespace asbuilt {

class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int world_size() const = 0;
  // Every rank calls each collective, in the same order, with tensors of the
  // same shape and type (contiguous, CPU). On failure (a rank died, or did
  // not arrive within the timeout) they throw Error.
  //
  // Replaces `t` by its sum over the ranks, the same bits on every rank.
  virtual void AllReduceSum(torch::Tensor& t) = 0;
  // Replaces `t` by rank `root`'s.
  virtual void Broadcast(torch::Tensor& t, int root) = 0;
  // Returns when every rank has called it.
  virtual void Barrier() = 0;
};

// Joins the K processes `options` describes (it must be enabled(): world size
// > 1): rank 0 serves a TCPStore on master_addr:master_port, every rank meets
// there, and the Gloo process group connects them all; Gloo's sockets bind
// to GLOO_SOCKET_IFNAME's interface when set, to the loopback when the master
// address is a loopback one, else to this host's name. Every collective then
// fails after options.timeout_s. Throws Error naming the address when the
// others do not all arrive in time; Error in a build without Gloo's headers.
std::shared_ptr<Communicator> ConnectGloo(const DistributedOptions& options);

// The collectives on many tensors at once (one message for all): the sum of
// each over the ranks, in place (gradients; may include undefined tensors,
// which are skipped), and rank `root`'s values in every tensor (parameters).
void AllReduceSumEach(Communicator& comm, const std::vector<torch::Tensor>& tensors);
void BroadcastEach(Communicator& comm, const std::vector<torch::Tensor>& tensors, int root);

// Throws Error unless every rank passes the same `value`; `what` names it in
// the message ("rank 1's parameters differ from rank 0's…" style).
void CheckSameOnEveryRank(Communicator& comm, std::int64_t value, const std::string& what);

}  // namespace asbuilt

#endif  // ASBUILT_SEG_COMMUNICATOR_H_
