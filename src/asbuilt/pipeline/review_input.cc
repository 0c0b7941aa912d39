#include "asbuilt/pipeline/review_input.h"

#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

#include "asbuilt/formats/points_file.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/fields.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

nlohmann::json Vec3Json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

std::string PathForOut(const fs::path& path, const fs::path& out_dir) {
  std::error_code ec;
  const fs::path abs = fs::weakly_canonical(fs::absolute(path), ec);
  const fs::path out = fs::weakly_canonical(fs::absolute(out_dir), ec);
  // Inside OUT: relative (the folder can move); elsewhere: absolute.
  const fs::path rel = abs.lexically_relative(out);
  const bool inside = !rel.empty() && *rel.begin() != "..";
  return inside ? rel.string() : abs.string();
}

// The points, exactly: "asbuilt review points v1\n", a little-endian uint64
// count, then per point x, y, z, sigma_m (float64), label, source (uint8) and
// frame (int32) — 38 bytes a point, a third of the text at 10 µm.
constexpr char kPointsMagic[] = "asbuilt review points v1\n";
constexpr std::size_t kRecordBytes = 4 * 8 + 2 + 4;

template <typename T>
void Put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}
template <typename T>
T Take(const std::string& in, std::size_t& at) {
  T value;
  std::memcpy(&value, in.data() + at, sizeof value);
  at += sizeof value;
  return value;
}

std::string PointsBytes(const std::vector<ClassPoint>& points) {
  static_assert(std::endian::native == std::endian::little, "review/points.bin is little-endian");
  std::string out = kPointsMagic;
  out.reserve(out.size() + 8 + points.size() * kRecordBytes);
  Put<std::uint64_t>(out, points.size());
  for (const ClassPoint& p : points) {
    for (double v : {p.position_m.x(), p.position_m.y(), p.position_m.z(), p.sigma_m}) Put<double>(out, v);
    Put<std::uint8_t>(out, static_cast<std::uint8_t>(p.label));
    Put<std::uint8_t>(out, static_cast<std::uint8_t>(p.source));
    Put<std::int32_t>(out, p.frame);
  }
  return out;
}

std::vector<ClassPoint> ReadPointsBytes(const fs::path& path) {
  const std::string in = ReadFile(path);
  const std::size_t header = sizeof kPointsMagic - 1;
  if (in.size() < header + 8 || in.compare(0, header, kPointsMagic) != 0) {
    throw InputError(path.string(), "", "not an asbuilt review points file (bad header)");
  }
  std::size_t at = header;
  const std::uint64_t count = Take<std::uint64_t>(in, at);
  if (count > (in.size() - at) / kRecordBytes || in.size() - at != count * kRecordBytes) {
    throw InputError(path.string(), "", fmt::format("{} bytes do not hold {} points", in.size(), count));
  }
  std::vector<ClassPoint> points(count);
  for (std::uint64_t i = 0; i < count; ++i) {
    ClassPoint& p = points[i];
    const double x = Take<double>(in, at), y = Take<double>(in, at), z = Take<double>(in, at);
    p.position_m = Vec3(x, y, z);
    p.sigma_m = Take<double>(in, at);
    const auto label = Take<std::uint8_t>(in, at), source = Take<std::uint8_t>(in, at);
    p.frame = Take<std::int32_t>(in, at);
    if (!p.position_m.allFinite() || !std::isfinite(p.sigma_m) || p.sigma_m < 0 || label > 3 ||
        source > static_cast<std::uint8_t>(PointSource::kVertex)) {
      throw InputError(path.string(), fmt::format("points[{}]", i), "not a valid point");
    }
    p.label = static_cast<LabelClass>(label);
    p.source = static_cast<PointSource>(source);
  }
  return points;
}

double NumberOrNan(const nlohmann::json& v) { return v.is_number() ? v.get<double>() : NAN; }

}  // namespace

