#include "asbuilt/labels/import.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <mutex>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "asbuilt/labels/convert.h"
#include "asbuilt/labels/label_io.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"
#include "asbuilt/util/text.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

constexpr std::uint8_t kBackground = 0, kWall = 1, kDoor = 2, kWindow = 3, kIgnore = 255;

// SceneParsing-150 ids (objectInfo150.csv).
constexpr int kAdeMaxId = 150;
constexpr int kAdeWall = 1, kAdeWindowpane = 9, kAdeDoor = 15, kAdeScreenDoor = 59;
// NYUv2 40-class ids (Gupta et al. 2013).
constexpr int kNyuMaxId = 40;
constexpr int kNyuWall = 1, kNyuDoor = 8, kNyuWindow = 9;

std::string Trim(std::string s) {
  auto not_space = [](unsigned char c) { return !std::isspace(c); };
  s.erase(s.begin(), std::find_if(s.begin(), s.end(), not_space));
  s.erase(std::find_if(s.rbegin(), s.rend(), not_space).base(), s.end());
  return s;
}

cv::Mat MapIds(const fs::path& input, const std::array<std::uint8_t, 256>& table, int max_id, const char* format_name) {
  cv::Mat raw = ReadLabelImage(input);
  double lo = 0, hi = 0;
  cv::Point hi_at;
  cv::minMaxLoc(raw, &lo, &hi, nullptr, &hi_at);
  if (hi > max_id) {
    throw InputError(input.string(), "",
                     fmt::format("pixel ({}, {}) has value {}, not a {} class id (0..{})", hi_at.x, hi_at.y,
                                 static_cast<int>(hi), format_name, max_id));
  }
  cv::Mat lut(1, 256, CV_8UC1, const_cast<std::uint8_t*>(table.data()));
  cv::Mat out;
  cv::LUT(raw, lut, out);
  return out;
}

const std::map<std::string, std::uint8_t>& DefaultLabelMeNames() {
  static const std::map<std::string, std::uint8_t> kNames = {
      {"wall", kWall},
      {"walls", kWall},
      {"door", kDoor},
      {"doors", kDoor},
      {"double door", kDoor},
      {"double_door", kDoor},
      {"doorway", kDoor},
      {"screen door", kDoor},
      {"screen_door", kDoor},
      {"window", kWindow},
      {"windows", kWindow},
      {"windowpane", kWindow},
      {"window pane", kWindow},
      {"window_pane", kWindow},
      {"background", kBackground},
      {"_background_", kBackground},
      {"ignore", kIgnore},
      {"__ignore__", kIgnore},
      {"_ignore_", kIgnore},
      {"void", kIgnore},
  };
  return kNames;
}

// Sets the pixels whose centres lie inside the polygon (even-odd rule,
// half-open on edges, so two polygons sharing an edge never overlap and a
// rectangle from (4.5, 9.5) to (14.5, 29.5) covers exactly 10 × 20 pixels).
// Coordinates are pixels, (0, 0) the centre of the top-left pixel.
void FillPolygon(cv::Mat& labels, const std::vector<std::array<double, 2>>& poly, std::uint8_t id) {
  double y_min = poly[0][1], y_max = poly[0][1];
  for (const auto& p : poly) {
    y_min = std::min(y_min, p[1]);
    y_max = std::max(y_max, p[1]);
  }
  const int row0 = std::max(0, static_cast<int>(std::ceil(y_min)));
  const int row1 = std::min(labels.rows - 1, static_cast<int>(std::floor(y_max)));
  std::vector<double> xs;
  for (int y = row0; y <= row1; ++y) {
    xs.clear();
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const auto& a = poly[i];
      const auto& b = poly[(i + 1) % poly.size()];
      if ((a[1] <= y && y < b[1]) || (b[1] <= y && y < a[1])) {
        xs.push_back(a[0] + (y - a[1]) * (b[0] - a[0]) / (b[1] - a[1]));
      }
    }
    std::sort(xs.begin(), xs.end());
    std::uint8_t* row = labels.ptr<std::uint8_t>(y);
    for (std::size_t i = 0; i + 1 < xs.size(); i += 2) {
      const int x0 = std::max(0, static_cast<int>(std::ceil(xs[i])));
      const int x1 = std::min(labels.cols, static_cast<int>(std::ceil(xs[i + 1])));  // Exclusive.
      for (int x = x0; x < x1; ++x) row[x] = id;
    }
  }
}

// Sets the pixels whose centres lie strictly within `radius` of `centre`.
void FillCircle(cv::Mat& labels, const std::array<double, 2>& centre, double radius, std::uint8_t id) {
  const int row0 = std::max(0, static_cast<int>(std::floor(centre[1] - radius)));
  const int row1 = std::min(labels.rows - 1, static_cast<int>(std::ceil(centre[1] + radius)));
  const int col0 = std::max(0, static_cast<int>(std::floor(centre[0] - radius)));
  const int col1 = std::min(labels.cols - 1, static_cast<int>(std::ceil(centre[0] + radius)));
  for (int y = row0; y <= row1; ++y) {
    for (int x = col0; x <= col1; ++x) {
      if (std::hypot(x - centre[0], y - centre[1]) < radius) labels.at<std::uint8_t>(y, x) = id;
    }
  }
}

}  // namespace

