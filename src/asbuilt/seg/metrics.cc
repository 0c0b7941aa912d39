#include "asbuilt/seg/metrics.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double Ratio(double num, double den) { return den == 0 ? kNaN : num / den; }

double NanMean(const std::vector<double>& v) {
  double sum = 0;
  int n = 0;
  for (double x : v) {
    if (!std::isnan(x)) {
      sum += x;
      ++n;
    }
  }
  return n == 0 ? kNaN : sum / n;
}

std::string Fmt(double x) { return std::isnan(x) ? "nan" : fmt::format("{:.4f}", x); }

nlohmann::json JsonNumber(double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); }

}  // namespace

ConfusionMatrix::ConfusionMatrix(int num_classes) : num_classes_(num_classes) {
  CheckArgument(num_classes > 0 && num_classes < 255,
                fmt::format("ConfusionMatrix num_classes = {}, must be in [1, 254]", num_classes));
  counts_.assign(static_cast<size_t>(num_classes * num_classes), 0);
}

void ConfusionMatrix::Add(int label, int pred, std::int64_t count) {
  CheckArgument(label >= 0 && label < num_classes_ && pred >= 0 && pred < num_classes_,
                fmt::format("ConfusionMatrix::Add({}, {}): out of range [0, {})", label, pred, num_classes_));
  counts_[label * num_classes_ + pred] += count;
}

void ConfusionMatrix::Add(const cv::Mat& label, const cv::Mat& pred, int ignore_label) {
  CheckArgument(label.type() == CV_8UC1 && pred.type() == CV_8UC1,
                "ConfusionMatrix::Add: label and prediction must be single-channel 8-bit");
  CheckArgument(label.size() == pred.size(), fmt::format("ConfusionMatrix::Add: label is {}x{}, prediction {}x{}",
                                                         label.cols, label.rows, pred.cols, pred.rows));
  std::vector<std::int64_t> local(counts_.size(), 0);
  for (int r = 0; r < label.rows; ++r) {
    const std::uint8_t* l = label.ptr<std::uint8_t>(r);
    const std::uint8_t* p = pred.ptr<std::uint8_t>(r);
    for (int c = 0; c < label.cols; ++c) {
      if (l[c] == ignore_label || l[c] >= num_classes_) {
        ++ignored_;
        continue;
      }
      CheckArgument(p[c] < num_classes_, fmt::format("ConfusionMatrix::Add: prediction {} at ({}, {}) out of "
                                                     "range [0, {})",
                                                     p[c], c, r, num_classes_));
      ++local[l[c] * num_classes_ + p[c]];
    }
  }
  for (size_t i = 0; i < local.size(); ++i) counts_[i] += local[i];
}

void ConfusionMatrix::Merge(const ConfusionMatrix& other) {
  CheckArgument(other.num_classes_ == num_classes_, "ConfusionMatrix::Merge: class counts differ");
  for (size_t i = 0; i < counts_.size(); ++i) counts_[i] += other.counts_[i];
  ignored_ += other.ignored_;
}

std::int64_t ConfusionMatrix::total() const {
  std::int64_t t = 0;
  for (auto c : counts_) t += c;
  return t;
}

std::vector<std::string> DefaultClassNames() { return {"background", "wall", "door", "window"}; }

SegmentationMetrics ComputeMetrics(const ConfusionMatrix& confusion, const std::vector<std::string>& class_names) {
  const int n = confusion.num_classes();
  CheckArgument(class_names.empty() || static_cast<int>(class_names.size()) == n,
                fmt::format("ComputeMetrics: {} class names for {} classes", class_names.size(), n));
  SegmentationMetrics m;
  m.confusion = confusion;
  std::vector<double> ious, fs, ps, rs;
  std::int64_t sum_intersect = 0, sum_label = 0;
  for (int c = 0; c < n; ++c) {
    ClassMetrics cm;
    cm.name = class_names.empty() ? fmt::format("class{}", c) : class_names[c];
    cm.intersect = confusion.at(c, c);
    for (int k = 0; k < n; ++k) {
      cm.pred_pixels += confusion.at(k, c);
      cm.label_pixels += confusion.at(c, k);
    }
    cm.union_ = cm.pred_pixels + cm.label_pixels - cm.intersect;
    cm.iou = Ratio(cm.intersect, cm.union_);
    cm.precision = Ratio(cm.intersect, cm.pred_pixels);
    cm.recall = Ratio(cm.intersect, cm.label_pixels);
    // β = 1; NaN propagates from P or R; P = R = 0 gives 0/0 = NaN, as in torch.
    cm.fscore = (std::isnan(cm.precision) || std::isnan(cm.recall))
                    ? kNaN
                    : Ratio(2 * cm.precision * cm.recall, cm.precision + cm.recall);
    ious.push_back(cm.iou);
    fs.push_back(cm.fscore);
    ps.push_back(cm.precision);
    rs.push_back(cm.recall);
    sum_intersect += cm.intersect;
    sum_label += cm.label_pixels;
    m.classes.push_back(cm);
  }
  m.miou = NanMean(ious);
  m.mfscore = NanMean(fs);
  m.mprecision = NanMean(ps);
  m.mrecall = NanMean(rs);
  m.aacc = Ratio(static_cast<double>(sum_intersect), static_cast<double>(sum_label));
  return m;
}

