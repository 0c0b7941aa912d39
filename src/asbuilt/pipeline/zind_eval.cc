#include "asbuilt/pipeline/zind_eval.h"

#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/pano/layout_labels.h"
#include "asbuilt/pano/pano_views.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

std::string F3(double x) { return std::isnan(x) ? "–" : fmt::format("{:.3f}", x); }

// Labels with the rows at or below the horizon set to ignore.
cv::Mat UpperHalf(const cv::Mat& labels, const PanoView& view) {
  cv::Mat upper = labels.clone();
  for (int v = 0; v < upper.rows; ++v) {
    if (view.RayInWorld(Vec2(view.camera.cx, v)).z() <= 0) upper.row(v).setTo(255);
  }
  return upper;
}

SegmentationMetrics Metrics(const ConfusionMatrix& cm, std::int64_t images) {
  SegmentationMetrics m = ComputeMetrics(cm);
  m.images = images;
  return m;
}

// One tile of a contact sheet: the layout labels over the photo above the
// prediction over the photo, half size, with the horizon dashed and a caption.
cv::Mat SheetTile(const cv::Mat& bgr, const cv::Mat& truth, const cv::Mat& pred, const PanoView& view,
                  const std::string& caption) {
  const cv::Mat top = AsMat(DrawLabelOverlay(AsImage(bgr), AsImage(truth)));
  const cv::Mat bottom = AsMat(DrawLabelOverlay(AsImage(bgr), AsImage(pred)));
  cv::Mat tile;
  cv::vconcat(top, bottom, tile);
  cv::resize(tile, tile, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
  // Horizon: the first row whose ray points at or below it.
  int horizon = -1;
  for (int v = 0; v < bgr.rows && horizon < 0; ++v) {
    if (view.RayInWorld(Vec2(view.camera.cx, v)).z() <= 0) horizon = v;
  }
  if (horizon > 0) {
    for (int half = 0; half < 2; ++half) {
      const int y = (half * bgr.rows + horizon) / 2;
      for (int x = 0; x < tile.cols; x += 8)
        cv::line(tile, {x, y}, {std::min(x + 4, tile.cols - 1), y}, {255, 255, 255});
    }
  }
  cv::putText(tile, caption, {4, 14}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 0, 0}, 3);
  cv::putText(tile, caption, {4, 14}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {255, 255, 255}, 1);
  cv::putText(tile, "layout labels", {4, tile.rows / 2 - 6}, cv::FONT_HERSHEY_SIMPLEX, 0.35, {255, 255, 255}, 1);
  cv::putText(tile, "segmenter", {4, tile.rows - 6}, cv::FONT_HERSHEY_SIMPLEX, 0.35, {255, 255, 255}, 1);
  cv::line(tile, {0, tile.rows / 2}, {tile.cols - 1, tile.rows / 2}, {0, 0, 0}, 1);
  return tile;
}

// Tiles in rows of `per_row`, with a 2-pixel gap.
cv::Mat Sheet(const std::vector<cv::Mat>& tiles, int per_row) {
  const int w = tiles.front().cols, h = tiles.front().rows, gap = 2;
  const int rows = (static_cast<int>(tiles.size()) + per_row - 1) / per_row;
  cv::Mat sheet(rows * (h + gap) - gap, per_row * (w + gap) - gap, CV_8UC3, cv::Scalar(40, 40, 40));
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const int r = static_cast<int>(i) / per_row, c = static_cast<int>(i) % per_row;
    tiles[i].copyTo(sheet(cv::Rect(c * (w + gap), r * (h + gap), w, h)));
  }
  return sheet;
}

std::string ClassFigures(const SegmentationMetrics& m) {
  std::string s;
  for (std::size_t c = 1; c < m.classes.size(); ++c)
    s += fmt::format(" {} {}", m.classes[c].name, F3(m.classes[c].iou));
  return s;
}

std::string Table(const SegmentationMetrics& m) {
  std::string s = "| class | IoU | precision | recall | label px | pred px |\n|---|---|---|---|---|---|\n";
  for (const ClassMetrics& c : m.classes) {
    s += fmt::format("| {} | {} | {} | {} | {} | {} |\n", c.name, F3(c.iou), F3(c.precision), F3(c.recall),
                     c.label_pixels, c.pred_pixels);
  }
  s += fmt::format("| **mean** | **{}** | {} | {} | | |\n", F3(m.miou), F3(m.mprecision), F3(m.mrecall));
  return s;
}

std::string HtmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