const char* AnnotationFormatName(AnnotationFormat format) {
  switch (format) {
    case AnnotationFormat::kAde20k:
      return "ade20k";
    case AnnotationFormat::kNyu40:
      return "nyuv2";
    case AnnotationFormat::kLabelMe:
      return "labelme";
    case AnnotationFormat::kPalette:
      return "palette";
  }
  return "?";
}

std::optional<AnnotationFormat> ParseAnnotationFormat(std::string_view name) {
  for (AnnotationFormat f :
       {AnnotationFormat::kAde20k, AnnotationFormat::kNyu40, AnnotationFormat::kLabelMe, AnnotationFormat::kPalette}) {
    if (name == AnnotationFormatName(f)) return f;
  }
  if (name == "nyu40" || name == "nyu") return AnnotationFormat::kNyu40;
  if (name == "ade") return AnnotationFormat::kAde20k;
  return std::nullopt;
}

void ImportOptions::Check() const {
  if (format == AnnotationFormat::kPalette) {
    CheckArgument(!palette.colours.empty(), "ImportOptions.palette is empty: the palette format needs a palette file");
  }
  CheckArgument(std::isfinite(palette_threshold) && palette_threshold > 0,
                fmt::format("ImportOptions.palette_threshold = {}, must be > 0", palette_threshold));
  for (const auto& [name, id] : labelme_names) {
    CheckArgument(id <= 3 || id == kIgnore,
                  fmt::format("ImportOptions.labelme_names[\"{}\"] = {}, must be 0..3 or 255", name, id));
  }
  CheckArgument(num_threads >= 0, fmt::format("ImportOptions.num_threads = {}, must be >= 0", num_threads));
}

std::array<std::uint8_t, 256> Ade20kMapping(bool unlabeled_to_ignore) {
  std::array<std::uint8_t, 256> t;
  t.fill(kBackground);
  t[0] = unlabeled_to_ignore ? kIgnore : kBackground;
  t[kAdeWall] = kWall;
  t[kAdeWindowpane] = kWindow;
  t[kAdeDoor] = kDoor;
  t[kAdeScreenDoor] = kDoor;
  return t;
}

std::array<std::uint8_t, 256> Nyu40Mapping(bool unlabeled_to_ignore) {
  std::array<std::uint8_t, 256> t;
  t.fill(kBackground);
  t[0] = unlabeled_to_ignore ? kIgnore : kBackground;
  t[kNyuWall] = kWall;
  t[kNyuDoor] = kDoor;
  t[kNyuWindow] = kWindow;
  return t;
}

std::uint8_t LabelMeNameToId(std::string_view name, const ImportOptions& options) {
  std::string key = AsciiLower(Trim(std::string(name)));
  if (auto it = options.labelme_names.find(key); it != options.labelme_names.end()) return it->second;
  const auto& defaults = DefaultLabelMeNames();
  if (auto it = defaults.find(key); it != defaults.end()) return it->second;
  return kBackground;
}

