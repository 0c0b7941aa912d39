#include "asbuilt/seg/model_io.h"

#include <cstring>
#include <string>

#include <fmt/format.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;

nlohmann::json ConfigToJson(const SegformerConfig& c) {
  return {{"arch", c.arch},
          {"in_channels", c.in_channels},
          {"embed_dims", c.embed_dims},
          {"num_heads", c.num_heads},
          {"depths", c.depths},
          {"sr_ratios", c.sr_ratios},
          {"patch_sizes", c.patch_sizes},
          {"strides", c.strides},
          {"mlp_ratio", c.mlp_ratio},
          {"decoder_dim", c.decoder_dim},
          {"num_classes", c.num_classes},
          {"drop_path_rate", c.drop_path_rate},
          {"decoder_dropout", c.decoder_dropout}};
}

SegformerConfig ConfigFromMeta(const nlohmann::json& meta, const std::string& file) {
  try {
    const nlohmann::json& j = meta.at("config");
    SegformerConfig c;
    c.arch = j.at("arch").get<std::string>();
    c.in_channels = j.at("in_channels").get<int>();
    c.embed_dims = j.at("embed_dims").get<std::array<int, 4>>();
    c.num_heads = j.at("num_heads").get<std::array<int, 4>>();
    c.depths = j.at("depths").get<std::array<int, 4>>();
    c.sr_ratios = j.at("sr_ratios").get<std::array<int, 4>>();
    c.patch_sizes = j.at("patch_sizes").get<std::array<int, 4>>();
    c.strides = j.at("strides").get<std::array<int, 4>>();
    c.mlp_ratio = j.at("mlp_ratio").get<int>();
    c.decoder_dim = j.at("decoder_dim").get<int>();
    c.num_classes = j.at("num_classes").get<int>();
    c.drop_path_rate = j.value("drop_path_rate", 0.1);
    c.decoder_dropout = j.value("decoder_dropout", 0.1);
    c.Check();
    return c;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "asbuilt_meta.config", e.what());
  } catch (const InvalidArgument& e) {
    throw InputError(file, "asbuilt_meta.config", e.what());
  }
}

void SaveCheckpoint(const fs::path& path, torch::nn::Module& model, torch::optim::Optimizer* optimizer,
                    const nlohmann::json& meta) {
  torch::serialize::OutputArchive archive;
  std::string text = meta.dump();
  torch::Tensor bytes = torch::empty({static_cast<int64_t>(text.size())}, torch::kUInt8);
  std::memcpy(bytes.data_ptr(), text.data(), text.size());
  archive.write("asbuilt_meta", bytes);
  for (const auto& p : model.named_parameters()) archive.write("model/" + p.key(), p.value().detach());
  for (const auto& b : model.named_buffers()) archive.write("model/" + b.key(), b.value(), /*is_buffer=*/true);
  if (optimizer != nullptr) {
    torch::serialize::OutputArchive opt;
    optimizer->save(opt);
    archive.write("optimizer", opt);
  }
  fs::create_directories(path.parent_path().empty() ? fs::path(".") : path.parent_path());
  AtomicFile out(path);
  archive.save_to(out.temp_path().string());
  out.Commit();
}

namespace {

torch::serialize::InputArchive OpenArchive(const fs::path& path) {
  if (!fs::exists(path)) throw InputError(path.string(), "", "file not found");
  torch::serialize::InputArchive archive;
  try {
    archive.load_from(path.string());
  } catch (const std::exception& e) {
    std::string why = e.what();
    why = why.substr(0, why.find('\n'));  // LibTorch appends a backtrace.
    throw InputError(path.string(), "", fmt::format("not a LibTorch archive ({})", why));
  }
  return archive;
}

}  // namespace

nlohmann::json ReadCheckpointMeta(const fs::path& path) {
  torch::serialize::InputArchive archive = OpenArchive(path);
  torch::Tensor bytes;
  if (!archive.try_read("asbuilt_meta", bytes)) {
    throw InputError(path.string(), "asbuilt_meta", "missing: not an asbuilt SegFormer checkpoint");
  }
  std::string text(static_cast<const char*>(bytes.data_ptr()), static_cast<size_t>(bytes.numel()));
  nlohmann::json meta = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (meta.is_discarded() || !meta.is_object()) throw InputError(path.string(), "asbuilt_meta", "not valid JSON");
  const std::string format = meta.value("format", "nothing");
  if (format != kCheckpointFormat && format != kTfliteCheckpointFormat) {
    throw InputError(
        path.string(), "asbuilt_meta.format",
        fmt::format("expected \"{}\" or \"{}\", got {}", kCheckpointFormat, kTfliteCheckpointFormat, format));
  }
  return meta;
}

