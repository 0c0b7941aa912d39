// bench_seg [RESULTS.md] [ARCH] — SegFormer speed in C++ (LibTorch) vs Python
// PyTorch on the same machine, same threads, same architecture, same run.
//   inference: one 640×480 image, eval mode, logits upsampled, argmax
//   training:  batch 2 at 256² and 512², forward + cross-entropy + backward + AdamW
// Ratio = Python time / C++ time (≥ 1.0: C++ no slower). Peak RSS of each process.
// Set OMP_WAIT_POLICY=passive on a loaded machine (see docs/seg.md).

#include <cstdio>
#include <string>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "asbuilt/seg/segformer.h"
#include "bench/bench_util.h"

namespace {
namespace F = torch::nn::functional;
using asbuilt::bench::MedianSeconds;

std::string RunPython(const std::string& arch, int threads, int repeats) {
  std::string cmd = fmt::format("/usr/bin/python3 {}/bench/seg/segformer_bench.py {} {} {} 2>/dev/null",
                                ASBUILT_SOURCE_DIR, arch, threads, repeats);
  std::string out;
  if (std::FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[4096];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    if (::pclose(p) != 0) out.clear();
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string arch = argc > 2 ? argv[2] : "b0";
  const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int repeats = 5;
  asbuilt::SetTorchThreads(threads);
  torch::manual_seed(0);
  asbuilt::Segformer model(asbuilt::SegformerConfigFor(arch, 4));

  // Inference, 640×480.
  model->eval();
  torch::Tensor x = torch::randn({1, 3, 480, 640});
  double infer_s;
  {
    torch::NoGradGuard no_grad;
    auto run = [&] {
      F::interpolate(model->forward(x), F::InterpolateFuncOptions()
                                            .size(std::vector<int64_t>{480, 640})
                                            .mode(torch::kBilinear)
                                            .align_corners(false))
          .argmax(1);
    };
    run();
    infer_s = MedianSeconds(repeats, run);
  }
  // Training steps.
  model->train();
  torch::optim::AdamW opt(model->parameters(), torch::optim::AdamWOptions(1e-4).weight_decay(1e-3));
  double train_ips[2];
  const int sides[2] = {256, 512};
  for (int i = 0; i < 2; ++i) {
    const int side = sides[i];
    torch::Tensor xb = torch::randn({2, 3, side, side}), yb = torch::randint(0, 4, {2, side, side});
    auto step = [&] {
      torch::Tensor logits = F::interpolate(model->forward(xb), F::InterpolateFuncOptions()
                                                                    .size(std::vector<int64_t>{side, side})
                                                                    .mode(torch::kBilinear)
                                                                    .align_corners(false));
      torch::Tensor loss = F::cross_entropy(logits, yb, F::CrossEntropyFuncOptions().ignore_index(255));
      opt.zero_grad();
      loss.backward();
      opt.step();
    };
    step();
    train_ips[i] = 2.0 / MedianSeconds(repeats, step);
  }
  const double cpp_rss = asbuilt::bench::PeakRssMiB();

  std::string py_text = RunPython(arch, threads, repeats);
  nlohmann::json py = nlohmann::json::parse(py_text, nullptr, false);
  const bool have_py = !py.is_discarded() && py.is_object();

  std::string md = fmt::format(
      "## seg — SegFormer-{} speed, C++ LibTorch vs Python PyTorch\n\n"
      "{} threads, median of {} runs, batch 2 for training (forward + cross-entropy + backward + AdamW),\n"
      "one 640×480 image for inference (eval, upsampled logits, argmax). Same architecture ({} parameters)\n"
      "in both, same process order, same machine; ratio = Python time / C++ time (target ≥ 1.0).\n\n"
      "| measure | C++ | Python | ratio |\n|---|---|---|---|\n",
      arch, threads, repeats, asbuilt::CountParameters(*model));
  auto row = [&](const std::string& name, double cpp, const char* key, bool time_like, const char* unit) {
    if (have_py && py.contains(key)) {
      double p = py[key].get<double>();
      double ratio = time_like ? p / cpp : cpp / p;
      md += fmt::format("| {} | {:.3f} {} | {:.3f} {} | {:.2f} |\n", name, cpp, unit, p, unit, ratio);
    } else {
      md += fmt::format("| {} | {:.3f} {} | n/a | n/a |\n", name, cpp, unit);
    }
  };
  row("inference latency, 640×480", infer_s, "infer_640x480_s", true, "s");
  row("training, 256×256", train_ips[0], "train_256_images_per_s", false, "img/s");
  row("training, 512×512", train_ips[1], "train_512_images_per_s", false, "img/s");
  md += fmt::format("| peak RSS | {:.0f} MiB | {} | |\n", cpp_rss,
                    have_py ? fmt::format("{:.0f} MiB", py["peak_rss_mib"].get<double>()) : "n/a");
  if (!have_py) md += "\nPython PyTorch not found (`scripts/install-deps.sh --bench` installs python3-torch).\n";
  md += fmt::format("\nLibTorch {}.{}.{}{}.\n", TORCH_VERSION_MAJOR, TORCH_VERSION_MINOR, TORCH_VERSION_PATCH,
                    have_py ? ", Python torch " + py.value("torch", std::string("?")) : "");
  asbuilt::bench::WriteSection(asbuilt::bench::ResultsPath(argc, argv, "seg"), md);
  return 0;
}
