#include "asbuilt/formats/zind.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

// ZInD's local frame → the pano frame: mirror y, scale to metres.
Vec2 PanoFromZind(const Vec2& local, double metres_per_unit) { return Vec2(local.x(), -local.y()) * metres_per_unit; }

std::optional<Vec2> ReadZindPoint(const JsonField& f) {
  auto v = f.NumberArray(2);
  if (!v) return std::nullopt;
  return Vec2((*v)[0], (*v)[1]);
}

// Natural order of names with numbers ("pano_2" before "pano_15").
bool NaturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t i2 = i, j2 = j;
      while (i2 < a.size() && std::isdigit(static_cast<unsigned char>(a[i2]))) ++i2;
      while (j2 < b.size() && std::isdigit(static_cast<unsigned char>(b[j2]))) ++j2;
      const std::string na = a.substr(i, i2 - i), nb = b.substr(j, j2 - j);
      const std::string ta = na.substr(std::min(na.find_first_not_of('0'), na.size()));
      const std::string tb = nb.substr(std::min(nb.find_first_not_of('0'), nb.size()));
      if (ta.size() != tb.size()) return ta.size() < tb.size();
      if (ta != tb) return ta < tb;
      i = i2;
      j = j2;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

// The keys of an object member, in natural order; records an error and
// returns nothing when it is not an object.
std::vector<std::string> Keys(const JsonField& f) {
  std::vector<std::string> keys;
  if (!f.present()) return keys;
  if (!f.is_object()) {
    f.AddError(fmt::format("expected an object, got {}", DescribeJsonValue(*f.raw())));
    return keys;
  }
  for (const auto& item : f.raw()->items()) keys.push_back(item.key());
  std::sort(keys.begin(), keys.end(), NaturalLess);
  return keys;
}

// Places an opening on the layout edge whose line both its ends lie nearest
// to, among the edges its extent overlaps.
void PlaceOnWall(ZindOpening& o, const std::vector<Vec2>& vertices, double max_offset_m) {
  o.wall = -1;
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = vertices[i], b = vertices[(i + 1) % n];
    const double length = (b - a).norm();
    if (length < 1e-9) continue;
    const Vec2 d = (b - a) / length;
    const double offset = std::max(std::abs(Cross(d, o.start_m - a)), std::abs(Cross(d, o.end_m - a)));
    const double t0 = d.dot(o.start_m - a), t1 = d.dot(o.end_m - a);
    const bool overlaps = std::max(t0, t1) > 0.0 && std::min(t0, t1) < length;
    if (overlaps && offset < best) {
      best = offset;
      o.wall = static_cast<int>(i);
    }
  }
  if (best > max_offset_m) o.wall = -1;
  o.offset_m = o.wall >= 0 ? best : 0.0;
}

struct PanoScale {
  double metres_per_unit = 1.0;
  double camera_height_units = 1.0;
};