std::string Report(const ZindEvalSummary& s) {
  std::string html =
      "<!doctype html><meta charset=utf-8><title>asbuilt eval zind</title>\n"
      "<style>body{font-family:sans-serif;margin:1em}table{border-collapse:collapse}"
      "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}img{max-width:100%}"
      ".notice{background:#fee;padding:.5em;font-weight:bold}</style>\n";
  html += fmt::format("<p class=notice>{}</p>\n", kZindNotice);
  html += fmt::format("<h1>Segmenter on real photos (ZInD)</h1><p>{}<br>{} on {}<br>{}</p>\n",
                      HtmlEscape(s.BriefReport()), HtmlEscape(s.model), HtmlEscape(s.tour), HtmlEscape(s.views));
  html +=
      "<p>Labels are the annotated room layout: furniture in front of a wall counts as wall; a door covers its "
      "whole opening; ZInD passages are ignored. The upper half (above the horizon) is where furniture rarely "
      "hides the walls. In each sheet: layout labels over the photo (top), the segmenter (bottom); wall blue, "
      "door green, window red, ignored grey; the dashed line is the horizon.</p>\n";
  html +=
      "<table><tr><th>panorama</th><th>room</th><th>mIoU</th><th>wall</th><th>door</th><th>window</th>"
      "<th>upper mIoU</th></tr>\n";
  for (const ZindPanoramaScore& p : s.per_panorama) {
    html += fmt::format(
        "<tr><td><a href='#{0}'>{0}</a></td><td>{1}</td><td>{2}</td><td>{3}</td><td>{4}</td><td>{5}</td>"
        "<td>{6}</td></tr>\n",
        HtmlEscape(p.name), HtmlEscape(p.label), F3(p.whole.miou), F3(p.whole.classes[1].iou),
        F3(p.whole.classes[2].iou), F3(p.whole.classes[3].iou), F3(p.upper.miou));
  }
  html += "</table>\n";
  for (const ZindPanoramaScore& p : s.per_panorama) {
    if (p.sheet.empty()) continue;
    html += fmt::format("<h2 id='{0}'>{0} ({1}): mIoU {2}, upper half {3}</h2><img src='{4}' loading=lazy>\n",
                        HtmlEscape(p.name), HtmlEscape(p.label), F3(p.whole.miou), F3(p.upper.miou), p.sheet);
  }
  return html;
}

}  // namespace

void ZindEvalOptions::Check() const {
  turn.Check();
  CheckArgument(max_panoramas >= 0, fmt::format("ZindEvalOptions.max_panoramas = {}, must be >= 0", max_panoramas));
  CheckArgument(batch_size > 0, fmt::format("ZindEvalOptions.batch_size = {}, must be > 0", batch_size));
}

std::string ZindEvalSummary::BriefReport() const {
  return fmt::format("ZInD {} panoramas, {} views: mIoU {} ({}); upper half mIoU {} ({})", panoramas, images,
                     F3(whole.miou), ClassFigures(whole).substr(1), F3(upper.miou), ClassFigures(upper).substr(1));
}

std::string ZindEvalSummary::ToMarkdown() const {
  std::string s = fmt::format("**{}.**\n\n", kZindNotice);
  s += fmt::format("{} on {} ({} panoramas: the primary ones taken inside their room), {}; {} views in {:.0f} s.\n\n",
                   model, tour, panoramas, views, images, seconds);
  s += "Labels are the annotated room layout (walls between floor and ceiling, doors and windows from their "
       "annotated segments and heights, ZInD passages ignored): furniture in front of a wall counts as wall. "
       "The upper half (pixels above the horizon) is where furniture rarely hides the layout.\n\n";
  s += "Whole views:\n\n" + Table(whole) + "\nUpper half (above the horizon):\n\n" + Table(upper);
  s +=
      "\nPer panorama (mIoU; wall, door, window IoU; upper-half mIoU). A class a room lacks scores 0 where the "
      "segmenter predicts it anyway (mmseg's definition), – where neither has it:\n\n| panorama | room | mIoU | wall | "
      "door | window | upper mIoU |\n|---|---|---|---|---|---|---|\n";
  for (const ZindPanoramaScore& p : per_panorama) {
    s += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", p.name, p.label, F3(p.whole.miou),
                     F3(p.whole.classes[1].iou), F3(p.whole.classes[2].iou), F3(p.whole.classes[3].iou),
                     F3(p.upper.miou));
  }
  return s;
}

nlohmann::json ZindEvalSummary::ToJson() const {
  nlohmann::json per = nlohmann::json::array();
  for (const ZindPanoramaScore& p : per_panorama) {
    per.push_back({{"name", p.name},
                   {"label", p.label},
                   {"views", p.views},
                   {"whole", p.whole.ToJson()},
                   {"upper", p.upper.ToJson()},
                   {"sheet", p.sheet}});
  }
  return {{"notice", kZindNotice},  {"tour", tour},      {"model", model},          {"views", views},
          {"panoramas", panoramas}, {"images", images},  {"whole", whole.ToJson()}, {"upper", upper.ToJson()},
          {"per_panorama", per},    {"seconds", seconds}};
}

