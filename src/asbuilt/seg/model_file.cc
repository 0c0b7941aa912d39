#include "asbuilt/seg/model_file.h"

#include <cmath>
#include <cstring>
#include <set>
#include <string>

#include <fmt/format.h>

#include "asbuilt/formats/safetensors.h"
#include "asbuilt/seg/model_io.h"
#include "asbuilt/seg/tflite_segmenter.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

constexpr const char* kMetaKey = "asbuilt_meta";

SafeTensor ToSafeTensor(const torch::Tensor& value) {
  torch::Tensor t = value.detach().to(torch::kCPU).contiguous();
  SafeTensor out;
  if (t.scalar_type() == torch::kFloat32) {
    out.dtype = "F32";
  } else if (t.scalar_type() == torch::kInt64) {
    out.dtype = "I64";
  } else {
    t = t.to(torch::kFloat32);
    out.dtype = "F32";
  }
  out.shape.assign(t.sizes().begin(), t.sizes().end());
  out.data.resize(static_cast<size_t>(t.numel()) * t.element_size());
  if (!out.data.empty()) std::memcpy(out.data.data(), t.data_ptr(), out.data.size());
  return out;
}

// A view of the tensor's bytes as a LibTorch tensor of its dtype (copied).
torch::Tensor FromSafeTensor(const SafeTensor& t, const std::string& file, const std::string& name) {
  torch::ScalarType type;
  if (t.dtype == "F32") {
    type = torch::kFloat32;
  } else if (t.dtype == "F16") {
    type = torch::kFloat16;
  } else if (t.dtype == "BF16") {
    type = torch::kBFloat16;
  } else if (t.dtype == "I64") {
    type = torch::kInt64;
  } else {
    throw InputError(file, name + ".dtype",
                     fmt::format("{} cannot hold SegFormer weights (F32, F16, BF16, I64)", t.dtype));
  }
  torch::Tensor out = torch::empty(t.shape, torch::TensorOptions().dtype(type));
  if (!t.data.empty()) std::memcpy(out.data_ptr(), t.data.data(), t.data.size());
  return out;
}

}  // namespace

SegmenterInfo ExportModel(const fs::path& checkpoint, const fs::path& out_safetensors) {
  nlohmann::json meta = ReadCheckpointMeta(checkpoint);
  SegmenterInfo info = InfoFromMeta(meta, checkpoint.string());
  Segformer model(info.config);
  LoadWeights(checkpoint, *model, nullptr, /*strict=*/true);
  SafeTensorsFile file;
  for (const auto& p : model->named_parameters()) file.tensors[p.key()] = ToSafeTensor(p.value());
  for (const auto& b : model->named_buffers()) file.tensors[b.key()] = ToSafeTensor(b.value());
  file.metadata[kMetaKey] = meta.dump();
  WriteSafeTensors(out_safetensors, file);
  return info;
}

SegmenterInfo ImportModel(const fs::path& in, const fs::path& out_checkpoint) {
  const std::string file = in.string();
  SafeTensorsFile st = ReadSafeTensors(in);
  auto m = st.metadata.find(kMetaKey);
  if (m == st.metadata.end()) {
    throw InputError(file, std::string("__metadata__.") + kMetaKey,
                     "missing: the checkpoint metadata JSON (format, config, scale, crop) is needed "
                     "(tools/pytorch/asbuilt_segformer.py writes it)");
  }
  nlohmann::json meta = nlohmann::json::parse(m->second, nullptr, /*allow_exceptions=*/false);
  if (meta.is_discarded() || !meta.is_object()) {
    throw InputError(file, std::string("__metadata__.") + kMetaKey, "not a JSON object");
  }
  if (meta.value("format", "") != kCheckpointFormat) {
    throw InputError(file, std::string("__metadata__.") + kMetaKey + ".format",
                     fmt::format("expected \"{}\", got {}", kCheckpointFormat,
                                 meta.contains("format") ? meta["format"].dump() : "nothing"));
  }
  SegformerConfig config = ConfigFromMeta(meta, file);
  Segformer model(config);
  meta["parameters"] = CountParameters(*model);
  SegmenterInfo info = InfoFromMeta(meta, file);

  std::set<std::string> used;
  torch::NoGradGuard no_grad;
  auto load = [&](const std::string& name, torch::Tensor& target) {
    auto it = st.tensors.find(name);
    if (it == st.tensors.end()) throw InputError(file, name, "missing: the model's config needs this tensor");
    torch::Tensor t = FromSafeTensor(it->second, file, name);
    if (t.sizes() != target.sizes()) {
      throw InputError(
          file, name + ".shape",
          fmt::format("{} does not match the model's {}", fmt::join(t.sizes(), "x"), fmt::join(target.sizes(), "x")));
    }
    if (target.is_floating_point() != t.is_floating_point()) {
      throw InputError(file, name + ".dtype", fmt::format("{} does not suit this tensor", it->second.dtype));
    }
    if (t.is_floating_point() && !torch::isfinite(t).all().item<bool>()) {
      throw InputError(file, name, "holds NaN or infinite values");
    }
    target.copy_(t);
    used.insert(name);
  };
  for (auto& p : model->named_parameters()) load(p.key(), p.value());
  for (auto& b : model->named_buffers()) load(b.key(), b.value());
  for (const auto& [name, t] : st.tensors) {
    if (!used.count(name)) throw InputError(file, name, "not a tensor of the configured model (wrong config?)");
  }
  SaveCheckpoint(out_checkpoint, *model, nullptr, meta);
  return info;
}