std::string SegmentationMetrics::BriefReport() const {
  return fmt::format("mIoU {} mFscore {} mPrecision {} mRecall {} aAcc {} ({} image{})", Fmt(miou), Fmt(mfscore),
                     Fmt(mprecision), Fmt(mrecall), Fmt(aacc), images, images == 1 ? "" : "s");
}

std::string SegmentationMetrics::ToMarkdown() const {
  std::string s = "| class | IoU | Fscore | Precision | Recall | label px | pred px |\n";
  s += "|---|---|---|---|---|---|---|\n";
  for (const auto& c : classes) {
    s += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", c.name, Fmt(c.iou), Fmt(c.fscore), Fmt(c.precision),
                     Fmt(c.recall), c.label_pixels, c.pred_pixels);
  }
  s += fmt::format("| **mean** | **{}** | **{}** | **{}** | **{}** | | |\n\n", Fmt(miou), Fmt(mfscore), Fmt(mprecision),
                   Fmt(mrecall));
  s += fmt::format("aAcc {} over {} image{}.\n\nConfusion matrix (rows: label, columns: prediction):\n\n", Fmt(aacc),
                   images, images == 1 ? "" : "s");
  s += "| label \\ pred |";
  for (const auto& c : classes) s += " " + c.name + " |";
  s += "\n|---|";
  for (size_t i = 0; i < classes.size(); ++i) s += "---|";
  s += "\n";
  for (size_t r = 0; r < classes.size(); ++r) {
    s += "| " + classes[r].name + " |";
    for (size_t c = 0; c < classes.size(); ++c) s += fmt::format(" {} |", confusion.at(int(r), int(c)));
    s += "\n";
  }
  return s;
}

nlohmann::json SegmentationMetrics::ToJson() const {
  nlohmann::json j;
  j["mIoU"] = JsonNumber(miou);
  j["mFscore"] = JsonNumber(mfscore);
  j["mPrecision"] = JsonNumber(mprecision);
  j["mRecall"] = JsonNumber(mrecall);
  j["aAcc"] = JsonNumber(aacc);
  j["images"] = images;
  nlohmann::json per = nlohmann::json::array();
  for (const auto& c : classes) {
    per.push_back({{"name", c.name},
                   {"IoU", JsonNumber(c.iou)},
                   {"Fscore", JsonNumber(c.fscore)},
                   {"Precision", JsonNumber(c.precision)},
                   {"Recall", JsonNumber(c.recall)},
                   {"intersect", c.intersect},
                   {"union", c.union_},
                   {"pred_pixels", c.pred_pixels},
                   {"label_pixels", c.label_pixels}});
  }
  j["classes"] = per;
  nlohmann::json cm = nlohmann::json::array();
  for (int r = 0; r < confusion.num_classes(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (int c = 0; c < confusion.num_classes(); ++c) row.push_back(confusion.at(r, c));
    cm.push_back(row);
  }
  j["confusion_matrix"] = cm;
  return j;
}

SegmentationMetrics MetricsFromJson(const nlohmann::json& json, const std::string& file) {
  const nlohmann::json* rows =
      json.is_object() && json.contains("confusion_matrix") ? &json["confusion_matrix"] : nullptr;
  if (rows == nullptr || !rows->is_array() || rows->empty()) {
    throw InputError(file, "confusion_matrix", "expected a square array of pixel counts");
  }
  const int n = static_cast<int>(rows->size());
  ConfusionMatrix confusion(n);
  for (int r = 0; r < n; ++r) {
    const nlohmann::json& row = (*rows)[r];
    if (!row.is_array() || static_cast<int>(row.size()) != n) {
      throw InputError(file, fmt::format("confusion_matrix[{}]", r), fmt::format("expected {} counts", n));
    }
    for (int c = 0; c < n; ++c) {
      if (!row[c].is_number_integer() || row[c].get<std::int64_t>() < 0) {
        throw InputError(file, fmt::format("confusion_matrix[{}][{}]", r, c), "expected a count >= 0");
      }
      confusion.Add(r, c, row[c].get<std::int64_t>());
    }
  }
  std::vector<std::string> names;
  if (json.contains("classes") && json["classes"].is_array() && static_cast<int>(json["classes"].size()) == n) {
    for (const nlohmann::json& c : json["classes"]) names.push_back(c.value("name", ""));
  }
  if (!json.contains("images") || !json["images"].is_number_integer()) {
    throw InputError(file, "images", "expected the number of images");
  }
  SegmentationMetrics m = ComputeMetrics(confusion, names);
  m.images = json["images"].get<std::int64_t>();
  return m;
}

SegmentationMetrics MergeMetrics(const std::vector<SegmentationMetrics>& parts) {
  CheckArgument(!parts.empty(), "MergeMetrics: no parts");
  ConfusionMatrix confusion(parts.front().confusion.num_classes());
  std::vector<std::string> names;
  for (const ClassMetrics& c : parts.front().classes) names.push_back(c.name);
  std::int64_t images = 0;
  for (const SegmentationMetrics& part : parts) {
    std::vector<std::string> part_names;
    for (const ClassMetrics& c : part.classes) part_names.push_back(c.name);
    CheckArgument(part.confusion.num_classes() == confusion.num_classes() && part_names == names,
                  "MergeMetrics: the parts score different classes");
    confusion.Merge(part.confusion);
    images += part.images;
  }
  SegmentationMetrics merged = ComputeMetrics(confusion, names);
  merged.images = images;
  return merged;
}

}  // namespace asbuilt