void WriteReviewInput(const fs::path& out_dir, const ReviewInput& input) {
  const fs::path dir = out_dir / "review";
  fs::create_directories(dir);
  nlohmann::json js = {{"version", 1},
                       {"kind", input.kind},
                       {"capture", PathForOut(input.capture_json, out_dir)},
                       {"labels_source", input.labels_source},
                       {"points", "points.bin"},
                       {"one_camera", input.plan_input.one_camera},
                       {"exact_labels", input.plan_input.exact_labels}};
  js["ceiling_height_m"] =
      std::isfinite(input.plan_input.ceiling_height_m) ? nlohmann::json(input.plan_input.ceiling_height_m) : nullptr;
  js["ceiling_height_sigma_m"] = std::isfinite(input.plan_input.ceiling_height_sigma_m)
                                     ? nlohmann::json(input.plan_input.ceiling_height_sigma_m)
                                     : nullptr;
  js["camera_height_sigma_m"] = std::isfinite(input.plan_input.camera_height_sigma_m)
                                    ? nlohmann::json(input.plan_input.camera_height_sigma_m)
                                    : nullptr;
  js["frames"] = nlohmann::json::array();
  for (const PlanFrame& f : input.plan_input.frames) {
    js["frames"].push_back(
        {{"index", f.index}, {"position_m", Vec3Json(f.position_m)}, {"camera_m", Vec3Json(f.camera_m)}});
  }
  auto image_json = [&](const ReviewImage& im) {
    return nlohmann::json{
        {"frame", im.frame},
        {"image", PathForOut(im.image, out_dir)},
        {"width_px", im.width_px},
        {"height_px", im.height_px},
        {"camera", {{"fx", im.camera.fx}, {"fy", im.camera.fy}, {"cx", im.camera.cx}, {"cy", im.camera.cy}}},
        {"yaw_deg", im.yaw_deg},
        {"camera_m", Vec3Json(im.camera_m)}};
  };
  js["labels"] = nlohmann::json::array();
  for (const ReviewImage& im : input.labels) js["labels"].push_back(image_json(im));
  js["images"] = nlohmann::json::array();
  for (const ReviewImage& im : input.images) js["images"].push_back(image_json(im));
  nlohmann::json options = nlohmann::json::object();
  for (const auto& f : PlanOptionFields().bound()) {
    nlohmann::json v = f.get(input.plan_options);
    if (!v.is_null()) options[f.field.name] = v;
  }
  js["plan_options"] = options;
  WriteFileAtomic(dir / "points.bin", PointsBytes(input.plan_input.points));
  WriteFileAtomic(dir / "input.json", js.dump(1) + "\n");
}