ZindEvalSummary EvaluateOnZind(Segmenter& segmenter, const ZindTour& tour, const fs::path& out_dir,
                               const ZindEvalOptions& options, const ProgressCallback& progress, std::stop_token stop) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  std::vector<const ZindPanorama*> panoramas = tour.BenchmarkPanoramas();
  CheckArgument(!panoramas.empty(), fmt::format("{}: no primary panorama taken inside its room", tour.file.string()));
  if (options.max_panoramas > 0 && panoramas.size() > static_cast<std::size_t>(options.max_panoramas)) {
    panoramas.resize(static_cast<std::size_t>(options.max_panoramas));
  }
  const std::vector<PanoView> views = TurnInPlaceViews(options.turn);
  const int n_classes = segmenter.info().config.num_classes;
  const PinholeCamera& cam = views.front().camera;

  ZindEvalSummary summary;
  summary.tour = tour.dir.string();
  summary.model = options.segmenter_name.empty() ? segmenter.info().ToString() : options.segmenter_name;
  summary.views = fmt::format("{} views {}x{}, fx {:g}, fy {:g}, yaw step {:g}°, pitch {:g}°, layout_{}", views.size(),
                              cam.width_px, cam.height_px, cam.fx, cam.fy, options.turn.yaw_step_deg,
                              options.turn.pitch_deg, ZindLayoutKindName(options.layout));
  const bool sheets = !out_dir.empty() && options.write_sheets;
  if (!out_dir.empty()) fs::create_directories(out_dir);
  spdlog::info("{}", kZindNotice);

  ConfusionMatrix whole_cm(n_classes), upper_cm(n_classes);
  const std::int64_t total = static_cast<std::int64_t>(panoramas.size() * views.size());
  for (const ZindPanorama* pano : panoramas) {
    if (stop.stop_requested()) break;
    const Image equirect = ReadEquirect(pano->image);
    ConfusionMatrix pano_whole(n_classes), pano_upper(n_classes);
    std::vector<cv::Mat> tiles;
    for (std::size_t first = 0; first < views.size(); first += static_cast<std::size_t>(options.batch_size)) {
      const std::size_t end = std::min(views.size(), first + static_cast<std::size_t>(options.batch_size));
      std::vector<cv::Mat> images, labels;
      for (std::size_t i = first; i < end; ++i) {
        images.push_back(AsMat(RenderPanoView(equirect, views[i])));
        labels.push_back(AsMat(LayoutLabels(*pano, views[i], options.layout)));
      }
      const std::vector<cv::Mat> predictions = segmenter.SegmentBatch(images);
      for (std::size_t k = 0; k < images.size(); ++k) {
        const PanoView& view = views[first + k];
        const cv::Mat upper = UpperHalf(labels[k], view);
        ConfusionMatrix view_cm(n_classes);
        view_cm.Add(labels[k], predictions[k]);
        pano_whole.Merge(view_cm);
        pano_upper.Add(upper, predictions[k]);
        if (sheets) {
          tiles.push_back(SheetTile(images[k], labels[k], predictions[k], view,
                                    fmt::format("yaw {:g}  mIoU {}", view.yaw_deg, F3(ComputeMetrics(view_cm).miou))));
        }
      }
      summary.images += static_cast<int>(images.size());
      ReportProgress(progress, {.stage = "eval zind", .done = summary.images, .total = total, .detail = pano->pano_id});
    }
    ZindPanoramaScore score;
    score.name = pano->Name();
    score.label = pano->label;
    score.views = static_cast<int>(views.size());
    score.whole = Metrics(pano_whole, score.views);
    score.upper = Metrics(pano_upper, score.views);
    if (sheets) {
      score.sheet = fmt::format("sheets/{}_{}.jpg", pano->partial_room_id, pano->pano_id);
      const fs::path path = out_dir / score.sheet;
      fs::create_directories(path.parent_path());
      AtomicFile file(path);
      if (!cv::imwrite(file.temp_path().string(), Sheet(tiles, std::min<int>(6, static_cast<int>(tiles.size()))),
                       {cv::IMWRITE_JPEG_QUALITY, 85})) {
        throw Error(path.string() + ": cannot write");
      }
      file.Commit();
    }
    whole_cm.Merge(pano_whole);
    upper_cm.Merge(pano_upper);
    summary.per_panorama.push_back(std::move(score));
    ++summary.panoramas;
  }
  summary.whole = Metrics(whole_cm, summary.images);
  summary.upper = Metrics(upper_cm, summary.images);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!out_dir.empty()) {
    summary.out_dir = out_dir;
    WriteFileAtomic(out_dir / "metrics.json", summary.ToJson().dump(1) + "\n");
    WriteFileAtomic(out_dir / "metrics.md", summary.ToMarkdown());
    if (sheets) WriteFileAtomic(out_dir / "report.html", Report(summary));
  }
  return summary;
}

}  // namespace asbuilt
