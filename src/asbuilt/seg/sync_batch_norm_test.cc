#include "asbuilt/seg/sync_batch_norm.h"

#include <barrier>
#include <functional>
#include <memory>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "asbuilt/seg/communicator.h"
#include "asbuilt/seg/segformer.h"

namespace asbuilt {
namespace {
namespace nn = torch::nn;

// K ranks as K threads of this process: each collective meets at a barrier.
struct ThreadGroup {
  explicit ThreadGroup(int k) : barrier(k), slots(k) {}
  std::barrier<> barrier;
  std::vector<torch::Tensor> slots;
};

class ThreadCommunicator : public Communicator {
 public:
  ThreadCommunicator(std::shared_ptr<ThreadGroup> group, int rank) : group_(std::move(group)), rank_(rank) {}
  int rank() const override { return rank_; }
  int world_size() const override { return static_cast<int>(group_->slots.size()); }
  void AllReduceSum(torch::Tensor& t) override {
    Exchange(t);
    torch::Tensor sum = group_->slots[0].clone();  // In rank order: the same bits on every rank.
    for (int r = 1; r < world_size(); ++r) sum += group_->slots[r];
    group_->barrier.arrive_and_wait();
    t.copy_(sum);
  }
  void Broadcast(torch::Tensor& t, int root) override {
    Exchange(t);
    torch::Tensor v = group_->slots[root].clone();
    group_->barrier.arrive_and_wait();
    t.copy_(v);
  }
  void Barrier() override { group_->barrier.arrive_and_wait(); }