ZindLayout ParseLayout(const JsonField& f, const PanoScale& scale, const ZindReadOptions& options) {
  ZindLayout layout;
  if (!f.Object({"vertices", "doors", "windows", "openings", "internal"})) return layout;
  JsonField vertices = f.Required("vertices");
  if (auto n = vertices.ArraySize(3)) {
    for (std::size_t i = 0; i < *n; ++i) {
      if (auto p = ReadZindPoint(vertices.At(i))) layout.vertices_m.push_back(PanoFromZind(*p, scale.metres_per_unit));
    }
  }
  const std::pair<const char*, ZindOpeningKind> kinds[] = {{"doors", ZindOpeningKind::kDoor},
                                                           {"windows", ZindOpeningKind::kWindow},
                                                           {"openings", ZindOpeningKind::kOpening}};
  for (const auto& [key, kind] : kinds) {
    JsonField list = f.Optional(key);
    if (!list.present()) continue;
    auto n = list.ArraySize();
    if (!n) continue;
    if (*n % 3 != 0) {
      list.AddError(
          fmt::format("expected 3 entries per {} (end A, end B, [bottom z, top z]), got {} entries", key, *n));
      continue;
    }
    for (std::size_t i = 0; i < *n; i += 3) {
      auto a = ReadZindPoint(list.At(i));
      auto b = ReadZindPoint(list.At(i + 1));
      auto z = ReadZindPoint(list.At(i + 2));
      if (!a || !b || !z) continue;
      ZindOpening o;
      o.kind = kind;
      o.start_m = PanoFromZind(*a, scale.metres_per_unit);
      o.end_m = PanoFromZind(*b, scale.metres_per_unit);
      double bottom = z->x(), top = z->y();
      if (bottom > top) {
        list.At(i + 2).AddWarning(fmt::format("bottom {} above top {}, swapped", bottom, top));
        std::swap(bottom, top);
      }
      // ZInD heights are relative to the camera; ours to the floor.
      o.bottom_m = (bottom + scale.camera_height_units) * scale.metres_per_unit;
      o.top_m = (top + scale.camera_height_units) * scale.metres_per_unit;
      if (o.Width() < 1e-9) {
        list.At(i).AddError("zero width (both ends coincide)");
        continue;
      }
      if (layout.vertices_m.size() >= 3) {
        PlaceOnWall(o, layout.vertices_m, options.max_opening_offset_m);
        if (o.wall < 0) {
          list.At(i).AddWarning(
              fmt::format("lies on no wall of the layout (within {} m); left unplaced", options.max_opening_offset_m));
        }
      }
      layout.openings.push_back(o);
    }
  }
  // "internal": one polygon as a list of points, or a list of polygons.
  JsonField internal = f.Optional("internal");
  if (internal.present()) {
    if (auto n = internal.ArraySize(); n && *n > 0) {
      const nlohmann::json& first = (*internal.raw())[0];
      const bool one_polygon = first.is_array() && !first.empty() && first[0].is_number();
      if (one_polygon) {
        std::vector<Vec2> poly;
        for (std::size_t i = 0; i < *n; ++i) {
          if (auto p = ReadZindPoint(internal.At(i))) poly.push_back(PanoFromZind(*p, scale.metres_per_unit));
        }
        layout.internal_m.push_back(std::move(poly));
      } else {
        for (std::size_t k = 0; k < *n; ++k) {
          JsonField poly_field = internal.At(k);
          std::vector<Vec2> poly;
          if (auto m = poly_field.ArraySize()) {
            for (std::size_t i = 0; i < *m; ++i) {
              if (auto p = ReadZindPoint(poly_field.At(i))) poly.push_back(PanoFromZind(*p, scale.metres_per_unit));
            }
          }
          layout.internal_m.push_back(std::move(poly));
        }
      }
    }
  }
  return layout;
}

ZindPanorama ParsePanorama(const JsonField& f, const fs::path& dir, std::optional<double> metres_per_coordinate,
                           const ZindReadOptions& options) {
  ZindPanorama p;
  if (!f.Object({"label", "is_primary", "is_inside", "is_ceiling_flat", "ceiling_height", "camera_height",
                 "floor_number", "image_path", "checksum", "layout_raw", "layout_complete", "layout_visible",
                 "floor_plan_transformation"})) {
    return p;
  }
  if (auto v = f.Optional("label").String()) p.label = *v;
  if (auto v = f.Required("is_primary").Bool()) p.is_primary = *v;
  if (auto v = f.Optional("is_inside").Bool()) p.is_inside = *v;
  if (auto v = f.Optional("is_ceiling_flat").Bool()) p.is_ceiling_flat = *v;
  if (auto v = f.Required("image_path").String()) {
    p.image_path = *v;
    p.image = dir / *v;
    if (!fs::is_regular_file(p.image))
      f.Required("image_path").AddError(fmt::format("no such file: {}", p.image.string()));
  }

  // metres = ZInD units × floor_plan_transformation.scale × scale_meters_per_coordinate.
  JsonField transform = f.Required("floor_plan_transformation");
  double transform_scale = 1.0, rotation_deg = 0.0;
  Vec2 translation = Vec2::Zero();
  if (transform.Object({"translation", "rotation", "scale"})) {
    if (auto v = transform.Required("scale").Positive()) transform_scale = *v;
    if (auto v = transform.Required("rotation").Number()) rotation_deg = *v;
    if (auto v = ReadZindPoint(transform.Required("translation"))) translation = *v;
  }
  PanoScale scale;
  p.metric = metres_per_coordinate.has_value();
  scale.metres_per_unit = p.metric ? transform_scale * *metres_per_coordinate : 1.0;
  p.metres_per_unit = scale.metres_per_unit;
  if (auto v = f.Required("camera_height").Positive()) scale.camera_height_units = *v;
  p.camera_height_m = scale.camera_height_units * scale.metres_per_unit;
  JsonField ceiling = f.Required("ceiling_height");
  if (auto v = ceiling.Positive()) {
    p.ceiling_height_m = *v * scale.metres_per_unit;
    if (*v <= scale.camera_height_units) {
      ceiling.AddError(fmt::format("ceiling {} not above the camera ({})", *v, scale.camera_height_units));
    }
  }
  // global = s·R(θ)·local + t (ZInD units); mirrored and scaled: R(−θ) and M·t·(mpu/s).
  p.floor_from_pano = Eigen::Isometry2d::Identity();
  p.floor_from_pano.linear() = Eigen::Rotation2Dd(-DegToRad(rotation_deg)).toRotationMatrix();
  p.floor_from_pano.translation() = Vec2(translation.x(), -translation.y()) * (scale.metres_per_unit / transform_scale);

  p.layout_raw = ParseLayout(f.Required("layout_raw"), scale, options);
  if (f.Optional("layout_complete").present())
    p.layout_complete = ParseLayout(f.Optional("layout_complete"), scale, options);
  if (f.Optional("layout_visible").present())
    p.layout_visible = ParseLayout(f.Optional("layout_visible"), scale, options);
  return p;
}

