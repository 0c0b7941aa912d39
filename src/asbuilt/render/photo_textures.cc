#include "asbuilt/render/photo_textures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <numbers>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/text.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

bool Contains(const std::string& s, std::initializer_list<const char*> words) {
  for (const char* w : words) {
    if (s.find(w) != std::string::npos) return true;
  }
  return false;
}

std::uint32_t BigEndian32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | p[3];
}

float SrgbToLinear(float x) { return x <= 0.04045f ? x / 12.92f : std::pow((x + 0.055f) / 1.055f, 2.4f); }

// 8-bit BGR → linear RGB float, through a 256-entry table.
cv::Mat LinearFromSrgb8(const cv::Mat& bgr) {
  static const std::array<float, 256> kTable = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = SrgbToLinear(i / 255.0f);
    return t;
  }();
  cv::Mat out(bgr.rows, bgr.cols, CV_32FC3);
  for (int y = 0; y < bgr.rows; ++y) {
    const auto* in = bgr.ptr<cv::Vec3b>(y);
    auto* o = out.ptr<cv::Vec3f>(y);
    for (int x = 0; x < bgr.cols; ++x) o[x] = cv::Vec3f(kTable[in[x][2]], kTable[in[x][1]], kTable[in[x][0]]);
  }
  return out;
}

std::optional<Photo> LoadPhoto(const fs::path& path, PhotoKind kind, int max_side_px) {
  const std::string ext = AsciiLower(path.extension().string());
  cv::Mat linear;
  if (ext == ".pat") {
    linear = LinearFromSrgb8(AsMat(ReadGimpPattern(path)));
  } else if (ext == ".exr" || ext == ".hdr") {
    AllowOpenExr();  // Files of a Debian package.
    cv::Mat m = ReadColourImageAnyDepth(path);
    m.convertTo(m, CV_32FC3);
    cv::cvtColor(m, linear, cv::COLOR_BGR2RGB);
    cv::max(linear, 0.0, linear);
  } else {
    linear = LinearFromSrgb8(ReadColourImage(path));
  }
  if (linear.empty()) return std::nullopt;
  const int side = std::max(linear.cols, linear.rows);
  if (side > max_side_px) {
    double f = static_cast<double>(max_side_px) / side;
    cv::resize(linear, linear, cv::Size(), f, f, cv::INTER_AREA);
  }
  Photo photo;
  photo.path = path.string();
  photo.kind = kind;
  photo.linear_rgb = AsImage(linear);
  cv::Scalar m = cv::mean(linear);
  photo.mean = Vec3f(static_cast<float>(m[0]), static_cast<float>(m[1]), static_cast<float>(m[2]));
  photo.mean_luminance = 0.2126f * photo.mean.x() + 0.7152f * photo.mean.y() + 0.0722f * photo.mean.z();
  if (!(photo.mean_luminance > 1e-6f)) return std::nullopt;  // Black or broken.
  return photo;
}

}  // namespace

const char* PhotoKindName(PhotoKind kind) {
  switch (kind) {
    case PhotoKind::kWood:
      return "wood";
    case PhotoKind::kStone:
      return "stone";
    case PhotoKind::kFabric:
      return "fabric";
    case PhotoKind::kPaper:
      return "paper";
    case PhotoKind::kEnvironment:
      return "environment";
    case PhotoKind::kView:
      return "view";
  }
  return "?";
}

