// bench_seg [RESULTS.md] [ARCH=b0] [REPEATS=15] — SegFormer speed in C++ (LibTorch)
// vs Python PyTorch on the same machine, same threads, same architecture,
// same run.
//   inference: one 640×480 image, eval mode, no_grad, logits upsampled, argmax
//   training:  batch 2 at 256² and 512², forward + cross-entropy + backward + AdamW
// The machine is shared and loaded, so the two sides are interleaved: the
// Python model lives in a peer process (segformer_bench.py ARCH THREADS serve)
// that runs one measurement per command while this process waits on the pipe,
// and each repetition runs C++ then Python or Python then C++ (ABBA…), so both
// see the same load drift. Ratio = Python time / C++ time (≥ 1.0: C++ no
// slower), as the median of the per-pair ratios (drift cancels within a
// pair) and as the ratio of medians; the per-pair range shows the noise.
// OMP_WAIT_POLICY defaults to passive (re-exec'd with it if unset: libgomp
// reads it at start-up); the peer inherits the same environment.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "asbuilt/seg/segformer.h"
#include "bench/bench_util.h"

namespace {
namespace F = torch::nn::functional;
using asbuilt::bench::LoadAverage1;
using asbuilt::bench::Median;

long MinorFaults() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

// Wall time of fn; adds its minor page faults to *faults.
double Seconds(const std::function<void()>& fn, long* faults) {
  const long f0 = MinorFaults();
  auto start = std::chrono::steady_clock::now();
  fn();
  double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  *faults += MinorFaults() - f0;
  return s;
}

// segformer_bench.py in serve mode, spoken to over two pipes.
class PythonPeer {
 public:
  PythonPeer(const std::string& arch, int threads) {
    int to_child[2], from_child[2];
    if (::pipe(to_child) != 0 || ::pipe(from_child) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(to_child[0], 0);
      ::dup2(from_child[1], 1);
      ::close(to_child[1]);
      ::close(from_child[0]);
      const std::string script = std::string(ASBUILT_SOURCE_DIR) + "/bench/seg/segformer_bench.py";
      const std::string t = std::to_string(threads);
      ::execl("/usr/bin/python3", "python3", script.c_str(), arch.c_str(), t.c_str(), "serve", nullptr);
      std::_Exit(127);
    }
    ::close(to_child[0]);
    ::close(from_child[1]);
    to_ = ::fdopen(to_child[1], "w");
    from_ = ::fdopen(from_child[0], "r");
    hello_ = Read();
  }
  ~PythonPeer() {
    if (to_) {
      std::fputs("quit\n", to_);
      std::fclose(to_);
    }
    if (from_) std::fclose(from_);
    if (pid_ > 0) ::waitpid(pid_, nullptr, 0);
  }
  bool ok() const { return hello_.is_object() && hello_.value("ready", false); }
  const nlohmann::json& hello() const { return hello_; }

  nlohmann::json Ask(const std::string& command) {
    std::fprintf(to_, "%s\n", command.c_str());
    std::fflush(to_);
    return Read();
  }
  double Time(const std::string& command, long* faults) {
    nlohmann::json j = Ask(command);
    if (!j.contains("s")) throw std::runtime_error("python peer: " + command + ": " + j.dump());
    *faults += j.value("minflt", 0L);
    return j["s"].get<double>();
  }

 private:
  nlohmann::json Read() {
    std::string line;
    char buf[4096];
    while (from_ && std::fgets(buf, sizeof buf, from_)) {
      line += buf;
      if (!line.empty() && line.back() == '\n') break;
    }
    return nlohmann::json::parse(line, nullptr, false);
  }
  pid_t pid_ = -1;
  std::FILE* to_ = nullptr;
  std::FILE* from_ = nullptr;
  nlohmann::json hello_;
};

struct Measure {
  std::string name;
  std::vector<double> cpp_s, py_s, load;
  long cpp_faults = 0, py_faults = 0;  // Minor page faults over the timed repetitions.
};

}  // namespace

