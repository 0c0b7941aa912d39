#include "asbuilt/seg/sync_batch_norm.h"

#include <cstdint>

namespace asbuilt {
namespace {
namespace autograd = torch::autograd;

// (C) → (1, C, 1, 1), to broadcast over (B, C, H, W).
torch::Tensor PerChannel(const torch::Tensor& t) { return t.view({1, -1, 1, 1}); }

struct SyncBatchNormFunction : public autograd::Function<SyncBatchNormFunction> {
  static torch::Tensor forward(autograd::AutogradContext* ctx, const torch::Tensor& x, const torch::Tensor& weight,
                               const torch::Tensor& bias, torch::nn::BatchNorm2dImpl* bn, Communicator* comm) {
    const int64_t c = x.size(1);
    // Global sums: Σx, Σx², n.
    torch::Tensor sums =
        torch::cat({x.sum({0, 2, 3}, false, torch::kDouble), (x * x).sum({0, 2, 3}, false, torch::kDouble),
                    torch::full({1}, static_cast<double>(x.numel() / c), torch::kDouble)});
    comm->AllReduceSum(sums);
    const double n = sums[2 * c].item<double>();
    torch::Tensor mean = sums.narrow(0, 0, c) / n;
    torch::Tensor var = (sums.narrow(0, c, c) / n - mean * mean).clamp_min(0);

    // Running statistics, as BatchNorm2d (momentum, or the cumulative average without one).
    const auto& o = bn->options;
    if (o.track_running_stats() && bn->running_mean.defined()) {
      double factor = o.momentum().value_or(0.0);
      if (bn->num_batches_tracked.defined()) {
        bn->num_batches_tracked += 1;
        if (!o.momentum()) factor = 1.0 / bn->num_batches_tracked.item<double>();
      }
      const torch::Tensor unbiased = n > 1 ? var * (n / (n - 1)) : var;
      bn->running_mean.mul_(1 - factor).add_(mean.to(bn->running_mean.scalar_type()) * factor);
      bn->running_var.mul_(1 - factor).add_(unbiased.to(bn->running_var.scalar_type()) * factor);
    }

    const torch::Tensor invstd = (var + o.eps()).rsqrt().to(x.scalar_type());
    const torch::Tensor xhat = (x - PerChannel(mean.to(x.scalar_type()))) * PerChannel(invstd);
    ctx->save_for_backward({xhat, weight, invstd});
    ctx->saved_data["n"] = n;
    ctx->saved_data["comm"] = reinterpret_cast<std::int64_t>(comm);
    return weight.defined() ? xhat * PerChannel(weight) + PerChannel(bias) : xhat;
  }

  static autograd::variable_list backward(autograd::AutogradContext* ctx, autograd::variable_list grad_outputs) {
    const autograd::variable_list saved = ctx->get_saved_variables();
    const torch::Tensor &xhat = saved[0], &weight = saved[1], &invstd = saved[2];
    const double n = ctx->saved_data["n"].toDouble();
    auto* comm = reinterpret_cast<Communicator*>(ctx->saved_data["comm"].toInt());
    const torch::Tensor& dy = grad_outputs[0];
    const int64_t c = dy.size(1);
    // This rank's Σdy and Σdy·x̂ (β's and γ's gradients), then the global ones.
    const torch::Tensor sum_dy = dy.sum({0, 2, 3});
    const torch::Tensor sum_dy_xhat = (dy * xhat).sum({0, 2, 3});
    torch::Tensor global = torch::cat({sum_dy, sum_dy_xhat}).to(torch::kDouble);
    comm->AllReduceSum(global);
    const torch::Tensor mean_dy = (global.narrow(0, 0, c) / n).to(dy.scalar_type());
    const torch::Tensor mean_dy_xhat = (global.narrow(0, c, c) / n).to(dy.scalar_type());
    torch::Tensor scale = weight.defined() ? invstd * weight : invstd;
    torch::Tensor dx = PerChannel(scale) * (dy - PerChannel(mean_dy) - xhat * PerChannel(mean_dy_xhat));
    return {dx, weight.defined() ? sum_dy_xhat : torch::Tensor(), weight.defined() ? sum_dy : torch::Tensor(),
            torch::Tensor(), torch::Tensor()};
  }
};

}  // namespace

torch::Tensor SyncBatchNorm(torch::nn::BatchNorm2dImpl& bn, const torch::Tensor& x, Communicator& comm) {
  TORCH_CHECK(x.dim() == 4, "SyncBatchNorm: expected (B, C, H, W), got ", x.sizes());
  return SyncBatchNormFunction::apply(x, bn.weight, bn.bias, &bn, &comm);
}

}  // namespace asbuilt