ReviewInput ReadReviewInput(const fs::path& out_dir) {
  const fs::path file = out_dir / "review" / "input.json";
  std::error_code ec;
  if (!fs::is_directory(out_dir, ec)) {
    throw InputError(out_dir.string(), "", "not a folder: give the folder `asbuilt survey -o` wrote");
  }
  if (!fs::is_regular_file(file, ec)) {
    throw InputError(out_dir.string(), "",
                     "has no review/input.json: not a folder written by `asbuilt survey` (or written before "
                     "the review existed; survey the capture again)");
  }
  JsonDiagnostics diag(file.string());
  const nlohmann::json js = ParseJsonFile(file, diag);
  diag.ThrowIfErrors();
  const std::string name = file.string();
  auto need = [&](const nlohmann::json& obj, const char* key, const std::string& path) -> const nlohmann::json& {
    if (!obj.is_object() || !obj.contains(key)) throw InputError(name, path + key, "missing");
    return obj.at(key);
  };
  auto vec3 = [&](const nlohmann::json& v, const std::string& path) {
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number()) {
      throw InputError(name, path, "expected 3 numbers");
    }
    return Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  };
  ReviewInput in;
  try {
    if (js.value("points", "") != "points.bin") {
      throw InputError(name, "points", "written by an older asbuilt survey: survey the capture again to review it");
    }
    in.kind = need(js, "kind", "").get<std::string>();
    if (in.kind != "stereo" && in.kind != "mono" && in.kind != "panorama") {
      throw InputError(name, "kind", fmt::format("unknown kind \"{}\"", in.kind));
    }
    in.capture_json = fs::absolute(out_dir / need(js, "capture", "").get<std::string>());
    in.labels_source = js.value("labels_source", "");
    in.plan_input.one_camera = need(js, "one_camera", "").get<bool>();
    in.plan_input.exact_labels = need(js, "exact_labels", "").get<bool>();
    in.plan_input.ceiling_height_m = NumberOrNan(js.value("ceiling_height_m", nlohmann::json()));
    in.plan_input.ceiling_height_sigma_m = NumberOrNan(js.value("ceiling_height_sigma_m", nlohmann::json()));
    in.plan_input.camera_height_sigma_m = NumberOrNan(js.value("camera_height_sigma_m", nlohmann::json()));
    in.plan_input.source = (out_dir / "review" / "points.bin").string();
    const nlohmann::json& frames = need(js, "frames", "");
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const std::string path = fmt::format("frames[{}].", i);
      in.plan_input.frames.push_back({.index = need(frames[i], "index", path).get<int>(),
                                      .position_m = vec3(need(frames[i], "position_m", path), path + "position_m"),
                                      .camera_m = vec3(need(frames[i], "camera_m", path), path + "camera_m")});
    }
    const nlohmann::json& images = need(js, "images", "");
    if (!images.is_array() || images.empty()) throw InputError(name, "images", "expected at least one image");
    const nlohmann::json labels = js.value("labels", nlohmann::json::array());
    for (std::size_t i = 0; i < images.size() + labels.size(); ++i) {
      const bool is_label = i >= images.size();
      const nlohmann::json& im = is_label ? labels[i - images.size()] : images[i];
      const std::string path = is_label ? fmt::format("labels[{}].", i - images.size()) : fmt::format("images[{}].", i);
      ReviewImage r;
      r.frame = need(im, "frame", path).get<int>();
      r.image = fs::absolute(out_dir / need(im, "image", path).get<std::string>());
      r.width_px = need(im, "width_px", path).get<int>();
      r.height_px = need(im, "height_px", path).get<int>();
      if (r.width_px <= 0 || r.height_px <= 0 || r.width_px > 32768 || r.height_px > 32768) {
        throw InputError(name, path + "width_px", "image size out of 1..32768");
      }
      const nlohmann::json& cam = need(im, "camera", path);
      r.camera = {.width_px = r.width_px,
                  .height_px = r.height_px,
                  .fx = need(cam, "fx", path + "camera.").get<double>(),
                  .fy = need(cam, "fy", path + "camera.").get<double>(),
                  .cx = need(cam, "cx", path + "camera.").get<double>(),
                  .cy = need(cam, "cy", path + "camera.").get<double>()};
      r.yaw_deg = need(im, "yaw_deg", path).get<double>();
      r.camera_m = vec3(need(im, "camera_m", path), path + "camera_m");
      (is_label ? in.labels : in.images).push_back(r);
    }
    if (in.kind == "panorama" && in.images.size() != 1) {
      throw InputError(name, "images", "a panorama survey has exactly one image");
    }
    const nlohmann::json& options = need(js, "plan_options", "");
    in.plan_options = PlanOptionFields().FromArgs(ParseFieldArgs(PlanOptionFields().Fields(), options));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(name, "", fmt::format("unexpected value: {}", e.what()));
  } catch (const InvalidArgument& e) {
    throw InputError(name, "plan_options", e.what());
  }
  in.plan_input.points = ReadPointsBytes(out_dir / "review" / "points.bin");
  return in;
}

}  // namespace asbuilt
