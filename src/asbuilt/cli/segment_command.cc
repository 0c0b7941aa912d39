// `asbuilt segment --model M IMAGES… -o DIR [--overlay] [--confidence]` —
// label PNGs (0 bg, 1 wall, 2 door, 3 window) named like their inputs
// (seg/segmenter.h), and with --confidence how sure the model was.

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/cli/command.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/seg/seg_data.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {
namespace {
namespace fs = std::filesystem;

bool IsImageFile(const fs::path& p) {
  return IsImageExtension(p) && !IsAtomicTempName(p) && p.filename().string()[0] != '.';
}

void WritePng(const fs::path& path, const cv::Mat& image) {
  AtomicFile out(path);
  if (!cv::imwrite(out.temp_path().string(), image)) throw Error(path.string() + ": cannot write");
  out.Commit();
}

// How sure the model was of one image: per pixel the probability of the
// class it chose, and two summaries of it.
struct ImageConfidence {
  cv::Mat top;  // CV_32F, 0–1.
  double mean = 0.0;
  double unsure_share = 0.0;  // Pixels whose chosen class has under kUnsure.
  static constexpr double kUnsure = 0.6;
};

ImageConfidence ConfidenceOf(const std::vector<cv::Mat>& probabilities) {
  ImageConfidence c;
  c.top = probabilities.at(0).clone();
  for (std::size_t k = 1; k < probabilities.size(); ++k) cv::max(c.top, probabilities[k], c.top);
  c.mean = cv::mean(c.top)[0];
  c.unsure_share = static_cast<double>(cv::countNonZero(c.top < ImageConfidence::kUnsure)) / c.top.total();
  return c;
}

}  // namespace

int RunSegmentCommand(int argc, char** argv) {
  CLI::App app(
      "Segment images into background (0), wall (1), door (2), window (3) with a trained SegFormer.\n"
      "Writes OUT/<name>.png (single-channel labels), with --overlay OUT/<name>_overlay.png, and with\n"
      "--confidence OUT/<name>_confidence.png (the chosen class's probability, 0–255) and OUT/confidence.csv.",
      "asbuilt segment");
  AddCommonFlags(app);
  std::string model, out;
  std::vector<std::string> inputs;
  bool overlay = false, confidence = false;
  SegmentOptions o;
  app.add_option("--model", model, "a checkpoint, a .tflite file, or a shipped model's name (default, renders, real)")
      ->required();
  app.add_option("images", inputs, "image files or folders")->required();
  app.add_option("-o,--out", out, "output folder")->required();
  app.add_flag("--overlay", overlay, "also write colour overlays");
  app.add_flag("--confidence", confidence,
               "also write how sure the model was: per image a grey map of the chosen class's probability, and "
               "confidence.csv (mean, share of pixels under 0.6)");
  const auto segment_flags = AddSegmentFlags(app, o);
  Parse(app, argc, argv);
  segment_flags->ReadGiven(SegmentOptionFields(), o);

  std::vector<fs::path> files;
  for (const std::string& in : inputs) {
    if (fs::is_directory(in)) {
      std::vector<fs::path> found;
      for (const auto& e : fs::directory_iterator(in)) {
        if (e.is_regular_file() && IsImageFile(e.path())) found.push_back(e.path());
      }
      std::sort(found.begin(), found.end());
      if (found.empty()) throw InputError(in, "", "no images in this folder (PNG, JPEG, …)");
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::is_regular_file(in)) {
      files.push_back(in);
    } else {
      throw InputError(in, "", "no such file or folder");
    }
  }
  // Read every input first: a bad file fails before anything is written.
  std::vector<cv::Mat> images;
  for (const fs::path& f : files) images.push_back(ReadColourImage(f));
  auto segmenter = LoadSegmenter(ModelPathFor(model), o);
  fs::create_directories(out);
  ProgressPrinter printer;
  std::string csv = "image,mean_confidence,unsure_share\n";
  for (size_t start = 0; start < images.size(); start += o.batch_size) {
    size_t end = std::min(images.size(), start + o.batch_size);
    std::vector<cv::Mat> batch(images.begin() + start, images.begin() + end);
    std::vector<cv::Mat> labels = segmenter->SegmentBatch(batch);
    for (size_t k = 0; k < batch.size(); ++k) {
      const std::string stem = files[start + k].stem().string();
      WritePng(fs::path(out) / (stem + ".png"), labels[k]);
      if (overlay) WritePng(fs::path(out) / (stem + "_overlay.png"), LabelOverlay(batch[k], labels[k]));
      if (confidence) {
        const ImageConfidence c = ConfidenceOf(segmenter->Probabilities(batch[k]));
        cv::Mat grey;
        c.top.convertTo(grey, CV_8U, 255.0);
        WritePng(fs::path(out) / (stem + "_confidence.png"), grey);
        csv += fmt::format("{},{:.4f},{:.4f}\n", files[start + k].filename().string(), c.mean, c.unsure_share);
      }
    }
    printer.Update({.stage = "segment",
                    .done = static_cast<std::int64_t>(end),
                    .total = static_cast<std::int64_t>(images.size())});
  }
  printer.Finish();
  if (confidence) WriteFileAtomic(fs::path(out) / "confidence.csv", csv);
  fmt::print("segmented {} image{} with {} → {}\n", images.size(), images.size() == 1 ? "" : "s",
             segmenter->info().ToString(), out);
  return 0;
}

}  // namespace asbuilt::cli
