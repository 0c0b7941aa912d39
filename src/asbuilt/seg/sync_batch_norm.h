#ifndef ASBUILT_SEG_SYNC_BATCH_NORM_H_
#define ASBUILT_SEG_SYNC_BATCH_NORM_H_

// Batch norm over a batch split across ranks (PyTorch's SyncBatchNorm, which
// mmseg's SegFormer head uses in distributed training). INTERNAL to seg/.
//
// Forward: per channel, the sum, the sum of squares and the count of this
// rank's values are summed over the ranks (in double), giving the global
// batch's mean and biased variance; y = (x − mean)/√(var + eps)·γ + β.
// Backward: the two per-channel sums of the input gradient's formula,
// Σ dy and Σ dy·x̂, are summed over the ranks; dx = γ/σ·(dy − Σdy/n − x̂·Σdy·x̂/n).
// The gradients of γ and β are this rank's own sums: data-parallel training
// sums every gradient over the ranks afterwards.

#include <torch/torch.h>

#include "asbuilt/seg/communicator.h"

namespace asbuilt {

// `bn`'s batch norm of x (B, C, H, W) in training mode with the statistics of
// every rank's x: updates bn's running mean and (unbiased) variance and its
// batch count as BatchNorm2d's forward does. Every rank must call it, in the
// same order, with the same C.
torch::Tensor SyncBatchNorm(torch::nn::BatchNorm2dImpl& bn, const torch::Tensor& x, Communicator& comm);

}  // namespace asbuilt

#endif  // ASBUILT_SEG_SYNC_BATCH_NORM_H_
