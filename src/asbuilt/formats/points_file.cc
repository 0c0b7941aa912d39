#include "asbuilt/formats/points_file.h"

#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;

const char* PointSourceName(PointSource s) {
  switch (s) {
    case PointSource::kCorner:
      return "corner";
    case PointSource::kDense:
      return "dense";
    case PointSource::kEdge:
      return "edge";
    case PointSource::kOther:
      return "other";
    case PointSource::kBoundary:
      return "boundary";
    case PointSource::kContact:
      return "contact";
    case PointSource::kVertex:
      return "vertex";
  }
  return "other";
}

std::vector<ClassPoint> ReadPoints(const fs::path& path) { return ParsePoints(ReadFile(path), path.string()); }

std::vector<ClassPoint> ParsePoints(std::string_view text_view, const std::string& name) {
  std::string text(text_view);
  std::vector<ClassPoint> points;
  std::vector<Problem> problems;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  auto fail = [&](const std::string& message) {
    if (problems.size() < 20) {
      problems.push_back({name, fmt::format("line {}", line_no), message});
    }
  };
  while (std::getline(in, line)) {
    ++line_no;
    auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    std::vector<std::string> cols;
    for (std::string c; fields >> c;) cols.push_back(c);
    if (cols.size() < 4 || cols.size() > 7) {
      fail(fmt::format("expected 4 to 7 columns (class x y z [sigma_m source frame]), got {}", cols.size()));
      continue;
    }
    ClassPoint p;
    const std::string& cls = cols[0];
    if (cls == "wall" || cls == "1") {
      p.label = LabelClass::kWall;
    } else if (cls == "door" || cls == "2") {
      p.label = LabelClass::kDoor;
    } else if (cls == "window" || cls == "3") {
      p.label = LabelClass::kWindow;
    } else {
      fail(fmt::format("unknown class \"{}\" (expected wall, door or window)", cls));
      continue;
    }
    bool ok = true;
    double v[4] = {0, 0, 0, 0};
    for (std::size_t i = 1; i < std::min<std::size_t>(cols.size(), 5); ++i) {
      try {
        std::size_t used = 0;
        v[i - 1] = std::stod(cols[i], &used);
        if (used != cols[i].size() || !std::isfinite(v[i - 1])) throw std::invalid_argument("");
      } catch (const std::exception&) {
        fail(fmt::format("column {}: expected a finite number, got \"{}\"", i + 1, cols[i]));
        ok = false;
        break;
      }
    }
    if (!ok) continue;
    if (v[3] < 0) {
      fail(fmt::format("sigma_m must be >= 0, got {}", v[3]));
      continue;
    }
    p.position_m = Vec3(v[0], v[1], v[2]);
    p.sigma_m = v[3];
    if (cols.size() >= 6) {
      const std::string& s = cols[5];
      if (s == "corner")
        p.source = PointSource::kCorner;
      else if (s == "dense")
        p.source = PointSource::kDense;
      else if (s == "edge")
        p.source = PointSource::kEdge;
      else if (s == "other")
        p.source = PointSource::kOther;
      else if (s == "boundary")
        p.source = PointSource::kBoundary;
      else if (s == "contact")
        p.source = PointSource::kContact;
      else if (s == "vertex")
        p.source = PointSource::kVertex;
      else {
        fail(fmt::format("unknown source \"{}\" (corner, dense, edge, boundary, contact, vertex, other)", s));
        continue;
      }
    }
    if (cols.size() == 7) {
      try {
        p.frame = std::stoi(cols[6]);
      } catch (const std::exception&) {
        fail(fmt::format("column 7: expected a frame index, got \"{}\"", cols[6]));
        continue;
      }
    }
    points.push_back(p);
  }
  if (!problems.empty()) throw InputError(problems);
  return points;
}

void WritePoints(const std::vector<ClassPoint>& points, const fs::path& path) {
  std::string out = "# asbuilt points v1\n# class x y z sigma_m source frame\n";
  out.reserve(out.size() + points.size() * 56);
  for (const ClassPoint& p : points) {
    out += fmt::format("{} {:.5f} {:.5f} {:.5f} {:.5f} {} {}\n", LabelClassName(p.label), p.position_m.x(),
                       p.position_m.y(), p.position_m.z(), p.sigma_m, PointSourceName(p.source), p.frame);
  }
  WriteFileAtomic(path, out);
}

}  // namespace asbuilt