int LoadWeights(const fs::path& path, torch::nn::Module& model, torch::optim::Optimizer* optimizer, bool strict,
                int* skipped) {
  torch::serialize::InputArchive archive = OpenArchive(path);
  torch::NoGradGuard no_grad;
  int loaded = 0, missing = 0;
  auto load_one = [&](const std::string& name, torch::Tensor& target) {
    torch::Tensor t;
    if (archive.try_read("model/" + name, t) && t.sizes() == target.sizes()) {
      target.copy_(t);
      ++loaded;
    } else {
      if (strict) {
        throw InputError(path.string(), "model/" + name,
                         t.defined() ? fmt::format("shape {} does not match the model's {}", fmt::join(t.sizes(), "x"),
                                                   fmt::join(target.sizes(), "x"))
                                     : "missing from the checkpoint");
      }
      ++missing;
    }
  };
  for (auto& p : model.named_parameters()) load_one(p.key(), p.value());
  for (auto& b : model.named_buffers()) load_one(b.key(), b.value());
  if (skipped != nullptr) *skipped = missing;
  if (optimizer != nullptr) {
    torch::serialize::InputArchive opt;
    if (archive.try_read("optimizer", opt)) optimizer->load(opt);
  }
  return loaded;
}

std::vector<cv::Mat> ClassMaps(const torch::Tensor& chw) {
  const torch::Tensor p = chw.to(torch::kFloat32).contiguous();
  std::vector<cv::Mat> out;
  for (int64_t c = 0; c < p.size(0); ++c) {
    cv::Mat m(static_cast<int>(p.size(1)), static_cast<int>(p.size(2)), CV_32FC1);
    std::memcpy(m.data, p[c].data_ptr(), m.total() * sizeof(float));
    out.push_back(m);
  }
  return out;
}

torch::Tensor ImagesToTensor(const std::vector<cv::Mat>& bgr) {
  const int h = bgr.at(0).rows, w = bgr.at(0).cols;
  torch::Tensor out = torch::empty({static_cast<int64_t>(bgr.size()), 3, h, w}, torch::kFloat32);
  // ImageNet statistics in RGB order (mmseg data_preprocessor).
  const float mean[3] = {123.675f, 116.28f, 103.53f}, inv_std[3] = {1 / 58.395f, 1 / 57.12f, 1 / 57.375f};
  for (size_t i = 0; i < bgr.size(); ++i) {
    CheckArgument(bgr[i].type() == CV_8UC3 && bgr[i].rows == h && bgr[i].cols == w,
                  "ImagesToTensor: images must be 8-bit BGR of one size");
    float* base = out[static_cast<int64_t>(i)].data_ptr<float>();
    for (int r = 0; r < h; ++r) {
      const cv::Vec3b* row = bgr[i].ptr<cv::Vec3b>(r);
      for (int c = 0; c < w; ++c) {
        for (int k = 0; k < 3; ++k) {
          base[(static_cast<size_t>(k) * h + r) * w + c] = (row[c][2 - k] - mean[k]) * inv_std[k];
        }
      }
    }
  }
  return out;
}

torch::Tensor LabelsToTensor(const std::vector<cv::Mat>& labels) {
  const int h = labels.at(0).rows, w = labels.at(0).cols;
  torch::Tensor out = torch::empty({static_cast<int64_t>(labels.size()), h, w}, torch::kInt64);
  for (size_t i = 0; i < labels.size(); ++i) {
    int64_t* base = out[static_cast<int64_t>(i)].data_ptr<int64_t>();
    for (int r = 0; r < h; ++r) {
      const std::uint8_t* row = labels[i].ptr<std::uint8_t>(r);
      for (int c = 0; c < w; ++c) base[static_cast<size_t>(r) * w + c] = row[c];
    }
  }
  return out;
}

}  // namespace asbuilt
