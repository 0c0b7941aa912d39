#include "asbuilt/formats/points_ply.h"

#include <string>

#include <fmt/format.h>

#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;

void WritePointsPly(const std::vector<ClassPoint>& points, const fs::path& path) {
  static const int kColour[4][3] = {{128, 128, 128}, {150, 160, 190}, {150, 90, 40}, {40, 200, 220}};
  std::string out = fmt::format(
      "ply\nformat ascii 1.0\ncomment asbuilt points (world "
      "metres; wall, door, window)\n"
      "element vertex {}\nproperty float x\nproperty float "
      "y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar "
      "blue\nproperty uchar label\nend_header\n",
      points.size());
  for (const ClassPoint& p : points) {
    const int c = static_cast<int>(p.label) & 3;
    out += fmt::format("{:.4f} {:.4f} {:.4f} {} {} {} {}\n", p.position_m.x(), p.position_m.y(), p.position_m.z(),
                       kColour[c][0], kColour[c][1], kColour[c][2], c);
  }
  WriteFileAtomic(path, out);
}

}  // namespace asbuilt
