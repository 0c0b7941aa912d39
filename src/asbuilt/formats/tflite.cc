#include "asbuilt/formats/tflite.h"

#include <cstring>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {

// Field ids of TFLite's schema.fbs tables (the order of the fields there).
namespace model_field {
constexpr int kOperatorCodes = 1, kSubgraphs = 2, kDescription = 3, kBuffers = 4;
}
namespace subgraph_field {
constexpr int kTensors = 0, kInputs = 1, kOutputs = 2, kOperators = 3;
}
namespace tensor_field {
constexpr int kShape = 0, kType = 1, kBuffer = 2, kName = 3, kQuantization = 4;
}
namespace quant_field {
constexpr int kScale = 2, kZeroPoint = 3, kQuantizedDimension = 6;
}
namespace operator_field {
constexpr int kOpcodeIndex = 0, kInputs = 1, kOutputs = 2, kBuiltinOptions = 4;
}
namespace opcode_field {
constexpr int kDeprecatedBuiltinCode = 0, kBuiltinCode = 3;
}

// Bounds-checked access to a FlatBuffer: every read names what it was reading
// when it falls outside the file.
class FlatReader {
 public:
  FlatReader(std::string_view bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  [[noreturn]] void Fail(const std::string& field, const std::string& message) const {
    throw InputError(file_, field, message);
  }

  template <typename T>
  T Scalar(std::size_t pos, const std::string& field) const {
    if (pos > bytes_.size() || bytes_.size() - pos < sizeof(T)) {
      Fail(field, fmt::format("offset {} is past the end of the file ({} bytes): truncated or not a TFLite model", pos,
                              bytes_.size()));
    }
    T value;
    std::memcpy(&value, bytes_.data() + pos, sizeof(T));
    return value;  // FlatBuffers are little-endian, as is every host we build for.
  }

  // A table: its position and its vtable.
  struct Table {
    std::size_t pos = 0;
    std::size_t vtable = 0;
    std::uint16_t vtable_size = 0;
  };

  Table TableAt(std::size_t pos, const std::string& field) const {
    const auto soffset = Scalar<std::int32_t>(pos, field);
    const auto vtable = static_cast<std::int64_t>(pos) - soffset;
    if (vtable < 0) Fail(field, "table's vtable lies before the start of the file");
    Table t{pos, static_cast<std::size_t>(vtable), 0};
    t.vtable_size = Scalar<std::uint16_t>(t.vtable, field);
    if (t.vtable_size < 4 || t.vtable_size % 2 != 0) Fail(field, fmt::format("bad vtable size {}", t.vtable_size));
    return t;
  }

  // Position of field `id` of `t`, or 0 when the file leaves it out.
  std::size_t Field(const Table& t, int id, const std::string& field) const {
    const std::size_t entry = 4 + 2 * static_cast<std::size_t>(id);
    if (entry + 2 > t.vtable_size) return 0;
    const auto off = Scalar<std::uint16_t>(t.vtable + entry, field);
    return off == 0 ? 0 : t.pos + off;
  }

  template <typename T>
  T FieldScalar(const Table& t, int id, T fallback, const std::string& field) const {
    const std::size_t pos = Field(t, id, field);
    return pos == 0 ? fallback : Scalar<T>(pos, field);
  }

  // Follows the uoffset stored at `pos`.
  std::size_t Deref(std::size_t pos, const std::string& field) const { return pos + Scalar<std::uint32_t>(pos, field); }

  // A vector field: position of its first element and its length (0, 0 if absent).
  std::pair<std::size_t, std::size_t> Vector(const Table& t, int id, std::size_t element_size,
                                             const std::string& field) const {
    const std::size_t pos = Field(t, id, field);
    if (pos == 0) return {0, 0};
    const std::size_t vec = Deref(pos, field);
    const auto n = Scalar<std::uint32_t>(vec, field);
    const std::size_t start = vec + 4;
    if (start > bytes_.size() || (bytes_.size() - start) / element_size < n) {
      Fail(field, fmt::format("vector of {} elements runs past the end of the file", n));
    }
    return {start, n};
  }

  template <typename T>
  std::vector<T> ScalarVector(const Table& t, int id, const std::string& field) const {
    auto [start, n] = Vector(t, id, sizeof(T), field);
    std::vector<T> out(n);
    if (n > 0) std::memcpy(out.data(), bytes_.data() + start, n * sizeof(T));
    return out;
  }

  std::vector<Table> TableVector(const Table& t, int id, const std::string& field) const {
    auto [start, n] = Vector(t, id, 4, field);
    std::vector<Table> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::string item = fmt::format("{}[{}]", field, i);
      out.push_back(TableAt(Deref(start + 4 * i, item), item));
    }
    return out;
  }

