#include "asbuilt/imageio/image_io.h"

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {

void WriteImageAtomic(const std::filesystem::path& path, const cv::Mat& image) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  AtomicFile file(path);
  bool ok = false;
  try {
    ok = cv::imwrite(file.temp_path().string(), image, {cv::IMWRITE_PNG_COMPRESSION, 1});
  } catch (const cv::Exception& e) {
    throw Error(fmt::format("{}: cannot write image: {}", path.string(), e.what()));
  }
  if (!ok) throw Error(fmt::format("{}: cannot write image", path.string()));
  file.Commit();
}

}  // namespace asbuilt
