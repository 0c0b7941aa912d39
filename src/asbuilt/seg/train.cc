#include "asbuilt/seg/train.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "asbuilt/seg/communicator.h"
#include "asbuilt/seg/metrics.h"
#include "asbuilt/seg/model_io.h"
#include "asbuilt/seg/tflite_segmenter.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;
namespace F = torch::nn::functional;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

nlohmann::json Num(double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); }
double FromNum(const nlohmann::json& j) { return j.is_null() ? kNaN : j.get<double>(); }

EpochRecord RecordFromJson(const nlohmann::json& j) {
  EpochRecord r;
  r.epoch = j.at("epoch");
  r.step = j.at("step");
  r.lr = j.at("lr");
  r.train_loss = FromNum(j.at("train_loss"));
  r.val_miou = FromNum(j.at("val_mIoU"));
  r.val_mfscore = FromNum(j.at("val_mFscore"));
  r.val_mprecision = FromNum(j.at("val_mPrecision"));
  r.val_mrecall = FromNum(j.at("val_mRecall"));
  r.val_aacc = FromNum(j.at("val_aAcc"));
  r.wall_s = j.at("wall_s");
  return r;
}

// lr at `step` (0-based) of `total`: linear warm-up, then poly decay.
double LearningRate(const TrainOptions& o, std::int64_t step, std::int64_t total) {
  double poly =
      std::pow(std::max(0.0, 1.0 - static_cast<double>(step) / std::max<std::int64_t>(1, total)), o.poly_power);
  double lr = o.lr * poly;
  if (step < o.warmup_steps) {
    double k = (1.0 - static_cast<double>(step) / o.warmup_steps) * (1.0 - o.warmup_ratio);
    lr *= (1.0 - k);
  }
  return lr;
}

// Sample index for global draw k: a fresh permutation every pass over the
// data, each seeded by (seed, pass), so resume reproduces the order.
size_t SampleIndex(std::uint64_t seed, std::int64_t k, size_t n, std::vector<size_t>& perm, std::int64_t& perm_pass) {
  std::int64_t pass = k / static_cast<std::int64_t>(n);
  if (pass != perm_pass) {
    perm.resize(n);
    for (size_t i = 0; i < n; ++i) perm[i] = i;
    std::mt19937_64 rng(seed * 1000003ull + static_cast<std::uint64_t>(pass));
    std::shuffle(perm.begin(), perm.end(), rng);
    perm_pass = pass;
  }
  return perm[static_cast<size_t>(k % static_cast<std::int64_t>(n))];
}

std::string CsvOf(const std::vector<EpochRecord>& history) {
  std::string s = "epoch,step,lr,train_loss,val_mIoU,val_mFscore,val_mPrecision,val_mRecall,val_aAcc,wall_s\n";
  auto f = [](double x) { return std::isnan(x) ? std::string("nan") : fmt::format("{:.6g}", x); };
  for (const auto& r : history) {
    s += fmt::format("{},{},{:.6g},{},{},{},{},{},{},{:.1f}\n", r.epoch, r.step, r.lr, f(r.train_loss), f(r.val_miou),
                     f(r.val_mfscore), f(r.val_mprecision), f(r.val_mrecall), f(r.val_aacc), r.wall_s);
  }
  return s;
}