  std::string String(const Table& t, int id, const std::string& field) const {
    auto [start, n] = Vector(t, id, 1, field);
    return std::string(bytes_.substr(start, n));
  }

  std::optional<Table> SubTable(const Table& t, int id, const std::string& field) const {
    const std::size_t pos = Field(t, id, field);
    if (pos == 0) return std::nullopt;
    return TableAt(Deref(pos, field), field);
  }

 private:
  std::string_view bytes_;
  const std::string& file_;
};

// Reads the options table of one operator according to its builtin code.
TfliteOptions ReadOptions(const FlatReader& r, const FlatReader::Table& options, int code, const std::string& field) {
  TfliteOptions o;
  auto i32 = [&](int id, int fallback) { return r.FieldScalar<std::int32_t>(options, id, fallback, field); };
  auto u8 = [&](int id, int fallback) {
    return static_cast<int>(r.FieldScalar<std::uint8_t>(options, id, fallback, field));
  };
  switch (static_cast<TfliteOp>(code)) {
    case TfliteOp::kConv2d:
      o.padding_same = u8(0, 0) == 0;
      o.stride_w = i32(1, 1), o.stride_h = i32(2, 1);
      o.activation = u8(3, 0);
      o.dilation_w = i32(4, 1), o.dilation_h = i32(5, 1);
      break;
    case TfliteOp::kDepthwiseConv2d:
      o.padding_same = u8(0, 0) == 0;
      o.stride_w = i32(1, 1), o.stride_h = i32(2, 1);
      o.depth_multiplier = i32(3, 1);
      o.activation = u8(4, 0);
      o.dilation_w = i32(5, 1), o.dilation_h = i32(6, 1);
      break;
    case TfliteOp::kAveragePool2d:
    case TfliteOp::kMaxPool2d:
      o.padding_same = u8(0, 0) == 0;
      o.stride_w = i32(1, 1), o.stride_h = i32(2, 1);
      o.filter_w = i32(3, 1), o.filter_h = i32(4, 1);
      o.activation = u8(5, 0);
      break;
    case TfliteOp::kConcatenation:
      o.axis = i32(0, 0);
      o.activation = u8(1, 0);
      break;
    case TfliteOp::kAdd:
    case TfliteOp::kMul:
      o.activation = u8(0, 0);
      break;
    case TfliteOp::kResizeBilinear:
      o.align_corners = u8(2, 0) != 0;
      o.half_pixel_centers = u8(3, 0) != 0;
      break;
    case TfliteOp::kSplit:
      o.num_splits = i32(0, 0);
      break;
    case TfliteOp::kMean:
      o.keep_dims = u8(0, 0) != 0;
      break;
    default:
      break;
  }
  return o;
}

}  // namespace

std::string TfliteOpName(int code) {
  static const std::map<int, std::string> names = {
      {0, "ADD"},        {1, "AVERAGE_POOL_2D"},  {2, "CONCATENATION"}, {3, "CONV_2D"},   {4, "DEPTHWISE_CONV_2D"},
      {6, "DEQUANTIZE"}, {17, "MAX_POOL_2D"},     {18, "MUL"},          {19, "RELU"},     {21, "RELU6"},
      {22, "RESHAPE"},   {23, "RESIZE_BILINEAR"}, {25, "SOFTMAX"},      {32, "CUSTOM"},   {34, "PAD"},
      {40, "MEAN"},      {49, "SPLIT"},           {56, "ARG_MAX"},      {114, "QUANTIZE"}};
  auto it = names.find(code);
  return it != names.end() ? it->second : fmt::format("builtin {}", code);
}

