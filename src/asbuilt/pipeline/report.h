#ifndef ASBUILT_PIPELINE_REPORT_H_
#define ASBUILT_PIPELINE_REPORT_H_

// report.html: one self-contained file (inline images and styles, no
// scripts from the network) that shows what a survey measured and how far
// to trust it.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/pipeline/survey.h"

namespace asbuilt {

// Pictures of one frame, already encoded (JPEG or PNG bytes).
struct ReportFrame {
  int index = -1;
  double yaw_deg = 0.0;
  std::string left_jpeg;       // Capture thumbnail.
  std::string overlay_jpeg;    // Segmentation overlay.
  std::string disparity_jpeg;  // Colour disparity.
  std::string cues;            // FrameCues::BriefReport().
};

struct SurveyReport {
  std::string title;  // "Survey of capture.json".
  std::filesystem::path capture_path;
  SurveySummary summary;
  Plan plan;
  std::optional<Plan> truth;
  std::vector<ReportFrame> frames;
  std::string points_plot_png;  // Top-down plot of the class points.
  std::string layout_jpeg;      // Panorama with its layout drawn (--pano-layout); may be empty.
  std::string layout_caption;   // What the layout found (PanoLayout::BriefReport()).
  std::string plan_svg;         // The drawing (plan.svg text); may be empty.
};

// The HTML text of the report.
std::string SurveyReportHtml(const SurveyReport& report);
// Writes it atomically.
void WriteSurveyReport(const SurveyReport& report, const std::filesystem::path& path);

// Escapes &, <, >, " and ' for HTML text and attributes.
std::string HtmlEscape(std::string_view text);

}  // namespace asbuilt

#endif  // ASBUILT_PIPELINE_REPORT_H_
