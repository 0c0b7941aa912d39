#include "asbuilt/labels/agreement.h"

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt {

void AgreementOptions::Check() const {
  CheckArgument(boundary_band_px >= 1 && boundary_band_px <= 32,
                fmt::format("AgreementOptions.boundary_band_px = {}, must be in 1..32", boundary_band_px));
}

void LabelAgreement::Add(const LabelAgreement& o) {
  pixels += o.pixels;
  agree += o.agree;
  band_pixels += o.band_pixels;
  band_agree += o.band_agree;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) confusion[i][j] += o.confusion[i][j];
  }
}

std::string LabelAgreement::ToString() const {
  return fmt::format("agreement {:.2f} % (band {:.2f} %, interior {:.2f} %) over {} px", 100 * Overall(), 100 * Band(),
                     100 * Interior(), pixels);
}

LabelAgreement CompareLabels(const cv::Mat& predicted, const cv::Mat& exact, const AgreementOptions& options) {
  options.Check();
  CheckArgument(predicted.type() == CV_8UC1 && exact.type() == CV_8UC1, "CompareLabels: label maps must be CV_8UC1");
  CheckArgument(predicted.size() == exact.size(), "CompareLabels: label maps differ in size");
  // Band: the neighbourhood's min and max exact label differ.
  const int w = 2 * options.boundary_band_px + 1;
  cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, {w, w});
  cv::Mat lo, hi;
  cv::erode(exact, lo, kernel, {-1, -1}, 1, cv::BORDER_REPLICATE);
  cv::dilate(exact, hi, kernel, {-1, -1}, 1, cv::BORDER_REPLICATE);
  LabelAgreement a;
  for (int y = 0; y < exact.rows; ++y) {
    const std::uint8_t* p = predicted.ptr<std::uint8_t>(y);
    const std::uint8_t* e = exact.ptr<std::uint8_t>(y);
    const std::uint8_t* l = lo.ptr<std::uint8_t>(y);
    const std::uint8_t* h = hi.ptr<std::uint8_t>(y);
    for (int x = 0; x < exact.cols; ++x) {
      if (e[x] == 255) continue;
      const bool same = p[x] == e[x];
      const bool band = l[x] != h[x];
      ++a.pixels;
      a.agree += same;
      a.band_pixels += band;
      a.band_agree += band && same;
      ++a.confusion[e[x] < 4 ? e[x] : 4][p[x] < 4 ? p[x] : 4];
    }
  }
  return a;
}

}  // namespace asbuilt