// Loss (left axis, blue) and validation mIoU (right axis 0..1, red) per epoch.
void WritePlot(const fs::path& path, const std::vector<EpochRecord>& history) {
  const int W = 640, H = 400, L = 60, R = 60, T = 30, B = 50;
  cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::rectangle(img, {L, T}, {W - R, H - B}, cv::Scalar(0, 0, 0), 1);
  double max_loss = 1e-6;
  for (const auto& r : history) {
    if (!std::isnan(r.train_loss)) max_loss = std::max(max_loss, r.train_loss);
  }
  const int n = static_cast<int>(history.size());
  auto X = [&](int i) { return L + (n <= 1 ? (W - L - R) / 2 : i * (W - L - R) / (n - 1)); };
  auto Yl = [&](double v) { return static_cast<int>(H - B - v / max_loss * (H - T - B)); };
  auto Ym = [&](double v) { return static_cast<int>(H - B - v * (H - T - B)); };
  for (int i = 0; i < n; ++i) {
    const auto& r = history[i];
    if (!std::isnan(r.train_loss)) {
      cv::circle(img, {X(i), Yl(r.train_loss)}, 3, cv::Scalar(200, 80, 0), cv::FILLED);
      if (i > 0 && !std::isnan(history[i - 1].train_loss)) {
        cv::line(img, {X(i - 1), Yl(history[i - 1].train_loss)}, {X(i), Yl(r.train_loss)}, cv::Scalar(200, 80, 0), 2);
      }
    }
    if (!std::isnan(r.val_miou)) {
      cv::circle(img, {X(i), Ym(r.val_miou)}, 3, cv::Scalar(0, 0, 220), cv::FILLED);
      if (i > 0 && !std::isnan(history[i - 1].val_miou)) {
        cv::line(img, {X(i - 1), Ym(history[i - 1].val_miou)}, {X(i), Ym(r.val_miou)}, cv::Scalar(0, 0, 220), 2);
      }
    }
  }
  const auto font = cv::FONT_HERSHEY_SIMPLEX;
  cv::putText(img, "train loss", {L, T - 10}, font, 0.5, cv::Scalar(200, 80, 0), 1, cv::LINE_AA);
  cv::putText(img, "val mIoU", {W - R - 80, T - 10}, font, 0.5, cv::Scalar(0, 0, 220), 1, cv::LINE_AA);
  cv::putText(img, fmt::format("{:.3g}", max_loss), {5, T + 5}, font, 0.4, cv::Scalar(200, 80, 0), 1, cv::LINE_AA);
  cv::putText(img, "0", {L - 15, H - B}, font, 0.4, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  cv::putText(img, "1.0", {W - R + 5, T + 5}, font, 0.4, cv::Scalar(0, 0, 220), 1, cv::LINE_AA);
  cv::putText(img, fmt::format("epoch (1..{})", n), {W / 2 - 40, H - 15}, font, 0.5, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  AtomicFile out(path);
  if (!cv::imwrite(out.temp_path().string(), img)) throw Error(path.string() + ": cannot write plot");
  out.Commit();
}

void WriteLogs(const fs::path& dir, const std::vector<EpochRecord>& history) {
  WriteFileAtomic(dir / "log.csv", CsvOf(history));
  std::string jsonl;
  for (const auto& r : history) jsonl += r.ToJson().dump() + "\n";
  WriteFileAtomic(dir / "log.jsonl", jsonl);
  WritePlot(dir / "plot.png", history);
}

// One training batch: images (8-bit BGR) and labels, augmented to crop size.
struct TrainBatch {
  std::vector<cv::Mat> images, labels;
};

// Samples [first, first + count) of the batch of global step `step`: which
// pairs (SampleIndex) and how they are augmented follow from the seed, the
// step and the place in the batch alone, so a resumed run reads the batches
// an uninterrupted one would, and K ranks reading a share each read the
// global batch one process would.
TrainBatch ReadTrainBatch(const TrainOptions& options, const std::vector<SegSample>& train, std::int64_t step,
                          int first, int count, std::vector<size_t>& perm, std::int64_t& perm_pass) {
  TrainBatch batch;
  for (int b = first; b < first + count; ++b) {
    const std::int64_t k = step * options.batch_size + b;
    const SegSample& sample = train[SampleIndex(options.seed, k, train.size(), perm, perm_pass)];
    SegPair pair = ReadSegPair(sample, options.num_classes);
    std::mt19937_64 rng(options.seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(k));
    AugmentPair(pair, options.augment, rng);
    batch.images.push_back(pair.bgr);
    batch.labels.push_back(pair.label);
  }
  return batch;
}

// The network being trained: a SegFormer, or a TFLite graph whose 32 classes
// are trained through their sums onto asbuilt's four.
class TrainNet {
 public:
  virtual ~TrainNet() = default;
  virtual torch::nn::Module& module() = 0;
  // Trained at lr · head_lr_mult; the rest at lr.
  virtual std::vector<torch::Tensor> HeadParameters() = 0;
  // (B, 4, h, w) scores at the label size whose cross entropy is the loss.
  virtual torch::Tensor Scores(const std::vector<cv::Mat>& images, int64_t h, int64_t w) = 0;
  virtual const char* format() const = 0;
  virtual nlohmann::json Config() const = 0;
  virtual std::unique_ptr<Segmenter> Validator(const SegmenterInfo& info) = 0;
  // Data-parallel training: what the network draws at random or reduces over
  // the batch must span every rank's share (SegformerImpl::SetDataParallel).
  // A TFLite graph has neither (its batch norms are folded into its convs).
  virtual void SetDataParallel(const std::shared_ptr<Communicator>& comm) {}
};

torch::Tensor Upsampled(const torch::Tensor& logits, int64_t h, int64_t w) {
  return F::interpolate(
      logits, F::InterpolateFuncOptions().size(std::vector<int64_t>{h, w}).mode(torch::kBilinear).align_corners(false));
}

class SegformerTrainNet : public TrainNet {
 public:
  explicit SegformerTrainNet(const TrainOptions& options)
      : config_(SegformerConfigFor(options.arch, options.num_classes)) {
    config_.drop_path_rate = options.drop_path_rate;
    model_ = Segformer(config_);
  }
  torch::nn::Module& module() override { return *model_; }
  std::vector<torch::Tensor> HeadParameters() override { return model_->decoder->parameters(); }
  torch::Tensor Scores(const std::vector<cv::Mat>& images, int64_t h, int64_t w) override {
    return Upsampled(model_->forward(ImagesToTensor(images)), h, w);
  }
  const char* format() const override { return kCheckpointFormat; }
  nlohmann::json Config() const override { return ConfigToJson(config_); }
  void SetDataParallel(const std::shared_ptr<Communicator>& comm) override { model_->SetDataParallel(comm); }
  std::unique_ptr<Segmenter> Validator(const SegmenterInfo& info) override {
    SegmenterInfo i = info;
    i.config = config_;
    return MakeSegmenter(model_, i, {});
  }

 private:
  SegformerConfig config_;
  Segformer model_{nullptr};
};

class TfliteTrainNet : public TrainNet {
 public:
  explicit TfliteTrainNet(const TrainOptions& options) : net_(LoadTfliteNet(options.init)) {}
  torch::nn::Module& module() override { return *net_; }
  std::vector<torch::Tensor> HeadParameters() override { return net_->head_parameters(); }
  torch::Tensor Scores(const std::vector<cv::Mat>& images, int64_t h, int64_t w) override {
    return GroupedLogProbabilities(Upsampled(net_->forward(RgbTensor(images)), h, w));
  }
  const char* format() const override { return kTfliteCheckpointFormat; }
  nlohmann::json Config() const override { return TfliteCheckpointConfig(net_); }
  std::unique_ptr<Segmenter> Validator(const SegmenterInfo& info) override {
    SegmenterInfo i = info;
    i.config.arch = "tflite";
    i.config.num_classes = 4;
    return MakeTfliteSegmenter(net_, i, {});
  }

 private:
  TfliteNet net_;
};

std::unique_ptr<TrainNet> MakeTrainNet(const TrainOptions& options) {
  if (options.arch == "tflite") return std::make_unique<TfliteTrainNet>(options);
  return std::make_unique<SegformerTrainNet>(options);
}

// The parameters of `all` that are not in `head`.
std::vector<torch::Tensor> Without(const std::vector<torch::Tensor>& all, const std::vector<torch::Tensor>& head) {
  std::vector<torch::Tensor> out;
  for (const torch::Tensor& p : all) {
    const bool in_head = std::any_of(head.begin(), head.end(), [&](const torch::Tensor& h) {
      return h.unsafeGetTensorImpl() == p.unsafeGetTensorImpl();
    });
    if (!in_head) out.push_back(p);
  }
  return out;
}

// One AdamW step on `batch` at the optimizer's current learning rates: cross
// entropy (label 255 ignored) of the scores at the label size. Returns the
// batch's loss before the step.
double OptimizerStep(TrainNet& net, torch::optim::AdamW& optimizer, const TrainBatch& batch) {
  torch::Tensor y = LabelsToTensor(batch.labels);
  torch::Tensor scores = net.Scores(batch.images, y.size(1), y.size(2));
  torch::Tensor loss = F::cross_entropy(scores, y, F::CrossEntropyFuncOptions().ignore_index(255));
  optimizer.zero_grad();
  loss.backward();
  optimizer.step();
  return loss.item<double>();
}

// The same step for rank r of K ranks, `batch` being the r-th share of the
// global batch. The global count of labelled pixels is summed first, this
// rank's loss is the sum of its pixels' cross entropy over that count (so the
// ranks' losses add up to the global batch's mean) and every gradient is
// summed over the ranks before the step: the step one process takes on the
// global batch, up to rounding. Returns the global batch's loss, or nullopt,
// taking no step, when a rank asked to stop (`stop` on any rank stops all).
std::optional<double> DataParallelStep(TrainNet& net, torch::optim::AdamW& optimizer, const TrainBatch& batch,
                                       Communicator& comm, bool stop) {
  torch::Tensor y = LabelsToTensor(batch.labels);
  torch::Tensor counts =
      torch::tensor({static_cast<double>((y != 255).sum().item<std::int64_t>()), stop ? 1.0 : 0.0}, torch::kDouble);
  comm.AllReduceSum(counts);
  if (counts[1].item<double>() > 0) return std::nullopt;
  torch::Tensor scores = net.Scores(batch.images, y.size(1), y.size(2));
  torch::Tensor loss =
      F::cross_entropy(scores, y, F::CrossEntropyFuncOptions().ignore_index(255).reduction(torch::kSum)) /
      counts[0].item<double>();
  optimizer.zero_grad();
  loss.backward();
  std::vector<torch::Tensor> sums;
  for (const torch::Tensor& p : net.module().parameters()) sums.push_back(p.grad());
  torch::Tensor global_loss = loss.detach().reshape({1}).clone();
  sums.push_back(global_loss);
  AllReduceSumEach(comm, sums);
  optimizer.step();
  return global_loss.item<double>();
}

// FNV-1a over the bytes of every parameter and buffer: equal on every rank
// as long as the ranks train in step.
std::int64_t ParameterDigest(torch::nn::Module& module) {
  std::uint64_t h = 1469598103934665603ull;
  auto add = [&](const torch::Tensor& t) {
    const torch::Tensor c = t.detach().contiguous();
    const auto* bytes = static_cast<const unsigned char*>(c.data_ptr());
    for (std::size_t i = 0; i < c.nbytes(); ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  };
  for (const torch::Tensor& p : module.parameters()) add(p);
  for (const torch::Tensor& b : module.buffers()) add(b);
  return static_cast<std::int64_t>(h);
}

// Segments the validation pairs with the model being trained and stores the
// metrics (mIoU, mFscore, …) in `rec`. With `comm`, rank r segments pairs
// r, r + K, … and the confusion matrices are summed: the same metrics, K×
// sooner.
void ValidateEpoch(Segmenter& validator, const std::vector<SegSample>& val, int num_classes, int epoch,
                   const ProgressCallback& progress, Communicator* comm, EpochRecord& rec) {
  ConfusionMatrix cm(num_classes);
  for (size_t i = 0; i < val.size(); ++i) {
    if (comm != nullptr && static_cast<int>(i % comm->world_size()) != comm->rank()) continue;
    SegPair pair = ReadSegPair(val[i], num_classes);
    cm.Add(pair.label, validator.Segment(pair.bgr));
    ReportProgress(progress, {.stage = fmt::format("validate epoch {}", epoch),
                              .done = static_cast<std::int64_t>(i + 1),
                              .total = static_cast<std::int64_t>(val.size())});
  }
  if (comm != nullptr) {
    torch::Tensor counts = torch::zeros({num_classes * num_classes}, torch::kInt64);
    for (int l = 0; l < num_classes; ++l) {
      for (int p = 0; p < num_classes; ++p) counts[l * num_classes + p] = cm.at(l, p);
    }
    comm->AllReduceSum(counts);
    cm = ConfusionMatrix(num_classes);
    for (int l = 0; l < num_classes; ++l) {
      for (int p = 0; p < num_classes; ++p) cm.Add(l, p, counts[l * num_classes + p].item<std::int64_t>());
    }
  }
  const SegmentationMetrics m = ComputeMetrics(cm);
  rec.val_miou = m.miou;
  rec.val_mfscore = m.mfscore;
  rec.val_mprecision = m.mprecision;
  rec.val_mrecall = m.mrecall;
  rec.val_aacc = m.aacc;
}

// AdamW over the body at lr and the head at lr · head_lr_mult (mmseg
// SegFormer's decoder: lr_mult 10).
std::unique_ptr<torch::optim::AdamW> MakeOptimizer(TrainNet& net, const TrainOptions& options) {
  std::vector<torch::Tensor> head_params = net.HeadParameters();
  std::vector<torch::Tensor> body_params = Without(net.module().parameters(), head_params);
  std::vector<torch::optim::OptimizerParamGroup> groups;
  groups.emplace_back(body_params, std::make_unique<torch::optim::AdamWOptions>(
                                       torch::optim::AdamWOptions(options.lr).weight_decay(options.weight_decay)));
  groups.emplace_back(
      head_params,
      std::make_unique<torch::optim::AdamWOptions>(
          torch::optim::AdamWOptions(options.lr * options.head_lr_mult).weight_decay(options.weight_decay)));
  return std::make_unique<torch::optim::AdamW>(std::move(groups), torch::optim::AdamWOptions(options.lr));
}

// Loads OUT/last.pt (model, optimizer, history into `summary`) when resuming,
// else the --init weights; returns the last finished epoch (0: fresh start).
int ResumeOrInit(const TrainOptions& options, const fs::path& last_path, TrainNet& net, torch::optim::AdamW& optimizer,
                 TrainSummary& summary) {
  if (options.resume && fs::exists(last_path)) {
    nlohmann::json meta = ReadCheckpointMeta(last_path);
    const std::string saved_arch = meta.value("config", nlohmann::json::object()).value("arch", "?");
    const int saved_classes = meta.value("config", nlohmann::json::object()).value("num_classes", 0);
    if (saved_arch != options.arch || saved_classes != options.num_classes) {
      throw InvalidArgument(
          fmt::format("{} holds a {} model with {} classes, but --arch {} with {} classes was "
                      "asked; use another -o or --no-resume",
                      last_path.string(), saved_arch, saved_classes, options.arch, options.num_classes));
    }
    LoadWeights(last_path, net.module(), &optimizer, /*strict=*/true);
    const int start_epoch = meta.value("epoch", 0);
    for (const auto& r : meta.at("history")) summary.history.push_back(RecordFromJson(r));
    summary.best_miou = meta.contains("best_miou") ? FromNum(meta["best_miou"]) : kNaN;
    summary.best_epoch = meta.value("best_epoch", 0);
    summary.resumed_from_epoch = start_epoch;
    spdlog::info("train: resuming {} after epoch {}", last_path.string(), start_epoch);
    return start_epoch;
  }
  if (!options.init.empty() && options.arch != "tflite") {  // A TFLite net is built from its init.
    int skipped = 0;
    int loaded = LoadWeights(options.init, net.module(), nullptr, /*strict=*/false, &skipped);
    if (loaded == 0) throw InputError(options.init.string(), "", "no tensor matches the model (wrong architecture?)");
    spdlog::info("train: initialised {} tensors from {} ({} skipped)", loaded, options.init.string(), skipped);
  }
  return 0;
}

// Every rank starts from rank 0's weights and from the same epoch (they all
// read OUT/last.pt, which must be on a shared file system).
void StartInStep(Communicator& comm, TrainNet& net, int start_epoch, const fs::path& out) {
  CheckSameOnEveryRank(comm, start_epoch,
                       fmt::format("epoch to resume after (is {} one shared folder for every rank?)", out.string()));
  std::vector<torch::Tensor> state = net.module().parameters();
  for (const torch::Tensor& b : net.module().buffers()) state.push_back(b);
  BroadcastEach(comm, state, 0);
}

// The training of one process: alone (comm null) or as one rank of several.
// Only rank 0 writes files and reports progress.
TrainSummary Train(const TrainOptions& options, const std::shared_ptr<Communicator>& comm,
                   const ProgressCallback& progress_in, std::stop_token stop) {
  const auto start_time = std::chrono::steady_clock::now();
  const int rank = comm ? comm->rank() : 0, world = comm ? comm->world_size() : 1;
  const bool writer = rank == 0;
  const ProgressCallback progress = writer ? progress_in : ProgressCallback{};
  SetTorchThreads(options.threads);
  torch::manual_seed(options.seed);

  SegDataSplit split = options.manifest.empty() ? SplitFromFolders(options.images_dir, options.labels_dir,
                                                                   options.val_fraction, options.seed)
                                                : SplitFromManifest(options.manifest);
  if (options.val_max_images > 0 && static_cast<int>(split.val.size()) > options.val_max_images) {
    split.val.resize(options.val_max_images);
  }
  spdlog::info("train: {} ({} train, {} val pairs{})", split.source, split.train.size(), split.val.size(),
               comm ? fmt::format("; {} ranks, global batch {}", world, options.batch_size) : "");

  std::unique_ptr<TrainNet> net = MakeTrainNet(options);
  const std::int64_t n_params = CountParameters(net->module());
  std::unique_ptr<torch::optim::AdamW> optimizer = MakeOptimizer(*net, options);

  const fs::path out = options.out_dir;
  fs::create_directories(out);
  // A run killed mid-write (SIGKILL, power loss) leaves a temp file beside the
  // intact checkpoint it was replacing; clear those before resuming.
  if (writer) {
    if (int stale = RemoveDeadAtomicTemps(out); stale > 0) {
      spdlog::info("train: removed {} temp file(s) left by a killed run in {}", stale, out.string());
    }
  }
  const fs::path last_path = out / "last.pt", best_path = out / "best.pt";

  TrainSummary summary;
  summary.out_dir = out;
  summary.train_pairs = static_cast<int>(split.train.size());
  summary.val_pairs = static_cast<int>(split.val.size());
  summary.best_miou = kNaN;
  const int start_epoch = ResumeOrInit(options, last_path, *net, *optimizer, summary);
  const double wall_offset = summary.history.empty() ? 0 : summary.history.back().wall_s;
  if (comm) {
    StartInStep(*comm, *net, start_epoch, out);
    net->SetDataParallel(comm);
  }

  const int steps_per_epoch =
      options.steps_per_epoch > 0
          ? options.steps_per_epoch
          : static_cast<int>((split.train.size() + options.batch_size - 1) / options.batch_size);
  const std::int64_t total_steps = static_cast<std::int64_t>(steps_per_epoch) * options.epochs;

  nlohmann::json resolved = options.ToJson();
  resolved["config"] = net->Config();
  if (resolved["config"].contains("graph")) resolved["config"].erase("graph");  // In the checkpoints.
  resolved["parameters"] = n_params;
  resolved["data"] = {{"source", split.source},
                      {"train_pairs", split.train.size()},
                      {"val_pairs", split.val.size()},
                      {"steps_per_epoch", steps_per_epoch},
                      {"total_steps", total_steps}};

  auto make_meta = [&](int epoch) {
    nlohmann::json meta;
    meta["format"] = net->format();
    meta["config"] = net->Config();
    meta["scale"] = {options.augment.scale_width_px, options.augment.scale_height_px};
    meta["crop"] = {options.augment.crop_width_px, options.augment.crop_height_px};
    meta["label_resize"] = "nearest_exact";  // SegmenterInfo::label_offset_px.
    meta["epoch"] = epoch;
    meta["step"] = static_cast<std::int64_t>(epoch) * steps_per_epoch;
    meta["parameters"] = n_params;
    meta["class_names"] = DefaultClassNames();
    meta["options"] = resolved;
    meta["best_miou"] = Num(summary.best_miou);
    meta["best_epoch"] = summary.best_epoch;
    nlohmann::json hist = nlohmann::json::array();
    for (const auto& r : summary.history) hist.push_back(r.ToJson());
    meta["history"] = hist;
    return meta;
  };

  SegmenterInfo info;
  info.scale_width_px = options.augment.scale_width_px;
  info.scale_height_px = options.augment.scale_height_px;
  info.crop_width_px = options.augment.crop_width_px;
  info.crop_height_px = options.augment.crop_height_px;
  info.parameters = n_params;
  auto validator = net->Validator(info);

  std::vector<size_t> perm;
  std::int64_t perm_pass = -1;
  const int share = options.batch_size / world;  // This rank's samples of each global batch.
  const int last_epoch =
      options.stop_after_epoch > 0 ? std::min(options.epochs, options.stop_after_epoch) : options.epochs;
  for (int epoch = start_epoch + 1; epoch <= last_epoch; ++epoch) {
    net->module().train();
    double loss_sum = 0;
    int loss_count = 0;
    double lr = 0;
    const std::string stage = fmt::format("train epoch {}/{}", epoch, options.epochs);
    for (int s = 0; s < steps_per_epoch; ++s) {
      if (!comm && stop.stop_requested()) {
        summary.stopped = true;
        break;
      }
      const std::int64_t step = static_cast<std::int64_t>(epoch - 1) * steps_per_epoch + s;
      const TrainBatch batch = ReadTrainBatch(options, split.train, step, rank * share, share, perm, perm_pass);
      lr = LearningRate(options, step, total_steps);
      optimizer->param_groups()[0].options().set_lr(lr);
      optimizer->param_groups()[1].options().set_lr(lr * options.head_lr_mult);
      double l = 0;
      if (comm) {
        const std::optional<double> global = DataParallelStep(*net, *optimizer, batch, *comm, stop.stop_requested());
        if (!global) {
          summary.stopped = true;
          break;
        }
        l = *global;
      } else {
        l = OptimizerStep(*net, *optimizer, batch);
      }
      if (!std::isfinite(l)) {
        throw Error(fmt::format("training diverged at epoch {} step {} (loss {}); lower --lr", epoch, s, l));
      }
      loss_sum += l;
      ++loss_count;
      const std::string detail = fmt::format("loss {:.4f} lr {:.2e}", loss_sum / loss_count, lr);
      ReportProgress(progress, {.stage = stage, .done = s + 1, .total = steps_per_epoch, .detail = detail});
    }
    if (summary.stopped) break;  // The partial epoch is dropped: resume redoes it.
    if (comm) CheckSameOnEveryRank(*comm, ParameterDigest(net->module()), fmt::format("weights after epoch {}", epoch));

    // Validation.
    EpochRecord rec;
    rec.epoch = epoch;
    rec.step = static_cast<std::int64_t>(epoch) * steps_per_epoch;
    rec.lr = lr;
    rec.train_loss = loss_count > 0 ? loss_sum / loss_count : kNaN;
    rec.val_miou = rec.val_mfscore = rec.val_mprecision = rec.val_mrecall = rec.val_aacc = kNaN;
    if (!split.val.empty()) ValidateEpoch(*validator, split.val, options.num_classes, epoch, progress, comm.get(), rec);
    rec.wall_s = wall_offset + std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    summary.history.push_back(rec);
    bool best = !std::isnan(rec.val_miou) && (std::isnan(summary.best_miou) || rec.val_miou > summary.best_miou);
    if (best || (split.val.empty() && epoch == options.epochs)) {
      summary.best_miou = rec.val_miou;
      summary.best_epoch = epoch;
    }
    if (writer) {
      // This run's options.json goes with its first checkpoint, so a run that
      // fails on its first batch (a corrupt image) leaves no file behind.
      if (epoch == start_epoch + 1) WriteFileAtomic(out / "options.json", resolved.dump(2) + "\n");
      // Checkpoints: best first, then last (the resume point) — both atomic.
      if (best || split.val.empty()) SaveCheckpoint(best_path, net->module(), nullptr, make_meta(epoch));
      SaveCheckpoint(last_path, net->module(), optimizer.get(), make_meta(epoch));
      WriteLogs(out, summary.history);
    }
    if (comm) comm->Barrier();  // No rank runs ahead of rank 0's checkpoint.
    spdlog::info("epoch {}: loss {:.4f}, val mIoU {:.4f}, lr {:.2e}{}", epoch, rec.train_loss, rec.val_miou, lr,
                 comm ? fmt::format(", weights identical on the {} ranks", world) : "");
  }

  summary.epochs_done = summary.history.empty() ? 0 : summary.history.back().epoch;
  summary.steps = static_cast<std::int64_t>(summary.epochs_done) * steps_per_epoch;
  if (!summary.history.empty()) {
    summary.first_loss = summary.history.front().train_loss;
    summary.last_loss = summary.history.back().train_loss;
    summary.wall_s = summary.history.back().wall_s;
  }
  return summary;
}

// Rethrows the exception in flight with "rank R of K: " before its message,
// keeping its kind (srun interleaves the ranks' error output).
[[noreturn]] void RethrowNamingRank(const DistributedOptions& d) {
  const std::string who = fmt::format("rank {} of {}: ", d.rank, d.world_size);
  try {
    throw;
  } catch (const InputError& e) {
    std::vector<Problem> problems = e.problems();
    for (Problem& p : problems) p.message = who + p.message;
    throw InputError(problems);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(who + e.what());
  } catch (const std::exception& e) {
    throw Error(who + e.what());
  }
}

}  // namespace

TrainSummary TrainSegmenter(const TrainOptions& options, const ProgressCallback& progress, std::stop_token stop) {
  options.Check();
  if (!options.distributed.enabled()) return Train(options, nullptr, progress, stop);
  try {
    return Train(options, ConnectGloo(options.distributed), progress, stop);
  } catch (...) {
    RethrowNamingRank(options.distributed);
  }
}

}  // namespace asbuilt
