// The host side of the LibTorch plugin (torch_plugin.h): seg's public entry
// points, forwarded to libasbuilt_torch.so, loaded on first use. Defines only
// symbols that asbuilt_seg_torch also defines (see torch_plugin.h).
#include "asbuilt/seg/torch_plugin.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>

#include <fmt/format.h>
#include <fmt/std.h>
#include <spdlog/spdlog.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

constexpr const char* kPluginName = "libasbuilt_torch.so";

fs::path PluginPath() {
  if (const char* env = std::getenv("ASBUILT_TORCH_PLUGIN"); env && *env) return env;
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    fs::path beside = exe.parent_path() / kPluginName;
    if (fs::exists(beside, ec)) return beside;
  }
#ifdef ASBUILT_TORCH_PLUGIN_BUILD_PATH
  if (fs::exists(ASBUILT_TORCH_PLUGIN_BUILD_PATH, ec)) return ASBUILT_TORCH_PLUGIN_BUILD_PATH;
#endif
  return ec ? fs::path(kPluginName) : exe.parent_path() / kPluginName;
}

const TorchPluginApi* Load() {
  const fs::path path = PluginPath();
  auto fail = [&](const std::string& why) {
    return Error(
        fmt::format("segmentation needs {} (asbuilt's LibTorch part) and {} could not be used: {}. Build it "
                    "(cmake --build BUILD --target asbuilt_torch; it goes beside the asbuilt binary) or set "
                    "ASBUILT_TORCH_PLUGIN to its path",
                    kPluginName, path.string(), why));
  };
  spdlog::debug("loading LibTorch plugin {}", path.string());
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) throw fail(::dlerror());
  using Entry = const TorchPluginApi* (*)();
  auto entry = reinterpret_cast<Entry>(::dlsym(handle, "asbuilt_torch_plugin_api"));
  if (entry == nullptr) throw fail("no asbuilt_torch_plugin_api symbol");
  const TorchPluginApi* api = entry();
  if (api == nullptr || api->abi != kTorchPluginAbi || api->size != sizeof(TorchPluginApi)) {
    throw fail(fmt::format("plugin ABI {} does not match this asbuilt's {} (rebuild both)", api ? api->abi : 0,
                           kTorchPluginAbi));
  }
  return api;  // The handle stays open for the life of the process.
}

// Loads once; a failed load is retried on the next call (and fails the same way).
const TorchPluginApi& Plugin() {
  static std::mutex mutex;
  static const TorchPluginApi* api = nullptr;
  std::lock_guard lock(mutex);
  if (api == nullptr) api = Load();
  return *api;
}

}  // namespace

std::unique_ptr<Segmenter> LoadSegmenter(const fs::path& path, const SegmentOptions& options) {
  return Plugin().load_segmenter(path, options);
}

SegmenterInfo ReadSegmenterInfo(const fs::path& path) { return Plugin().read_segmenter_info(path); }

bool SegmenterAvailable() {
  try {
    Plugin();
    return true;
  } catch (const Error& e) {
    spdlog::debug("{}", e.what());
    return false;
  }
}

TrainSummary TrainSegmenter(const TrainOptions& options, const ProgressCallback& progress, std::stop_token stop) {
  return Plugin().train_segmenter(options, progress, std::move(stop));
}

SegmenterInfo ExportModel(const fs::path& checkpoint, const fs::path& out_safetensors) {
  return Plugin().export_model(checkpoint, out_safetensors);
}

SegmenterInfo ImportModel(const fs::path& safetensors, const fs::path& out_checkpoint) {
  return Plugin().import_model(safetensors, out_checkpoint);
}

SegmenterInfo AverageModels(const std::vector<fs::path>& checkpoints, const std::vector<double>& weights,
                            const fs::path& out_checkpoint) {
  return Plugin().average_models(checkpoints, weights, out_checkpoint);
}

}  // namespace asbuilt