Vec3f Photo::Sample(float u, float v, bool clamp_v) const {
  const int w = linear_rgb.width(), h = linear_rgb.height();
  float x = (u - std::floor(u)) * w - 0.5f;
  float y = (clamp_v ? std::clamp(v, 0.0f, 1.0f) : v - std::floor(v)) * h - 0.5f;
  int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
  float fx = x - x0, fy = y - y0;
  auto at = [&](int xx, int yy) {
    xx = ((xx % w) + w) % w;
    yy = clamp_v ? std::clamp(yy, 0, h - 1) : ((yy % h) + h) % h;
    const float* c = linear_rgb.Row<float>(yy) + 3 * xx;
    return Vec3f(c[0], c[1], c[2]);
  };
  return (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) +
         (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
}

Vec3f Photo::Outside(const Vec3f& dir, float yaw_rad) const {
  const float azimuth = std::atan2(dir.y(), dir.x()) + yaw_rad;  // Counter-clockwise from +X.
  const float elevation = std::asin(std::clamp(dir.z(), -1.0f, 1.0f));
  if (kind == PhotoKind::kEnvironment) {
    // Equirectangular: u grows clockwise seen from above, v = 0 at the zenith.
    float u = 0.5f - azimuth / (2 * std::numbers::pi_v<float>);
    float v = 0.5f - elevation / std::numbers::pi_v<float>;
    return Sample(u, v, true);
  }
  // A flat photo over 120° of azimuth, mirrored (ping-pong) round the circle.
  constexpr float kSpanRad = 120.0f * std::numbers::pi_v<float> / 180.0f;
  float s = azimuth / kSpanRad;
  float f = s - 2.0f * std::floor(0.5f * s);  // [0, 2)
  float u = f < 1.0f ? f : 2.0f - f;
  constexpr float kLow = -25.0f * std::numbers::pi_v<float> / 180.0f,
                  kHigh = 45.0f * std::numbers::pi_v<float> / 180.0f;
  float v = (kHigh - elevation) / (kHigh - kLow);
  return Sample(std::clamp(u, 0.0f, 0.999f), v, true);
}

std::vector<fs::path> DefaultPhotoDirs() {
  std::vector<fs::path> dirs = {"/usr/share/gimp/2.0/patterns", "/usr/share/blender/datafiles/studiolights/world"};
  std::error_code ec;
  if (fs::is_directory("/usr/share/blender", ec)) {
    std::vector<fs::path> versioned;
    for (const auto& entry : fs::directory_iterator("/usr/share/blender", ec)) {
      fs::path world = entry.path() / "datafiles/studiolights/world";
      if (entry.path().filename() != "datafiles" && fs::is_directory(world, ec)) versioned.push_back(world);
    }
    std::sort(versioned.begin(), versioned.end());
    dirs.insert(dirs.end(), versioned.begin(), versioned.end());
  }
  return dirs;
}

void PhotoLibraryOptions::Check() const {
  CheckArgument(max_side_px >= 8 && max_side_px <= 16384,
                fmt::format("PhotoLibraryOptions.max_side_px = {}, must be in [8, 16384]", max_side_px));
}

std::optional<PhotoKind> ClassifyPhoto(const fs::path& path) {
  const std::string ext = AsciiLower(path.extension().string());
  const std::string name = AsciiLower(path.stem().string());
  const std::string full = AsciiLower(path.generic_string());
  if (ext == ".pat") {
    const std::string folder = AsciiLower(path.parent_path().filename().string());
    if (folder == "wood") {
      if (Contains(name, {"bark", "cork"})) return std::nullopt;  // Not a room surface; cork is blotchy.
      return PhotoKind::kWood;
    }
    if (folder == "stone") {
      if (Contains(name, {"crater", "moon", "amethyst", "rock", "ground", "cracked"})) return std::nullopt;
      return PhotoKind::kStone;
    }
    if (folder == "fabric") return PhotoKind::kFabric;
    if (folder == "animal") return name == "leather" ? std::optional(PhotoKind::kFabric) : std::nullopt;
    if (folder == "paper") return PhotoKind::kPaper;
    return std::nullopt;  // Legacy, Food, Water, Sky, Plant: not room surfaces.
  }
  if (ext == ".exr" || ext == ".hdr") {
    if (Contains(full, {"matcap"}) || Contains(name, {"studio", "interior"})) return std::nullopt;
    return PhotoKind::kEnvironment;
  }
  if (ext != ".png" && ext != ".jpg" && ext != ".jpeg" && ext != ".webp") return std::nullopt;
  if (Contains(name, {"wood", "parquet", "oak", "pine", "walnut"})) return PhotoKind::kWood;
  if (Contains(name, {"marble", "stone", "granite", "tile", "slate", "brick"})) return PhotoKind::kStone;
  if (Contains(name, {"fabric", "carpet", "cloth", "linen", "burlap", "leather", "rug"})) return PhotoKind::kFabric;
  if (Contains(name, {"paper", "plaster"})) return PhotoKind::kPaper;
  if (Contains(full, {"backgrounds/", "wallpapers/"})) return PhotoKind::kView;
  return std::nullopt;
}

Image ReadGimpPattern(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot open");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.size() < 24) throw InputError(path.string(), "header", "shorter than the 24-byte header");
  const std::uint32_t header_size = BigEndian32(&bytes[0]);
  const std::uint32_t version = BigEndian32(&bytes[4]);
  const std::uint32_t width = BigEndian32(&bytes[8]);
  const std::uint32_t height = BigEndian32(&bytes[12]);
  const std::uint32_t channels = BigEndian32(&bytes[16]);
  if (std::string(bytes.begin() + 20, bytes.begin() + 24) != "GPAT") {
    throw InputError(path.string(), "header.magic", "not \"GPAT\"");
  }
  if (version != 1) throw InputError(path.string(), "header.version", fmt::format("{}, expected 1", version));
  if (width == 0 || height == 0 || width > 16384 || height > 16384) {
    throw InputError(path.string(), "header.size", fmt::format("{}x{} out of range", width, height));
  }
  if (channels < 1 || channels > 4) {
    throw InputError(path.string(), "header.bytes", fmt::format("{} channels, expected 1–4", channels));
  }
  const std::size_t need = static_cast<std::size_t>(width) * height * channels;
  if (header_size < 24 || bytes.size() < header_size + need) {
    throw InputError(path.string(), "pixels", fmt::format("{} bytes, need {}", bytes.size(), header_size + need));
  }
  Image bgr(static_cast<int>(width), static_cast<int>(height), 3, PixelType::kU8);
  const unsigned char* p = bytes.data() + header_size;
  for (std::uint32_t y = 0; y < height; ++y) {
    std::uint8_t* row = bgr.Row<std::uint8_t>(static_cast<int>(y));
    for (std::uint32_t x = 0; x < width; ++x, p += channels) {
      // 1: grey, 2: grey + alpha, 3: RGB, 4: RGBA (alpha dropped).
      row[3 * x] = channels >= 3 ? p[2] : p[0];
      row[3 * x + 1] = channels >= 3 ? p[1] : p[0];
      row[3 * x + 2] = p[0];
    }
  }
  return bgr;
}

std::vector<std::shared_ptr<const Photo>> PhotoLibrary::OfKind(PhotoKind kind) const {
  std::vector<std::shared_ptr<const Photo>> out;
  for (const auto& p : photos) {
    if (p->kind == kind) out.push_back(p);
  }
  return out;
}

std::string PhotoLibrary::ToString() const {
  std::string s = "PhotoLibrary(";
  for (PhotoKind k : {PhotoKind::kWood, PhotoKind::kStone, PhotoKind::kFabric, PhotoKind::kPaper,
                      PhotoKind::kEnvironment, PhotoKind::kView}) {
    if (k != PhotoKind::kWood) s += ", ";
    s += fmt::format("{} {}", OfKind(k).size(), PhotoKindName(k));
  }
  return s + ")";
}

PhotoLibrary LoadPhotoLibrary(const PhotoLibraryOptions& options) {
  options.Check();
  std::vector<std::pair<fs::path, PhotoKind>> files;
  for (const fs::path& dir : options.dirs) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      if (!it->is_regular_file(ec)) continue;
      if (std::optional<PhotoKind> kind = ClassifyPhoto(it->path())) files.emplace_back(it->path(), *kind);
    }
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  PhotoLibrary library;
  for (const auto& [path, kind] : files) {
    try {
      if (std::optional<Photo> photo = LoadPhoto(path, kind, options.max_side_px)) {
        library.photos.push_back(std::make_shared<const Photo>(std::move(*photo)));
      } else {
        spdlog::warn("photo textures: {} is black or empty, skipped", path.string());
      }
    } catch (const std::exception& e) {
      spdlog::warn("photo textures: {}, skipped", e.what());
    }
  }
  return library;
}

}  // namespace asbuilt