 private:
  void Exchange(const torch::Tensor& t) {
    group_->slots[rank_] = t.detach().clone();
    group_->barrier.arrive_and_wait();
  }
  std::shared_ptr<ThreadGroup> group_;
  int rank_;
};

// Runs body(rank, comm) on K threads.
void RunRanks(int k, const std::function<void(int, Communicator&)>& body) {
  auto group = std::make_shared<ThreadGroup>(k);
  std::vector<std::thread> threads;
  for (int r = 0; r < k; ++r) {
    threads.emplace_back([&, r] {
      ThreadCommunicator comm(group, r);
      body(r, comm);
    });
  }
  for (auto& t : threads) t.join();
}

void ExpectNear(const torch::Tensor& a, const torch::Tensor& b, double tol, const char* what) {
  ASSERT_EQ(a.sizes(), b.sizes()) << what;
  EXPECT_LT((a - b).abs().max().item<double>(), tol) << what;
}

struct BnResult {
  torch::Tensor y, dx, dweight, dbias, running_mean, running_var;
};

// Batch norm of rows [first, first + count) of x, its gradients under the
// loss Σ y·w, and the running statistics after one step.
BnResult RunBatchNorm(const nn::BatchNorm2d& prototype, const torch::Tensor& x_all, const torch::Tensor& w_all,
                      int64_t first, int64_t count, Communicator* comm) {
  auto bn = std::dynamic_pointer_cast<nn::BatchNorm2dImpl>(prototype->clone());
  bn->train();
  torch::Tensor x = x_all.narrow(0, first, count).clone().requires_grad_(true);
  torch::Tensor y = comm ? SyncBatchNorm(*bn, x, *comm) : bn->forward(x);
  (y * w_all.narrow(0, first, count)).sum().backward();
  return {y.detach(), x.grad(), bn->weight.grad(), bn->bias.grad(), bn->running_mean.clone(), bn->running_var.clone()};
}

class SyncBatchNormTest : public ::testing::Test {
 protected:
  void SetUp() override {
    torch::manual_seed(7);
    bn = nn::BatchNorm2d(5);
    torch::NoGradGuard no_grad;
    bn->weight.uniform_(0.5, 1.5);
    bn->bias.uniform_(-0.5, 0.5);
    x = torch::randn({4, 5, 6, 7}) * 3 + 1;
    w = torch::randn({4, 5, 6, 7});
  }
  nn::BatchNorm2d bn{nullptr};
  torch::Tensor x, w;
};

TEST_F(SyncBatchNormTest, OneRankEqualsBatchNorm2d) {
  BnResult want = RunBatchNorm(bn, x, w, 0, 4, nullptr);
  BnResult got;
  RunRanks(1, [&](int, Communicator& comm) { got = RunBatchNorm(bn, x, w, 0, 4, &comm); });
  ExpectNear(got.y, want.y, 1e-5, "y");
  ExpectNear(got.dx, want.dx, 1e-5, "dx");
  ExpectNear(got.dweight, want.dweight, 1e-4, "dweight");
  ExpectNear(got.dbias, want.dbias, 1e-4, "dbias");
  ExpectNear(got.running_mean, want.running_mean, 1e-6, "running_mean");
  ExpectNear(got.running_var, want.running_var, 1e-5, "running_var (unbiased)");
}

TEST_F(SyncBatchNormTest, TwoRanksWithHalfTheBatchEachEqualOneWithAll) {
  BnResult want = RunBatchNorm(bn, x, w, 0, 4, nullptr);
  std::vector<BnResult> got(2);
  RunRanks(2, [&](int r, Communicator& comm) { got[r] = RunBatchNorm(bn, x, w, 2 * r, 2, &comm); });
  ExpectNear(torch::cat({got[0].y, got[1].y}), want.y, 1e-5, "y");
  ExpectNear(torch::cat({got[0].dx, got[1].dx}), want.dx, 1e-5, "dx");
  // γ's and β's gradients are each rank's share: their sum is the whole batch's.
  ExpectNear(got[0].dweight + got[1].dweight, want.dweight, 1e-4, "dweight");
  ExpectNear(got[0].dbias + got[1].dbias, want.dbias, 1e-4, "dbias");
  for (const BnResult& g : got) {
    ExpectNear(g.running_mean, want.running_mean, 1e-6, "running_mean");
    ExpectNear(g.running_var, want.running_var, 1e-5, "running_var");
  }
}

// The whole SegFormer in training mode (batch norms synchronised; no random
// masks here, since the threads share one generator): two ranks with half
// the batch each give the logits and, summed, the gradients of one process.
// Also with one image per rank at the toy size of the CLI tests, where the
// deepest batch norm sees two values per rank.
void ExpectTwoRanksComputeTheGradientsOfOneProcess(int64_t batch, int64_t height, int64_t width) {
  SegformerConfig config = SegformerConfigFor("tiny", 4);
  config.drop_path_rate = 0;
  config.decoder_dropout = 0;
  torch::manual_seed(3);
  Segformer single(config);
  single->train();
  const torch::Tensor x = torch::randn({batch, 3, height, width});
  const torch::Tensor target = torch::randint(0, 4, {batch, (height + 3) / 4, (width + 3) / 4});
  auto loss_of = [&](Segformer& m, int64_t first, int64_t count) {
    torch::Tensor logits = m->forward(x.narrow(0, first, count));
    return torch::nn::functional::cross_entropy(
               logits, target.narrow(0, first, count),
               torch::nn::functional::CrossEntropyFuncOptions().reduction(torch::kSum)) /
           target.numel();
  };
  std::vector<Segformer> ranks;  // Copies of `single` before its step.
  for (int r = 0; r < 2; ++r) {
    ranks.emplace_back(config);
    torch::NoGradGuard no_grad;
    for (const auto& p : single->named_parameters()) ranks[r]->named_parameters()[p.key()].copy_(p.value());
    for (const auto& b : single->named_buffers()) ranks[r]->named_buffers()[b.key()].copy_(b.value());
  }
  loss_of(single, 0, batch).backward();

  RunRanks(2, [&](int r, Communicator& comm) {
    ranks[r]->SetDataParallel(std::shared_ptr<Communicator>(&comm, [](Communicator*) {}));
    ranks[r]->train();
    loss_of(ranks[r], batch / 2 * r, batch / 2).backward();
    ranks[r]->SetDataParallel(nullptr);
  });
  const auto a = ranks[0]->named_parameters(), b = ranks[1]->named_parameters();
  for (const auto& p : single->named_parameters()) {
    const torch::Tensor sum = a[p.key()].grad() + b[p.key()].grad();
    const double scale = std::max(1e-3, p.value().grad().abs().max().item<double>());
    const double err = (sum - p.value().grad()).abs().max().item<double>();
    EXPECT_LT(err / scale, 1e-4) << p.key();
  }
  for (const auto& buf : single->named_buffers()) {
    EXPECT_LT((ranks[0]->named_buffers()[buf.key()] - buf.value()).abs().max().item<double>(), 1e-4) << buf.key();
  }
}

TEST(SegformerDataParallel, TwoRanksComputeTheGradientsOfOneProcess) {
  ExpectTwoRanksComputeTheGradientsOfOneProcess(4, 64, 64);
}

TEST(SegformerDataParallel, TwoRanksOfOneImageEachComputeTheGradientsOfOneProcess) {
  ExpectTwoRanksComputeTheGradientsOfOneProcess(2, 32, 48);
}

}  // namespace
}  // namespace asbuilt
