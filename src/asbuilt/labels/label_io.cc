#include "asbuilt/labels/label_io.h"

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;

void WriteLabelImage(const fs::path& path, const cv::Mat& labels) {
  CheckArgument(labels.type() == CV_8UC1, "WriteLabelImage: labels must be CV_8UC1");
  WriteImageAtomic(path, labels);
}

}  // namespace asbuilt