namespace {

// The network a checkpoint holds, weights loaded.
std::shared_ptr<torch::nn::Module> LoadNetwork(const fs::path& path, const nlohmann::json& meta) {
  if (meta.value("format", "") == kTfliteCheckpointFormat) return LoadTfliteNet(path).ptr();
  Segformer model(ConfigFromMeta(meta, path.string()));
  LoadWeights(path, *model, nullptr, /*strict=*/true);
  return model.ptr();
}

}  // namespace

SegmenterInfo AverageModels(const std::vector<fs::path>& checkpoints, const std::vector<double>& weights_in,
                            const fs::path& out_checkpoint) {
  CheckArgument(checkpoints.size() >= 2, "AverageModels: give two or more checkpoints");
  std::vector<double> weights = weights_in;
  if (weights.empty()) weights.assign(checkpoints.size(), 1.0 / static_cast<double>(checkpoints.size()));
  CheckArgument(weights.size() == checkpoints.size(), "AverageModels: one weight per checkpoint");
  double total = 0;
  for (double w : weights) {
    CheckArgument(w >= 0, fmt::format("AverageModels: weight {} is negative", w));
    total += w;
  }
  CheckArgument(std::abs(total - 1.0) < 1e-6, fmt::format("AverageModels: the weights sum to {}, not 1", total));

  nlohmann::json meta = ReadCheckpointMeta(checkpoints[0]);
  std::shared_ptr<torch::nn::Module> mean = LoadNetwork(checkpoints[0], meta);
  torch::NoGradGuard no_grad;
  auto floating = [](const torch::Tensor& t) { return t.is_floating_point(); };
  for (auto& p : mean->named_parameters()) p.value().mul_(weights[0]);
  for (auto& b : mean->named_buffers()) {
    if (floating(b.value())) b.value().mul_(weights[0]);
  }
  for (std::size_t i = 1; i < checkpoints.size(); ++i) {
    const nlohmann::json other = ReadCheckpointMeta(checkpoints[i]);
    const nlohmann::json config = meta["config"], other_config = other["config"];
    if (other.value("format", "") != meta.value("format", "") ||
        config.value("arch", "") != other_config.value("arch", "") ||
        config.value("num_classes", 0) != other_config.value("num_classes", 0)) {
      throw InputError(checkpoints[i].string(), "asbuilt_meta.config",
                       fmt::format("holds another network than {} ({} {} against {} {})", checkpoints[0].string(),
                                   other.value("format", ""), other_config.value("arch", ""), meta.value("format", ""),
                                   config.value("arch", "")));
    }
    // Strict loading into the first's network checks every tensor's name and shape.
    std::shared_ptr<torch::nn::Module> next = LoadNetwork(checkpoints[0], meta);
    LoadWeights(checkpoints[i], *next, nullptr, /*strict=*/true);
    auto add = [&](auto&& into, auto&& from) {
      for (auto& t : into) {
        if (floating(t.value())) t.value().add_(from[t.key()], weights[i]);
      }
    };
    add(mean->named_parameters(), next->named_parameters());
    add(mean->named_buffers(), next->named_buffers());
  }
  meta.erase("history");
  meta.erase("best_miou");
  meta.erase("best_epoch");
  meta["averaged_from"] = nlohmann::json::array();
  for (std::size_t i = 0; i < checkpoints.size(); ++i) {
    meta["averaged_from"].push_back({{"checkpoint", checkpoints[i].filename().string()}, {"weight", weights[i]}});
  }
  SaveCheckpoint(out_checkpoint, *mean, nullptr, meta);
  return ReadSegmenterInfo(out_checkpoint);
}

}  // namespace asbuilt