TfliteModel ParseTflite(std::string_view bytes, const std::string& file) {
  FlatReader r(bytes, file);
  if (bytes.size() < 8 || bytes.substr(4, 4) != "TFL3") {
    r.Fail("", "not a TensorFlow Lite model (no \"TFL3\" file identifier)");
  }
  TfliteModel model;
  model.file = file;
  const auto root = r.TableAt(r.Deref(0, "root"), "root");
  model.description = r.String(root, model_field::kDescription, "description");

  std::vector<int> codes;
  for (const auto& t : r.TableVector(root, model_field::kOperatorCodes, "operator_codes")) {
    const int deprecated = r.FieldScalar<std::int8_t>(t, opcode_field::kDeprecatedBuiltinCode, 0, "operator_codes");
    const int builtin = r.FieldScalar<std::int32_t>(t, opcode_field::kBuiltinCode, 0, "operator_codes");
    codes.push_back(std::max(deprecated, builtin));  // The schema's rule for old and new files.
  }
  const auto buffers = r.TableVector(root, model_field::kBuffers, "buffers");
  const auto subgraphs = r.TableVector(root, model_field::kSubgraphs, "subgraphs");
  if (subgraphs.empty()) r.Fail("subgraphs", "the model has no subgraph");
  const auto& sg = subgraphs[0];

  const auto tensors = r.TableVector(sg, subgraph_field::kTensors, "subgraphs[0].tensors");
  for (std::size_t i = 0; i < tensors.size(); ++i) {
    const std::string field = fmt::format("subgraphs[0].tensors[{}]", i);
    const auto& t = tensors[i];
    TfliteTensor tensor;
    tensor.name = r.String(t, tensor_field::kName, field + ".name");
    tensor.shape = r.ScalarVector<std::int32_t>(t, tensor_field::kShape, field + ".shape");
    tensor.type = r.FieldScalar<std::int8_t>(t, tensor_field::kType, 0, field + ".type");
    const auto buffer = r.FieldScalar<std::uint32_t>(t, tensor_field::kBuffer, 0, field + ".buffer");
    if (buffer >= buffers.size())
      r.Fail(field + ".buffer", fmt::format("buffer {} of {} does not exist", buffer, buffers.size()));
    tensor.data = r.ScalarVector<std::uint8_t>(buffers[buffer], 0, fmt::format("buffers[{}].data", buffer));
    if (auto q = r.SubTable(t, tensor_field::kQuantization, field + ".quantization")) {
      tensor.quantization.scale = r.ScalarVector<float>(*q, quant_field::kScale, field + ".quantization.scale");
      tensor.quantization.zero_point =
          r.ScalarVector<std::int64_t>(*q, quant_field::kZeroPoint, field + ".quantization.zero_point");
      tensor.quantization.quantized_dimension =
          r.FieldScalar<std::int32_t>(*q, quant_field::kQuantizedDimension, 0, field + ".quantization");
    }
    for (int d : tensor.shape) {
      if (d < 0) r.Fail(field + ".shape", "negative dimension (dynamic shapes are not supported)");
    }
    model.tensors.push_back(std::move(tensor));
  }

  auto check_indices = [&](const std::vector<int>& ids, const std::string& field, bool optional) {
    for (int id : ids) {
      if ((id < 0 && !(optional && id == -1)) || id >= static_cast<int>(model.tensors.size())) {
        r.Fail(field, fmt::format("tensor index {} out of range (the subgraph has {})", id, model.tensors.size()));
      }
    }
  };
  model.inputs = r.ScalarVector<std::int32_t>(sg, subgraph_field::kInputs, "subgraphs[0].inputs");
  model.outputs = r.ScalarVector<std::int32_t>(sg, subgraph_field::kOutputs, "subgraphs[0].outputs");
  check_indices(model.inputs, "subgraphs[0].inputs", false);
  check_indices(model.outputs, "subgraphs[0].outputs", false);

  const auto ops = r.TableVector(sg, subgraph_field::kOperators, "subgraphs[0].operators");
  for (std::size_t i = 0; i < ops.size(); ++i) {
    const std::string field = fmt::format("subgraphs[0].operators[{}]", i);
    TfliteOperator op;
    const auto index = r.FieldScalar<std::uint32_t>(ops[i], operator_field::kOpcodeIndex, 0, field);
    if (index >= codes.size()) r.Fail(field + ".opcode_index", fmt::format("{} is not an operator code", index));
    op.builtin_code = codes[index];
    op.inputs = r.ScalarVector<std::int32_t>(ops[i], operator_field::kInputs, field + ".inputs");
    op.outputs = r.ScalarVector<std::int32_t>(ops[i], operator_field::kOutputs, field + ".outputs");
    check_indices(op.inputs, field + ".inputs", true);
    check_indices(op.outputs, field + ".outputs", false);
    if (auto options = r.SubTable(ops[i], operator_field::kBuiltinOptions, field + ".builtin_options")) {
      op.options = ReadOptions(r, *options, op.builtin_code, field + ".builtin_options");
    }
    model.operators.push_back(std::move(op));
  }
  return model;
}