int main(int argc, char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") == nullptr) {
    ::setenv("OMP_WAIT_POLICY", "passive", 1);
    ::execv("/proc/self/exe", argv);  // libgomp reads the policy at start-up.
  }
  ::signal(SIGPIPE, SIG_IGN);  // A peer that died reads as "no Python", not a crash.
  const std::string arch = argc > 2 ? argv[2] : "b0";
  const int repeats = argc > 3 ? std::max(1, std::atoi(argv[3])) : 15;  // Loaded machine: many pairs.
  const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const double load_start = LoadAverage1();
  const auto wall_start = std::chrono::steady_clock::now();
  asbuilt::SetTorchThreads(threads);
  torch::manual_seed(0);
  asbuilt::Segformer model(asbuilt::SegformerConfigFor(arch, 4));
  PythonPeer py(arch, threads);
  const bool have_py = py.ok();

  // The three workloads, exactly as segformer_bench.py's Workload runs them.
  torch::Tensor x = torch::randn({1, 3, 480, 640});
  auto infer = [&] {
    model->eval();
    torch::NoGradGuard no_grad;
    F::interpolate(
        model->forward(x),
        F::InterpolateFuncOptions().size(std::vector<int64_t>{480, 640}).mode(torch::kBilinear).align_corners(false))
        .argmax(1);
  };
  torch::optim::AdamW opt(model->parameters(), torch::optim::AdamWOptions(1e-4).weight_decay(1e-3));
  auto train = [&](int side) {
    static std::map<int, std::pair<torch::Tensor, torch::Tensor>> batches;
    if (!batches.count(side)) batches[side] = {torch::randn({2, 3, side, side}), torch::randint(0, 4, {2, side, side})};
    auto& [xb, yb] = batches[side];
    model->train();
    torch::Tensor logits = F::interpolate(
        model->forward(xb),
        F::InterpolateFuncOptions().size(std::vector<int64_t>{side, side}).mode(torch::kBilinear).align_corners(false));
    torch::Tensor loss = F::cross_entropy(logits, yb, F::CrossEntropyFuncOptions().ignore_index(255));
    opt.zero_grad();
    loss.backward();
    opt.step();
  };

  struct Job {
    const char* name;
    std::function<void()> cpp;
    std::string py_command;
    int repeats;
  };
  // Inference is the shortest and the most at the mercy of the load: three
  // times the repetitions.
  const std::vector<Job> jobs = {{"inference latency, 640×480", infer, "infer", 3 * repeats},
                                 {"training, 256×256", [&] { train(256); }, "train 256", repeats},
                                 {"training, 512×512", [&] { train(512); }, "train 512", repeats}};
  std::vector<Measure> measures;
  for (const Job& job : jobs) {
    Measure m{.name = job.name};
    long ignored = 0;
    job.cpp();  // Warm-up (and AdamW state) on both sides.
    if (have_py) py.Time(job.py_command, &ignored);
    for (int r = 0; r < job.repeats; ++r) {
      m.load.push_back(LoadAverage1());
      const bool cpp_first = r % 2 == 0;
      if (cpp_first) m.cpp_s.push_back(Seconds(job.cpp, &m.cpp_faults));
      if (have_py) m.py_s.push_back(py.Time(job.py_command, &m.py_faults));
      if (!cpp_first) m.cpp_s.push_back(Seconds(job.cpp, &m.cpp_faults));
    }
    std::fprintf(stderr, "bench_seg: %s: C++ %.3f s, Python %.3f s (medians); minor faults per run %ld vs %ld\n",
                 job.name, Median(m.cpp_s), have_py ? Median(m.py_s) : 0.0, m.cpp_faults / job.repeats,
                 have_py ? m.py_faults / job.repeats : 0L);
    measures.push_back(std::move(m));
  }
  const double cpp_rss = asbuilt::bench::PeakRssMiB();
  const double py_rss = have_py ? py.Ask("rss").value("peak_rss_mib", 0.0) : 0.0;
  const double load_end = LoadAverage1();
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::vector<double> all_load;
  for (const Measure& m : measures) all_load.insert(all_load.end(), m.load.begin(), m.load.end());

  std::string md = fmt::format(
      "## seg — SegFormer-{} speed, C++ LibTorch vs Python PyTorch\n\n"
      "{} threads (both), OMP_WAIT_POLICY={}, {} repetitions per measure ({} for inference), interleaved in one run: "
      "the Python\n"
      "model lives in a peer process that runs one measurement per request while the C++ process waits, and\n"
      "repetitions alternate C++→Python and Python→C++ (ABBA…), so both sides see the same load. Training:\n"
      "batch 2, forward + cross-entropy + backward + AdamW; inference: one 640×480 image, eval, no_grad,\n"
      "upsampled logits, argmax. Same architecture ({} parameters) and the same ATen kernels (Debian's\n"
      "libtorch 1.13 under both). Ratio = Python time / C++ time (target ≥ 1.0): the headline is the median\n"
      "of the per-pair ratios (each pair ran back to back, so slow load drift cancels), then the ratio of the\n"
      "two medians and the spread of the per-pair ratios.\n\n"
      "| measure | C++ (median) | Python (median) | ratio (median pair) | ratio of medians | per-pair range | "
      "page faults per run, C++ / Python |\n"
      "|---|---|---|---|---|---|---|\n",
      arch, threads, std::getenv("OMP_WAIT_POLICY"), repeats, 3 * repeats, asbuilt::CountParameters(*model));
  for (const Measure& m : measures) {
    const bool time_like = m.name.rfind("inference", 0) == 0;
    auto fmt_value = [&](double s) {
      return time_like ? fmt::format("{:.3f} s", s) : fmt::format("{:.2f} img/s", 2.0 / s);
    };
    if (!have_py) {
      md += fmt::format("| {} | {} | n/a | n/a | n/a | | {}k |\n", m.name, fmt_value(Median(m.cpp_s)),
                        m.cpp_faults / 1000 / static_cast<long>(m.cpp_s.size()));
      continue;
    }
    std::vector<double> pair_ratio;
    for (size_t i = 0; i < m.cpp_s.size(); ++i) pair_ratio.push_back(m.py_s[i] / m.cpp_s[i]);
    std::sort(pair_ratio.begin(), pair_ratio.end());
    const long n = static_cast<long>(m.cpp_s.size());
    md += fmt::format("| {} | {} | {} | **{:.2f}** | {:.2f} | {:.2f}–{:.2f} | {}k / {}k |\n", m.name,
                      fmt_value(Median(m.cpp_s)), fmt_value(Median(m.py_s)), Median(pair_ratio),
                      Median(m.py_s) / Median(m.cpp_s), pair_ratio.front(), pair_ratio.back(), m.cpp_faults / 1000 / n,
                      m.py_faults / 1000 / n);
  }
  md += fmt::format("| peak RSS (whole process) | {:.0f} MiB | {} | | | | |\n", cpp_rss,
                    have_py ? fmt::format("{:.0f} MiB", py_rss) : "n/a");
  std::sort(all_load.begin(), all_load.end());
  md += fmt::format(
      "\nLoad average (1 min) on {} cores: {:.1f} at the start, {:.1f} at the end, {:.1f}–{:.1f} (median {:.1f}) "
      "over the repetitions; {:.0f} s in all.\n",
      std::thread::hardware_concurrency(), load_start, load_end, all_load.front(), all_load.back(), Median(all_load),
      wall_s);
  if (!have_py) {
    md +=
        "\nPython PyTorch not found at /usr/bin/python3 (Debian `python3-torch`: `scripts/install-deps.sh --bench`).\n";
  }
  md += fmt::format("\nLibTorch {}.{}.{}{}.\n", TORCH_VERSION_MAJOR, TORCH_VERSION_MINOR, TORCH_VERSION_PATCH,
                    have_py ? ", Python torch " + py.hello().value("torch", std::string("?")) : "");
  asbuilt::bench::WriteSection(asbuilt::bench::ResultsPath(argc, argv, "seg"), md);
  return 0;
}