cv::Mat ImportLabelMeJson(std::string_view json_text, const std::string& file, const ImportOptions& options) {
  JsonDiagnostics diag(file);
  nlohmann::json root = ParseJsonText(json_text, diag);
  diag.ThrowIfErrors();
  JsonField doc(root, diag);
  if (!doc.is_object()) {
    doc.AddError("expected a LabelMe object with shapes, imageWidth and imageHeight");
    diag.ThrowIfErrors();
  }
  int width = 0, height = 0;
  for (auto [key, out] : {std::pair{"imageWidth", &width}, std::pair{"imageHeight", &height}}) {
    JsonField f = doc.Required(key);
    if (auto v = f.Integer()) {
      if (*v <= 0 || *v > 32768) {
        f.AddError(fmt::format("must be in 1..32768, got {}", *v));
      } else {
        *out = static_cast<int>(*v);
      }
    }
  }
  JsonField shapes = doc.Required("shapes");
  std::optional<std::size_t> n = shapes.ArraySize();
  struct Shape {
    std::uint8_t id;
    std::string type;
    std::vector<std::array<double, 2>> points;
  };
  std::vector<Shape> parsed;
  for (std::size_t i = 0; n && i < *n; ++i) {
    JsonField s = shapes.At(i);
    if (!s.is_object()) {
      s.AddError("expected a shape object");
      continue;
    }
    Shape shape;
    if (auto v = s.Required("label").String()) shape.id = LabelMeNameToId(*v, options);
    shape.type = s.Optional("shape_type").String().value_or("polygon");
    JsonField pts = s.Required("points");
    std::optional<std::size_t> m = pts.ArraySize();
    for (std::size_t j = 0; m && j < *m; ++j) {
      if (auto p = pts.At(j).NumberArray(2)) shape.points.push_back({(*p)[0], (*p)[1]});
    }
    if (!m || shape.points.size() != *m) continue;
    if (shape.type == "polygon" && shape.points.size() < 3) {
      pts.AddError(fmt::format("a polygon needs at least 3 points, got {}", shape.points.size()));
    } else if ((shape.type == "rectangle" || shape.type == "circle") && shape.points.size() != 2) {
      pts.AddError(fmt::format("a {} needs 2 points, got {}", shape.type, shape.points.size()));
    } else if (shape.type != "polygon" && shape.type != "rectangle" && shape.type != "circle") {
      s.Optional("shape_type").AddWarning(fmt::format("shape type \"{}\" has no area: skipped", shape.type));
      continue;
    }
    parsed.push_back(std::move(shape));
  }
  diag.ThrowIfErrors();
  diag.LogWarnings();

  // Draw in file order: a later shape covers an earlier one (LabelMe's own
  // export does the same).
  cv::Mat labels(height, width, CV_8UC1, cv::Scalar(kBackground));
  for (const Shape& s : parsed) {
    if (s.type == "circle") {
      FillCircle(labels, s.points[0], std::hypot(s.points[1][0] - s.points[0][0], s.points[1][1] - s.points[0][1]),
                 s.id);
    } else if (s.type == "rectangle") {
      const double x0 = s.points[0][0], y0 = s.points[0][1], x1 = s.points[1][0], y1 = s.points[1][1];
      FillPolygon(labels, {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, s.id);
    } else {
      FillPolygon(labels, s.points, s.id);
    }
  }
  return labels;
}

cv::Mat ImportAnnotation(const fs::path& input, const ImportOptions& options) {
  switch (options.format) {
    case AnnotationFormat::kAde20k:
      return MapIds(input, Ade20kMapping(options.unlabeled_to_ignore), kAdeMaxId, "SceneParsing-150");
    case AnnotationFormat::kNyu40:
      return MapIds(input, Nyu40Mapping(options.unlabeled_to_ignore), kNyuMaxId, "NYUv2-40");
    case AnnotationFormat::kLabelMe:
      return ImportLabelMeJson(ReadFile(input), input.string(), options);
    case AnnotationFormat::kPalette:
      return ConvertIdMap(ReadColourImage(input), options.palette, options.palette_threshold);
  }
  throw InvalidArgument("ImportAnnotation: unknown format");
}

std::string ImportSummary::BriefReport() const {
  std::int64_t total = 0;
  for (std::int64_t n : class_pixels) total += n;
  std::string out = fmt::format("imported {} {} annotation{} in {:.2f} s", imported, AnnotationFormatName(format),
                                imported == 1 ? "" : "s", seconds);
  if (total > 0) {
    static const char* kNames[] = {"background", "wall", "door", "window", "ignore"};
    out += ":";
    for (int i = 0; i < 5; ++i)
      out += fmt::format("{} {} {:.1f} %", i ? "," : "", kNames[i], 100.0 * class_pixels[i] / total);
  }
  if (!failed.empty()) out += fmt::format("; {} failed", failed.size());
  return out;
}

ImportSummary ImportAnnotations(const ImportOptions& options, const std::vector<fs::path>& inputs,
                                const fs::path& output_dir, const ProgressCallback& progress) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  ImportSummary summary;
  summary.format = options.format;
  std::mutex mutex;
  int done = 0;
  tbb::task_arena arena(options.num_threads > 0 ? options.num_threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, inputs.size(), [&](std::size_t i) {
      const fs::path& input = inputs[i];
      std::optional<Problem> problem;
      std::array<std::int64_t, 5> counts{};
      try {
        cv::Mat labels = ImportAnnotation(input, options);
        WriteLabelImage(output_dir / (input.stem().string() + ".png"), labels);
        for (int y = 0; y < labels.rows; ++y) {
          const std::uint8_t* p = labels.ptr<std::uint8_t>(y);
          for (int x = 0; x < labels.cols; ++x) ++counts[p[x] < 4 ? p[x] : 4];
        }
      } catch (const InputError& e) {
        problem = e.problems().front();
      } catch (const Error& e) {
        problem = Problem{input.string(), "", e.what()};
      }
      std::lock_guard lock(mutex);
      if (problem) {
        summary.failed.push_back(*problem);
      } else {
        ++summary.imported;
        for (int k = 0; k < 5; ++k) summary.class_pixels[k] += counts[k];
      }
      ReportProgress(progress, {"import", ++done, static_cast<std::int64_t>(inputs.size()), input.filename().string()});
    });
  });
  std::sort(summary.failed.begin(), summary.failed.end(),
            [](const Problem& a, const Problem& b) { return a.file < b.file; });
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

std::vector<fs::path> ListAnnotationFiles(const fs::path& dir, AnnotationFormat format) {
  if (format != AnnotationFormat::kLabelMe) return ListImageFiles(dir);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string(), "", "not a folder");
  std::vector<fs::path> out;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    const fs::path& p = entry.path();
    std::string name = p.filename().string();
    if (name.empty() || name[0] == '.' || IsAtomicTempName(p) || !entry.is_regular_file(ec)) continue;
    if (AsciiLower(p.extension().string()) == ".json") out.push_back(p);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace asbuilt