TfliteModel ReadTflite(const std::filesystem::path& path) { return ParseTflite(ReadFile(path), path.string()); }

std::vector<float> DequantizedData(const TfliteModel& model, int index) {
  const TfliteTensor& t = model.tensors.at(index);
  const std::string field = fmt::format("tensor {} ({})", index, t.name);
  std::size_t count = 1;
  for (int d : t.shape) count *= static_cast<std::size_t>(d);
  auto fail = [&](const std::string& message) -> void { throw InputError(model.file, field, message); };
  std::size_t element = 0;
  switch (static_cast<TfliteType>(t.type)) {
    case TfliteType::kFloat32:
    case TfliteType::kInt32:
      element = 4;
      break;
    case TfliteType::kUInt8:
    case TfliteType::kInt8:
      element = 1;
      break;
    default:
      fail(fmt::format("tensor type {} is not supported (float32, int32, uint8, int8 are)", t.type));
  }
  if (t.data.size() != count * element) {
    fail(fmt::format("holds {} bytes, its shape needs {}", t.data.size(), count * element));
  }
  std::vector<float> out(count);
  if (t.type == static_cast<int>(TfliteType::kFloat32)) {
    std::memcpy(out.data(), t.data.data(), count * 4);
    return out;
  }
  // Per-channel scales run along quantized_dimension: the stride of that axis
  // and its size give each element's channel.
  const auto& q = t.quantization;
  std::size_t inner = 1, channels = 1;
  if (q.scale.size() > 1) {
    const int dim = q.quantized_dimension;
    if (dim < 0 || dim >= static_cast<int>(t.shape.size()) || t.shape[dim] != static_cast<int>(q.scale.size())) {
      fail(fmt::format("{} scales do not match axis {} of its shape", q.scale.size(), dim));
    }
    for (std::size_t d = dim + 1; d < t.shape.size(); ++d) inner *= t.shape[d];
    channels = q.scale.size();
  }
  if (q.scale.empty() && t.type != static_cast<int>(TfliteType::kInt32)) fail("quantised tensor without a scale");
  if (!q.zero_point.empty() && q.zero_point.size() != q.scale.size()) fail("zero_point and scale differ in length");
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t c = channels > 1 ? (i / inner) % channels : 0;
    double raw = 0;
    switch (static_cast<TfliteType>(t.type)) {
      case TfliteType::kUInt8:
        raw = t.data[i];
        break;
      case TfliteType::kInt8:
        raw = static_cast<std::int8_t>(t.data[i]);
        break;
      default: {
        std::int32_t v;
        std::memcpy(&v, t.data.data() + 4 * i, 4);
        raw = v;
      }
    }
    if (q.scale.empty()) {
      out[i] = static_cast<float>(raw);
    } else {
      const double zero = q.zero_point.empty() ? 0.0 : static_cast<double>(q.zero_point[c]);
      out[i] = static_cast<float>((raw - zero) * q.scale[c]);
    }
  }
  return out;
}

}  // namespace asbuilt