ZindTour ParseTour(const nlohmann::json& root, const fs::path& dir, const ZindReadOptions& options,
                   JsonDiagnostics& diag) {
  ZindTour tour;
  JsonField doc(root, diag);
  if (!doc.Object({"scale_meters_per_coordinate", "merger", "redraw", "floorplan_to_redraw_transformation"})) {
    return tour;
  }
  JsonField scales = doc.Required("scale_meters_per_coordinate");
  JsonField merger = doc.Required("merger");
  for (const std::string& floor : Keys(merger)) {
    std::optional<double> metres_per_coordinate;
    JsonField s = scales.Optional(floor);
    if (s.present()) {
      metres_per_coordinate = s.Positive();
    } else if (scales.is_object()) {
      s.AddWarning("no metric scale for this floor (null or absent): lengths are in camera heights");
    }
    JsonField floor_field = merger.Required(floor);
    for (const std::string& complete : Keys(floor_field)) {
      JsonField complete_field = floor_field.Required(complete);
      for (const std::string& partial : Keys(complete_field)) {
        JsonField partial_field = complete_field.Required(partial);
        for (const std::string& pano : Keys(partial_field)) {
          ZindPanorama p = ParsePanorama(partial_field.Required(pano), dir, metres_per_coordinate, options);
          p.floor_id = floor;
          p.complete_room_id = complete;
          p.partial_room_id = partial;
          p.pano_id = pano;
          tour.panoramas.push_back(std::move(p));
        }
      }
    }
  }
  if (diag.ok() && tour.panoramas.empty()) merger.AddError("no panoramas");
  return tour;
}

}  // namespace

const char* ZindOpeningKindName(ZindOpeningKind kind) {
  switch (kind) {
    case ZindOpeningKind::kDoor:
      return "door";
    case ZindOpeningKind::kWindow:
      return "window";
    case ZindOpeningKind::kOpening:
      return "opening";
  }
  return "?";
}

const char* ZindLayoutKindName(ZindLayoutKind kind) {
  switch (kind) {
    case ZindLayoutKind::kRaw:
      return "raw";
    case ZindLayoutKind::kComplete:
      return "complete";
    case ZindLayoutKind::kVisible:
      return "visible";
  }
  return "?";
}

std::string ZindOpening::ToString() const {
  return fmt::format("{} {:.2f} m wide, {:.2f}–{:.2f} m{}", ZindOpeningKindName(kind), Width(), bottom_m, top_m,
                     wall >= 0 ? fmt::format(" on wall {}", wall) : std::string(" on no wall"));
}

int ZindLayout::Count(ZindOpeningKind kind) const {
  return static_cast<int>(
      std::count_if(openings.begin(), openings.end(), [&](const ZindOpening& o) { return o.kind == kind; }));
}

std::string ZindPanorama::Name() const {
  return fmt::format("{}/{}/{}/{}", floor_id, complete_room_id, partial_room_id, pano_id);
}

const ZindLayout& ZindPanorama::Layout(ZindLayoutKind kind) const {
  const std::optional<ZindLayout>* layout = nullptr;
  switch (kind) {
    case ZindLayoutKind::kRaw:
      return layout_raw;
    case ZindLayoutKind::kComplete:
      layout = &layout_complete;
      break;
    case ZindLayoutKind::kVisible:
      layout = &layout_visible;
      break;
  }
  if (layout == nullptr || !layout->has_value()) {
    throw InvalidArgument(fmt::format("{}: has no layout_{}", Name(), ZindLayoutKindName(kind)));
  }
  return **layout;
}

