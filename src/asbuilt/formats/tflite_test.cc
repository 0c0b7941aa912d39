#include "asbuilt/formats/tflite.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

const fs::path kTeachers = fs::path(ASBUILT_SHARED_DATA_DIR) / "ade20k-teachers";
const fs::path kDeeplab = kTeachers / "deeplabv3_mnv2_ade20k32_uint8.tflite";
const fs::path kMosaic = kTeachers / "mosaic_r4_ade20k32_uint8.tflite";

#define SKIP_WITHOUT_TEACHERS() \
  if (!fs::exists(kDeeplab)) GTEST_SKIP() << "shared data not present: " << kDeeplab

// The message of the InputError that parsing `bytes` throws ("" if none).
std::string ParseError(const std::string& bytes) {
  try {
    ParseTflite(bytes, "bad.tflite");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Tflite, ReadsTheDeeplabGraph) {
  SKIP_WITHOUT_TEACHERS();
  const TfliteModel m = ReadTflite(kDeeplab);
  ASSERT_EQ(m.operators.size(), 77u);
  ASSERT_EQ(m.tensors.size(), 202u);
  ASSERT_EQ(m.inputs.size(), 1u);
  const TfliteTensor& input = m.tensors[m.inputs[0]];
  EXPECT_EQ(input.name, "MobilenetV2/MobilenetV2/input");
  EXPECT_EQ(input.shape, (std::vector<int>{1, 512, 512, 3}));
  EXPECT_EQ(input.type, static_cast<int>(TfliteType::kUInt8));
  ASSERT_EQ(input.quantization.scale.size(), 1u);
  EXPECT_FLOAT_EQ(input.quantization.scale[0], 1.f / 128.f);
  EXPECT_EQ(input.quantization.zero_point[0], 128);
  // The first operator: a 3×3 stride-2 convolution, 3 → 32 channels; its
  // ReLU6 is the output's quantisation range [0, 6], not a fused activation.
  const TfliteOperator& conv = m.operators[0];
  EXPECT_EQ(conv.builtin_code, static_cast<int>(TfliteOp::kConv2d));
  EXPECT_EQ(conv.options.stride_w, 2);
  EXPECT_TRUE(conv.options.padding_same);
  EXPECT_EQ(conv.options.activation, 0);
  const TfliteQuantization& relu6 = m.tensors[conv.outputs[0]].quantization;
  EXPECT_EQ(relu6.zero_point[0], 0);
  EXPECT_NEAR(relu6.scale[0] * 255, 6.0, 1e-3);
  EXPECT_EQ(m.tensors[conv.inputs[1]].shape, (std::vector<int>{32, 3, 3, 3}));
  EXPECT_EQ(m.operators.back().builtin_code, static_cast<int>(TfliteOp::kArgMax));
}

TEST(Tflite, DequantisesPerChannelWeightsAndBiases) {
  SKIP_WITHOUT_TEACHERS();
  const TfliteModel m = ReadTflite(kDeeplab);
  const int filter = m.operators[0].inputs[1];
  const TfliteTensor& t = m.tensors[filter];
  const std::vector<float> w = DequantizedData(m, filter);
  ASSERT_EQ(w.size(), 32u * 27u);
  // Element 0 by hand: (q − zero point) · scale of its channel.
  const float scale = t.quantization.scale[0];
  const auto zero = t.quantization.zero_point.empty() ? 0 : t.quantization.zero_point[0];
  EXPECT_FLOAT_EQ(w[0], (static_cast<float>(t.data[0]) - zero) * scale);
  const std::vector<float> bias = DequantizedData(m, m.operators[0].inputs[2]);
  EXPECT_EQ(bias.size(), 32u);
  float largest = 0;
  for (float b : bias) largest = std::max(largest, std::abs(b));
  EXPECT_GT(largest, 0.f);
  EXPECT_LT(largest, 100.f);  // Folded batch-norm biases, not raw int32 counts.
}

TEST(Tflite, ReadsMosaicsSplitsAndPools) {
  if (!fs::exists(kMosaic)) GTEST_SKIP() << "shared data not present: " << kMosaic;
  const TfliteModel m = ReadTflite(kMosaic);
  int splits = 0, pools = 0;
  for (const TfliteOperator& op : m.operators) {
    if (op.builtin_code == static_cast<int>(TfliteOp::kSplit)) ++splits;
    if (op.builtin_code == static_cast<int>(TfliteOp::kAveragePool2d)) {
      ++pools;
      EXPECT_GT(op.options.filter_w, 1);
    }
  }
  EXPECT_EQ(splits, 3);
  EXPECT_EQ(pools, 3);
}

TEST(Tflite, RefusesWhatIsNotAModel) {
  EXPECT_NE(ParseError(""), "");
  EXPECT_NE(ParseError("{\"version\": 1}").find("not a TensorFlow Lite model"), std::string::npos);
  // A header that claims TFLite and offsets that point nowhere.
  std::string fake("\xff\xff\xff\x7fTFL3", 8);
  EXPECT_NE(ParseError(fake).find("past the end"), std::string::npos) << ParseError(fake);
}

TEST(Tflite, RefusesATruncatedModelNamingTheField) {
  SKIP_WITHOUT_TEACHERS();
  const std::string bytes = ReadFile(kDeeplab);
  for (std::size_t keep : {std::size_t{16}, bytes.size() / 3, bytes.size() - 100}) {
    const std::string message = ParseError(bytes.substr(0, keep));
    EXPECT_NE(message, "") << "kept " << keep << " bytes";
    EXPECT_NE(message.find("bad.tflite"), std::string::npos) << message;
  }
}

TEST(Tflite, RefusesAFileThatIsMissing) { EXPECT_THROW(ReadTflite("/nonexistent/model.tflite"), InputError); }

TEST(Tflite, GraphJsonKeepsTheTopologyAndLeavesTheFiltersOut) {
  SKIP_WITHOUT_TEACHERS();
  const TfliteModel m = ReadTflite(kDeeplab);
  const nlohmann::json j = TfliteGraphToJson(m);
  const TfliteModel back = TfliteGraphFromJson(nlohmann::json::parse(j.dump()), "ckpt.pt");
  ASSERT_EQ(back.operators.size(), m.operators.size());
  ASSERT_EQ(back.tensors.size(), m.tensors.size());
  EXPECT_EQ(back.inputs, m.inputs);
  EXPECT_EQ(back.outputs, m.outputs);
  for (std::size_t k = 0; k < m.operators.size(); ++k) {
    EXPECT_EQ(back.operators[k].builtin_code, m.operators[k].builtin_code);
    EXPECT_EQ(back.operators[k].inputs, m.operators[k].inputs);
    EXPECT_EQ(back.operators[k].options.stride_h, m.operators[k].options.stride_h);
    EXPECT_EQ(back.operators[k].options.dilation_w, m.operators[k].options.dilation_w);
    EXPECT_EQ(back.operators[k].options.align_corners, m.operators[k].options.align_corners);
  }
  std::size_t kept_bytes = 0;
  for (std::size_t t = 0; t < m.tensors.size(); ++t) {
    EXPECT_EQ(back.tensors[t].shape, m.tensors[t].shape);
    if (m.tensors[t].data.size() <= kTfliteSmallConstantBytes) EXPECT_EQ(back.tensors[t].data, m.tensors[t].data);
    kept_bytes += back.tensors[t].data.size();
  }
  EXPECT_LT(kept_bytes, 2000u);  // The 2.3 M weights are not in it.
  const TfliteTensor& filter = back.tensors[back.operators[0].inputs[1]];
  EXPECT_TRUE(filter.data.empty());
}

TEST(Tflite, GraphJsonRefusesATensorIndexOutOfRange) {
  nlohmann::json j = {{"description", ""},
                      {"tensors", nlohmann::json::array()},
                      {"operators", nlohmann::json::array({{{"code", 3}, {"inputs", {0, 7}}, {"outputs", {1}}}})},
                      {"inputs", {0}},
                      {"outputs", {1}}};
  try {
    TfliteGraphFromJson(j, "ckpt.pt");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ckpt.pt"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("graph.operators[0]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(TfliteGraphFromJson(nlohmann::json::object(), "ckpt.pt"), InputError);
}

}  // namespace
}  // namespace asbuilt