namespace asbuilt {

nlohmann::json TfliteGraphToJson(const TfliteModel& model) {
  nlohmann::json tensors = nlohmann::json::array();
  for (const TfliteTensor& t : model.tensors) {
    const bool kept = t.data.size() <= kTfliteSmallConstantBytes;
    nlohmann::json j = {{"name", t.name}, {"shape", t.shape}, {"type", t.type}};
    if (t.quantization.scale.size() == 1) {  // Per-channel scales belong to filters only.
      j["scale"] = t.quantization.scale;
      j["zero_point"] = t.quantization.zero_point;
      j["quantized_dimension"] = t.quantization.quantized_dimension;
    }
    if (kept && !t.data.empty()) j["data"] = t.data;
    tensors.push_back(std::move(j));
  }
  nlohmann::json operators = nlohmann::json::array();
  for (const TfliteOperator& op : model.operators) {
    const TfliteOptions& o = op.options;
    operators.push_back({{"code", op.builtin_code},
                         {"inputs", op.inputs},
                         {"outputs", op.outputs},
                         {"padding_same", o.padding_same},
                         {"stride", {o.stride_w, o.stride_h}},
                         {"dilation", {o.dilation_w, o.dilation_h}},
                         {"depth_multiplier", o.depth_multiplier},
                         {"filter", {o.filter_w, o.filter_h}},
                         {"activation", o.activation},
                         {"axis", o.axis},
                         {"num_splits", o.num_splits},
                         {"align_corners", o.align_corners},
                         {"half_pixel_centers", o.half_pixel_centers},
                         {"keep_dims", o.keep_dims}});
  }
  return {{"description", model.description},
          {"tensors", tensors},
          {"operators", operators},
          {"inputs", model.inputs},
          {"outputs", model.outputs}};
}

TfliteModel TfliteGraphFromJson(const nlohmann::json& graph, const std::string& file) {
  TfliteModel model;
  model.file = file;
  try {
    model.description = graph.at("description").get<std::string>();
    for (const nlohmann::json& j : graph.at("tensors")) {
      TfliteTensor t;
      t.name = j.at("name").get<std::string>();
      t.shape = j.at("shape").get<std::vector<int>>();
      t.type = j.at("type").get<int>();
      if (j.contains("scale")) {
        t.quantization.scale = j.at("scale").get<std::vector<float>>();
        t.quantization.zero_point = j.at("zero_point").get<std::vector<std::int64_t>>();
        t.quantization.quantized_dimension = j.at("quantized_dimension").get<int>();
      }
      if (j.contains("data")) t.data = j.at("data").get<std::vector<std::uint8_t>>();
      model.tensors.push_back(std::move(t));
    }
    const int n = static_cast<int>(model.tensors.size());
    auto check_indices = [&](const std::vector<int>& indices, const std::string& field) {
      for (int i : indices) {
        if (i < -1 || i >= n) {
          throw InputError(file, field, fmt::format("tensor index {} out of range (0..{})", i, n - 1));
        }
      }
    };
    for (const nlohmann::json& j : graph.at("operators")) {
      TfliteOperator op;
      TfliteOptions& o = op.options;
      op.builtin_code = j.at("code").get<int>();
      op.inputs = j.at("inputs").get<std::vector<int>>();
      op.outputs = j.at("outputs").get<std::vector<int>>();
      const std::string field = fmt::format("graph.operators[{}]", model.operators.size());
      check_indices(op.inputs, field + ".inputs");
      check_indices(op.outputs, field + ".outputs");
      o.padding_same = j.at("padding_same").get<bool>();
      o.stride_w = j.at("stride").at(0).get<int>(), o.stride_h = j.at("stride").at(1).get<int>();
      o.dilation_w = j.at("dilation").at(0).get<int>(), o.dilation_h = j.at("dilation").at(1).get<int>();
      o.depth_multiplier = j.at("depth_multiplier").get<int>();
      o.filter_w = j.at("filter").at(0).get<int>(), o.filter_h = j.at("filter").at(1).get<int>();
      o.activation = j.at("activation").get<int>();
      o.axis = j.at("axis").get<int>();
      o.num_splits = j.at("num_splits").get<int>();
      o.align_corners = j.at("align_corners").get<bool>();
      o.half_pixel_centers = j.at("half_pixel_centers").get<bool>();
      o.keep_dims = j.at("keep_dims").get<bool>();
      model.operators.push_back(std::move(op));
    }
    model.inputs = graph.at("inputs").get<std::vector<int>>();
    model.outputs = graph.at("outputs").get<std::vector<int>>();
    check_indices(model.inputs, "graph.inputs");
    check_indices(model.outputs, "graph.outputs");
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "graph", e.what());
  }
  return model;
}

}  // namespace asbuilt
