#ifndef ASBUILT_SEG_TFLITE_NET_H_
#define ASBUILT_SEG_TFLITE_NET_H_

// A TensorFlow Lite segmentation graph (DeepLabV3-MobileNetV2, MOSAIC) run in
// LibTorch: the file's operators in order, each a torch function, with the
// weights dequantised to float and registered as trainable parameters.
// Internal to seg/ (includes LibTorch).
//
// Activations are clamped to the range their uint8 quantisation can hold (the
// network's own ReLU6 / ReLU bounds); with `emulate_uint8` they are also
// rounded to that grid, as the quantised original computes, which is what
// reproduces its argmax.

#include <string>
#include <vector>

#include <torch/torch.h>

#include "asbuilt/formats/tflite.h"

namespace asbuilt {

struct TfliteNetOptions {
  // Round every uint8 activation to its quantisation grid (faithful to the
  // quantised original; off for training, where it would block gradients).
  bool emulate_uint8 = false;
  // Stop before the graph's last RESIZE_BILINEAR (the upsampling of the
  // logits to the input size): callers resize the low-resolution logits to
  // the size they want in one step.
  bool stop_before_final_resize = true;
};

class TfliteNetImpl : public torch::nn::Module {
 public:
  // Throws InputError naming the file and operator for an operator, tensor
  // type or layout it cannot run, and for a graph without one image input.
  TfliteNetImpl(const TfliteModel& model, TfliteNetOptions options);

  // `rgb`: (B, 3, H, W) float in 0..255. Returns the logits (B, C, h, w)
  // feeding the graph's final ARG_MAX: at the input size, or the size before
  // the final resize when `stop_before_final_resize`. Any H, W: the resize
  // targets and global pools of the file scale with the input.
  torch::Tensor forward(const torch::Tensor& rgb);

  int num_classes() const { return num_classes_; }
  int input_width_px() const { return input_w_; }  // The file's declared input size.
  int input_height_px() const { return input_h_; }
  const TfliteNetOptions& options() const { return options_; }
  void set_emulate_uint8(bool on) { options_.emulate_uint8 = on; }
  // Global average pools of an input whose long side exceeds its short side
  // by more than a quarter: over windows of `px` input pixels along the long
  // side (the squares the network was trained on), each row or column taking
  // the mean of the windows that cover it; 0 (the default): over the whole map.
  void set_pool_window(int px) { pool_window_px_ = px; }
  // The graph without its filters and biases (they are this module's
  // parameters): what a checkpoint stores to rebuild the network.
  const TfliteModel& graph() const { return graph_; }
  // The filter and bias of the convolution that computes the logits.
  std::vector<torch::Tensor> head_parameters() const;

 private:
  struct Quant {
    bool uint8 = false;
    float scale = 1.f, zero_point = 0.f;
  };
  torch::Tensor Requantize(const torch::Tensor& x, int tensor) const;

  TfliteModel graph_;  // Topology and constants (weights are copied into parameters).
  TfliteNetOptions options_;
  std::vector<Quant> quant_;                     // Per tensor.
  std::vector<torch::Tensor> weights_, biases_;  // Per operator (undefined when none).
  int input_tensor_ = 0, logits_tensor_ = 0, last_op_ = 0;
  int input_w_ = 0, input_h_ = 0, num_classes_ = 0;
  int pool_window_px_ = 0;
};
TORCH_MODULE(TfliteNet);

}  // namespace asbuilt

#endif  // ASBUILT_SEG_TFLITE_NET_H_
