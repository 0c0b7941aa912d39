#ifndef ASBUILT_FORMATS_TFLITE_H_
#define ASBUILT_FORMATS_TFLITE_H_

// A reader for TensorFlow Lite model files (a FlatBuffer of TFLite's public
// `schema.fbs`): the first subgraph's tensors (shape, type, quantisation,
// constant data) and operators (builtin code, inputs, outputs, the options
// the operators we run need). Plain C++ with explicit bounds checks on every
// offset; no TFLite runtime and no generated code.
//
//   TfliteModel model = ReadTflite("deeplabv3_mnv2_ade20k32_uint8.tflite");
//   std::vector<float> w = DequantizedData(model, model.operators[0].inputs[1]);
//
// A file that is not a TFLite model, is truncated, or has an offset out of
// range throws InputError naming the file and the field.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace asbuilt {

// TFLite's TensorType values for the types we read.
enum class TfliteType : int {
  kFloat32 = 0,
  kFloat16 = 1,
  kInt32 = 2,
  kUInt8 = 3,
  kInt64 = 4,
  kInt8 = 9,
};

// TFLite's BuiltinOperator codes of the operators asbuilt can run.
enum class TfliteOp : int {
  kAdd = 0,
  kAveragePool2d = 1,
  kConcatenation = 2,
  kConv2d = 3,
  kDepthwiseConv2d = 4,
  kDequantize = 6,
  kMaxPool2d = 17,
  kMul = 18,
  kRelu = 19,
  kRelu6 = 21,
  kReshape = 22,
  kResizeBilinear = 23,
  kSoftmax = 25,
  kPad = 34,
  kMean = 40,
  kSplit = 49,
  kArgMax = 56,
  kQuantize = 114,
};

std::string TfliteOpName(int builtin_code);  // "CONV_2D", or "builtin 77".

struct TfliteQuantization {
  std::vector<float> scale;  // One per tensor or one per channel; empty = not quantised.
  std::vector<std::int64_t> zero_point;
  int quantized_dimension = 0;  // The channel axis of per-channel scales.
};

struct TfliteTensor {
  std::string name;
  std::vector<int> shape;
  int type = 0;  // TfliteType value (other values are kept as read).
  TfliteQuantization quantization;
  std::vector<std::uint8_t> data;  // Constant data; empty for activations.
};

// The options of the operators asbuilt runs (fields of TFLite's option tables,
// with the schema's defaults where the file leaves them out).
struct TfliteOptions {
  bool padding_same = true;  // Padding: SAME (true) or VALID.
  int stride_w = 1, stride_h = 1;
  int dilation_w = 1, dilation_h = 1;
  int depth_multiplier = 1;
  int filter_w = 1, filter_h = 1;                          // Pooling windows.
  int activation = 0;                                      // 0 none, 1 RELU, 2 RELU_N1_TO_1, 3 RELU6.
  int axis = 0;                                            // CONCATENATION.
  int num_splits = 0;                                      // SPLIT.
  bool align_corners = false, half_pixel_centers = false;  // RESIZE_BILINEAR.
  bool keep_dims = false;                                  // MEAN.
};

struct TfliteOperator {
  int builtin_code = 0;              // TfliteOp value, or any other builtin code as read.
  std::vector<int> inputs, outputs;  // Tensor indices; -1 = optional input left out.
  TfliteOptions options;
};

struct TfliteModel {
  std::string file;  // As given, for messages.
  std::string description;
  std::vector<TfliteTensor> tensors;      // Of the first subgraph.
  std::vector<TfliteOperator> operators;  // In execution order.
  std::vector<int> inputs, outputs;       // Tensor indices.
};

// Parses a model held in memory; `file` names it in errors.
TfliteModel ParseTflite(std::string_view bytes, const std::string& file);
TfliteModel ReadTflite(const std::filesystem::path& path);

// A constant tensor's values as float: quantised types dequantised
// ((q − zero_point) · scale, per channel where the scales are), int32 and
// float32 as they are. Throws InputError for a tensor without data or of a
// type it does not know.
std::vector<float> DequantizedData(const TfliteModel& model, int tensor);

// The graph as JSON without its large constants (over 64 bytes: the filters
// and biases, which a fine-tuned checkpoint holds as trained parameters) and
// without per-channel quantisation (filters' only); everything else is kept
// exactly. FromJson throws
// InputError naming `file` and the field for a graph it cannot read.
nlohmann::json TfliteGraphToJson(const TfliteModel& model);
TfliteModel TfliteGraphFromJson(const nlohmann::json& graph, const std::string& file);
inline constexpr std::size_t kTfliteSmallConstantBytes = 64;

}  // namespace asbuilt

#endif  // ASBUILT_FORMATS_TFLITE_H_
