#include "asbuilt/seg/model_file.h"

#include <cstring>
#include <limits>
#include <filesystem>
#include <string>

#include <unistd.h>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/formats/safetensors.h"
#include "asbuilt/seg/model_io.h"
#include "asbuilt/seg/segformer.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

const fs::path kTestData = fs::path(ASBUILT_SOURCE_DIR) / "src/asbuilt/seg/testdata";

fs::path TempDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / fmt::format("asbuilt_model_file_test_{}_{}", ::getpid(), name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

torch::Tensor ToTensor(const SafeTensor& t) {
  EXPECT_EQ(t.dtype, "F32");
  torch::Tensor out = torch::empty(t.shape, torch::kFloat32);
  std::memcpy(out.data_ptr(), t.data.data(), t.data.size());
  return out;
}

Segformer LoadModel(const fs::path& checkpoint) {
  Segformer model(ConfigFromMeta(ReadCheckpointMeta(checkpoint), checkpoint.string()));
  LoadWeights(checkpoint, *model, nullptr, /*strict=*/true);
  model->eval();
  return model;
}

std::string ImportError(const fs::path& file, const fs::path& out) {
  try {
    ImportModel(file, out);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// The fixture was written by tools/pytorch/make_twin_fixture.py: the Python
// twin's logits for one input. Equal logits here mean the two networks are
// the same function, so weights trained in Python mean the same in C++.
TEST(ModelFile, PythonTwinAndCppGiveTheSameLogits) {
  fs::path dir = TempDir("twin");
  SegmenterInfo info = ImportModel(kTestData / "twin_model.safetensors", dir / "twin.pt");
  EXPECT_EQ(info.config.arch, "twin-test");
  EXPECT_EQ(info.parameters, 61612);
  SafeTensorsFile io = ReadSafeTensors(kTestData / "twin_io.safetensors");
  torch::Tensor x = ToTensor(io.tensors.at("input"));
  torch::Tensor expected = ToTensor(io.tensors.at("logits"));
  Segformer model = LoadModel(dir / "twin.pt");
  torch::NoGradGuard no_grad;
  torch::Tensor logits = model->forward(x);
  ASSERT_EQ(logits.sizes(), expected.sizes());
  const double max_diff = (logits - expected).abs().max().item<double>();
  EXPECT_LT(max_diff, 1e-4) << "logit range " << expected.abs().max().item<double>();
  EXPECT_GT(expected.abs().max().item<double>(), 0.1) << "fixture logits should not be trivial";
}

// A SegFormer small enough to save and load in milliseconds.
SegformerConfig SmallConfig() {
  SegformerConfig config = SegformerConfigFor("tiny");
  config.embed_dims = {8, 16, 24, 32};
  config.num_heads = {1, 2, 2, 4};
  config.decoder_dim = 16;
  return config;
}

TEST(ModelFile, ExportThenImportRoundTripsEveryTensorAndTheMetadata) {
  fs::path dir = TempDir("roundtrip");
  SegformerConfig config = SmallConfig();
  config.arch = "small-test";
  Segformer model(config);
  nlohmann::json meta = {{"format", kCheckpointFormat},
                         {"config", ConfigToJson(config)},
                         {"scale", {64, 48}},
                         {"crop", {32, 32}},
                         {"epoch", 4},
                         {"note", "kept"}};
  SaveCheckpoint(dir / "a.pt", *model, nullptr, meta);
  SegmenterInfo exported = ExportModel(dir / "a.pt", dir / "a.safetensors");
  EXPECT_EQ(exported.epoch, 4);
  SegmenterInfo imported = ImportModel(dir / "a.safetensors", dir / "b.pt");
  EXPECT_EQ(imported.metadata.at("note"), "kept");
  EXPECT_EQ(imported.scale_width_px, 64);
  Segformer back = LoadModel(dir / "b.pt");
  auto a = model->named_parameters(), b = back->named_parameters();
  ASSERT_EQ(a.size(), b.size());
  for (const auto& p : a) EXPECT_TRUE(torch::equal(p.value(), b[p.key()])) << p.key();
}

TEST(ModelFile, ImportRejectsFilesThatDoNotFitNamingTheTensor) {
  fs::path dir = TempDir("reject");
  SafeTensorsFile good = ReadSafeTensors(kTestData / "twin_model.safetensors");

  SafeTensorsFile no_meta = good;
  no_meta.metadata.clear();
  WriteSafeTensors(dir / "no_meta.safetensors", no_meta);
  EXPECT_NE(ImportError(dir / "no_meta.safetensors", dir / "x.pt").find("__metadata__.asbuilt_meta"),
            std::string::npos);

  SafeTensorsFile missing = good;
  missing.tensors.erase("decoder.classifier.weight");
  WriteSafeTensors(dir / "missing.safetensors", missing);
  EXPECT_NE(ImportError(dir / "missing.safetensors", dir / "x.pt").find("decoder.classifier.weight"),
            std::string::npos);

  SafeTensorsFile extra = good;
  extra.tensors["head.extra"] = good.tensors.at("decoder.classifier.bias");
  WriteSafeTensors(dir / "extra.safetensors", extra);
  EXPECT_NE(ImportError(dir / "extra.safetensors", dir / "x.pt").find("head.extra"), std::string::npos);

  SafeTensorsFile reshaped = good;
  reshaped.tensors["decoder.classifier.bias"].shape = {2, 2};
  WriteSafeTensors(dir / "reshaped.safetensors", reshaped);
  EXPECT_NE(ImportError(dir / "reshaped.safetensors", dir / "x.pt").find("decoder.classifier.bias.shape"),
            std::string::npos);

  SafeTensorsFile nan = good;
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan.tensors["decoder.classifier.bias"].data.data(), &q, 4);
  WriteSafeTensors(dir / "nan.safetensors", nan);
  EXPECT_NE(ImportError(dir / "nan.safetensors", dir / "x.pt").find("NaN"), std::string::npos);

  EXPECT_FALSE(fs::exists(dir / "x.pt")) << "no checkpoint is written for a rejected file";
}

TEST(ModelFile, AverageIsTheWeightedMeanOfEveryTensor) {
  fs::path dir = TempDir("average");
  SegformerConfig config = SmallConfig();
  nlohmann::json meta = {{"format", kCheckpointFormat},
                         {"config", ConfigToJson(config)},
                         {"scale", {64, 48}},
                         {"crop", {32, 32}},
                         {"epoch", 4},
                         {"best_miou", 0.5}};
  torch::manual_seed(1);
  Segformer a(config), b(config);
  SaveCheckpoint(dir / "a.pt", *a, nullptr, meta);
  SaveCheckpoint(dir / "b.pt", *b, nullptr, meta);
  SegmenterInfo info = AverageModels({dir / "a.pt", dir / "b.pt"}, {0.25, 0.75}, dir / "mean.pt");
  EXPECT_FALSE(info.metadata.contains("best_miou"));  // Measured on another network.
  EXPECT_EQ(info.metadata.at("averaged_from").size(), 2u);
  Segformer mean = LoadModel(dir / "mean.pt");
  auto pa = a->named_parameters(), pb = b->named_parameters();
  for (const auto& p : mean->named_parameters()) {
    EXPECT_TRUE(torch::allclose(p.value(), 0.25 * pa[p.key()] + 0.75 * pb[p.key()], 1e-5, 1e-6)) << p.key();
  }
  // Another network, or weights that are not a mean, are refused.
  SegformerConfig other = config;
  other.decoder_dim = 32;
  Segformer c(other);
  nlohmann::json other_meta = meta;
  other_meta["config"] = ConfigToJson(other);
  SaveCheckpoint(dir / "c.pt", *c, nullptr, other_meta);
  EXPECT_THROW(AverageModels({dir / "a.pt", dir / "c.pt"}, {}, dir / "bad.pt"), InputError);
  EXPECT_THROW(AverageModels({dir / "a.pt", dir / "b.pt"}, {0.5, 0.6}, dir / "bad.pt"), InvalidArgument);
  EXPECT_FALSE(fs::exists(dir / "bad.pt"));
}

}  // namespace
}  // namespace asbuilt