std::string ZindPanorama::ToString() const {
  const std::string unit = metric ? "m" : "camera heights";
  return fmt::format(
      "{} ({}, {}, {}): camera {:.3f} {}, ceiling {:.2f} {}, {} walls, {} doors, {} windows, {} passages", pano_id,
      label, is_primary ? "primary" : "secondary", is_inside ? "inside" : "outside", camera_height_m, unit,
      ceiling_height_m, unit, layout_raw.vertices_m.size(), layout_raw.Count(ZindOpeningKind::kDoor),
      layout_raw.Count(ZindOpeningKind::kWindow), layout_raw.Count(ZindOpeningKind::kOpening));
}

void ZindReadOptions::Check() const {
  CheckArgument(std::isfinite(max_opening_offset_m) && max_opening_offset_m >= 0,
                fmt::format("ZindReadOptions.max_opening_offset_m = {}, must be >= 0", max_opening_offset_m));
}

std::vector<const ZindPanorama*> ZindTour::BenchmarkPanoramas() const {
  std::vector<const ZindPanorama*> out;
  for (const ZindPanorama& p : panoramas) {
    if (p.is_primary && p.is_inside) out.push_back(&p);
  }
  return out;
}

const ZindPanorama* ZindTour::Find(const std::string& key) const {
  for (const ZindPanorama& p : panoramas) {
    if (p.pano_id == key || p.Name() == key || p.image_path == key) return &p;
  }
  return nullptr;
}

std::string ZindTour::ToString() const {
  const auto primary =
      std::count_if(panoramas.begin(), panoramas.end(), [](const ZindPanorama& p) { return p.is_primary; });
  return fmt::format("ZInD tour {}: {} panoramas, {} primary, {} primary inside", dir.string(), panoramas.size(),
                     primary, BenchmarkPanoramas().size());
}

ZindTour ReadZindTour(const fs::path& path, const ZindReadOptions& options) {
  options.Check();
  const fs::path file = fs::is_directory(path) ? path / "zind_data.json" : path;
  JsonDiagnostics diag(file.string());
  nlohmann::json root = ParseJsonFile(file, diag);
  diag.ThrowIfErrors();
  ZindTour tour = ParseTour(root, file.parent_path(), options, diag);
  diag.ThrowIfErrors();
  diag.LogWarnings();
  tour.dir = file.parent_path();
  tour.file = file;
  return tour;
}

Plan ZindTruthPlan(const ZindPanorama& pano, ZindLayoutKind kind) {
  const ZindLayout& layout = pano.Layout(kind);
  const std::size_t n = layout.vertices_m.size();
  if (n < 3)
    throw InvalidArgument(
        fmt::format("{}: layout_{} has {} vertices, a room needs 3", pano.Name(), ZindLayoutKindName(kind), n));
  // Counter-clockwise walls; wall i of the plan is layout edge map[i].
  const bool ccw = PolygonArea(layout.vertices_m) > 0;
  std::vector<Vec2> polygon = layout.vertices_m;
  if (!ccw) std::reverse(polygon.begin(), polygon.end());
  const auto plan_wall = [&](int edge) {  // Layout edge (v[e], v[e+1]) → plan wall index.
    return ccw ? edge : static_cast<int>((2 * n - 2 - static_cast<std::size_t>(edge)) % n);
  };
  Plan plan;
  for (std::size_t i = 0; i < n; ++i) {
    plan.walls.push_back({.start = polygon[i], .end = polygon[(i + 1) % n], .height = pano.ceiling_height_m});
  }
  for (const ZindOpening& o : layout.openings) {
    if (o.kind == ZindOpeningKind::kOpening || o.wall < 0) continue;
    PlanOpening op;
    op.kind = o.kind == ZindOpeningKind::kDoor ? OpeningKind::kDoor : OpeningKind::kWindow;
    op.wall = plan_wall(o.wall);
    const PlanWall& w = plan.walls[static_cast<std::size_t>(op.wall)];
    // Ends on the wall's line, the one nearer the wall's start first.
    const Vec2 d = (w.end - w.start).normalized();
    double t0 = d.dot(o.start_m - w.start), t1 = d.dot(o.end_m - w.start);
    if (t0 > t1) std::swap(t0, t1);
    op.start = w.start + t0 * d;
    op.end = w.start + t1 * d;
    op.width = t1 - t0;
    op.height = o.Height();
    op.sill = std::max(0.0, o.bottom_m);
    plan.openings.push_back(op);
  }
  plan.rooms.push_back({.polygon = polygon, .area_m2 = std::abs(PolygonArea(polygon))});
  return plan;
}

}  // namespace asbuilt
