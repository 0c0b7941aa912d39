#include "asbuilt/formats/plan_file.h"

#include <cmath>

#include <fmt/format.h>

#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

std::optional<Vec2> ReadPoint(const JsonField& f) {
  auto v = f.NumberArray(2);
  if (!v) return std::nullopt;
  return Vec2((*v)[0], (*v)[1]);
}

void ReadOptionalNonNegative(const JsonField& parent, const char* key, std::optional<double>& out) {
  JsonField f = parent.Optional(key);
  if (f.present()) out = f.NonNegative();
}

Plan ParsePlan(const nlohmann::json& root, JsonDiagnostics& diag) {
  Plan plan;
  JsonField doc(root, diag);
  if (!doc.Object({"version", "units", "verdict", "walls", "openings", "rooms"})) return plan;
  if (auto v = doc.Required("version").Integer()) {
    if (*v != 1) doc.Required("version").AddError(fmt::format("unsupported version {}, expected 1", *v));
  }
  if (auto u = doc.Optional("units").String()) {
    if (*u != "m") doc.Optional("units").AddError(fmt::format("expected \"m\", got \"{}\"", *u));
  }

  if (JsonField v = doc.Optional("verdict"); v.present() && v.Object({"verdict", "confidence", "reasons"})) {
    PlanVerdictNote note;
    if (auto word = v.Required("verdict").String()) {
      if (!IsVerdictWord(*word)) {
        v.Required("verdict").AddError(
            fmt::format("expected \"good\", \"check\" or \"unreliable\", got \"{}\"", *word));
      }
      note.verdict = *word;
    }
    if (auto c = v.Required("confidence").NonNegative()) {
      if (*c > 1) v.Required("confidence").AddError(fmt::format("{} is above 1", *c));
      note.confidence = *c;
    }
    JsonField reasons = v.Optional("reasons");
    auto n = reasons.present() ? reasons.ArraySize() : std::optional<std::size_t>(0);
    for (std::size_t i = 0; n && i < *n; ++i) {
      if (auto r = reasons.At(i).String()) note.reasons.push_back(*r);
    }
    plan.verdict = std::move(note);
  }

  JsonField walls = doc.Required("walls");
  auto n_walls = walls.ArraySize();
  for (std::size_t i = 0; n_walls && i < *n_walls; ++i) {
    JsonField w = walls.At(i);
    PlanWall wall;
    if (!w.Object({"start", "end", "thickness", "height", "length_sigma_m", "verdict"})) continue;
    auto s = ReadPoint(w.Required("start"));
    auto e = ReadPoint(w.Required("end"));
    if (s) wall.start = *s;
    if (e) wall.end = *e;
    if (s && e && (*s - *e).norm() < 1e-6) w.AddError("start and end coincide (zero-length wall)");
    JsonField t = w.Optional("thickness");
    if (t.present()) wall.thickness = t.Positive();
    JsonField h = w.Optional("height");
    if (h.present()) wall.height = h.Positive();
    ReadOptionalNonNegative(w, "length_sigma_m", wall.length_sigma_m);
    if (JsonField v = w.Optional("verdict"); v.present()) {
      if (auto word = v.String()) {
        if (!IsVerdictWord(*word)) {
          v.AddError(fmt::format("expected \"good\", \"check\" or \"unreliable\", got \"{}\"", *word));
        }
        wall.verdict = *word;
      }
    }
    plan.walls.push_back(wall);
  }

  JsonField openings = doc.Optional("openings");
  auto n_open = openings.present() ? openings.ArraySize() : std::optional<std::size_t>(0);
  for (std::size_t i = 0; n_open && i < *n_open; ++i) {
    JsonField o = openings.At(i);
    PlanOpening op;
    if (!o.Object({"kind", "wall", "start", "end", "width", "height", "sill", "width_sigma_m", "height_sigma_m",
                   "sill_sigma_m", "rooms"})) {
      continue;
    }
    if (auto k = o.Required("kind").String()) {
      if (*k == "door") {
        op.kind = OpeningKind::kDoor;
      } else if (*k == "window") {
        op.kind = OpeningKind::kWindow;
      } else {
        o.Required("kind").AddError(fmt::format("expected \"door\" or \"window\", got \"{}\"", *k));
      }
    }
    if (auto w = o.Required("wall").Integer()) {
      if (*w < 0 || (n_walls && static_cast<std::size_t>(*w) >= *n_walls)) {
        o.Required("wall").AddError(
            fmt::format("wall index {} out of range (plan has {} walls)", *w, n_walls.value_or(0)));
      } else {
        op.wall = static_cast<int>(*w);
      }
    }
    if (auto s = ReadPoint(o.Required("start"))) op.start = *s;
    if (auto e = ReadPoint(o.Required("end"))) op.end = *e;
    if (auto w = o.Required("width").Positive()) op.width = *w;
    JsonField h = o.Optional("height");
    if (h.present()) op.height = h.Positive();
    ReadOptionalNonNegative(o, "sill", op.sill);
    ReadOptionalNonNegative(o, "width_sigma_m", op.width_sigma_m);
    ReadOptionalNonNegative(o, "height_sigma_m", op.height_sigma_m);
    ReadOptionalNonNegative(o, "sill_sigma_m", op.sill_sigma_m);
    if (JsonField joined = o.Optional("rooms"); joined.present()) {
      if (auto v = joined.NumberArray(2)) {
        const double a = (*v)[0], b = (*v)[1];
        const double n_rooms = static_cast<double>(doc.Optional("rooms").ArraySize().value_or(0));
        if (a != std::floor(a) || b != std::floor(b) || a < 0 || b < 0 || a >= n_rooms || b >= n_rooms || a == b) {
          joined.AddError(fmt::format("expected two different room indices below {}, got [{}, {}]", n_rooms, a, b));
        } else {
          op.rooms = std::pair{static_cast<int>(a), static_cast<int>(b)};
        }
      }
    }
    if (op.width > 0 && std::abs((op.end - op.start).norm() - op.width) > 0.01) {
      o.AddWarning(
          fmt::format("width {:.3f} differs from |end − start| = {:.3f}", op.width, (op.end - op.start).norm()));
    }
    plan.openings.push_back(op);
  }

  JsonField rooms = doc.Optional("rooms");
  auto n_rooms = rooms.present() ? rooms.ArraySize() : std::optional<std::size_t>(0);
  for (std::size_t i = 0; n_rooms && i < *n_rooms; ++i) {
    JsonField r = rooms.At(i);
    PlanRoom room;
    if (!r.Object({"polygon", "area_m2", "area_sigma_m2", "name", "pose", "placed_by"})) continue;
    JsonField poly = r.Required("polygon");
    if (auto n = poly.ArraySize(3)) {
      for (std::size_t k = 0; k < *n; ++k) {
        if (auto p = ReadPoint(poly.At(k))) room.polygon.push_back(*p);
      }
    }
    if (auto a = r.Required("area_m2").NonNegative()) room.area_m2 = *a;
    ReadOptionalNonNegative(r, "area_sigma_m2", room.area_sigma_m2);
    if (auto name = r.Optional("name").String()) room.name = *name;
    if (JsonField pose = r.Optional("pose"); pose.present() && pose.Object({"position_m", "yaw_deg"})) {
      PlanPose p;
      if (auto at = pose.Required("position_m").NumberArray(2)) p.position_m = Vec2((*at)[0], (*at)[1]);
      if (auto yaw = pose.Required("yaw_deg").Number()) p.yaw_deg = *yaw;
      room.pose = p;
    }
    if (auto by = r.Optional("placed_by").String()) room.placed_by = *by;
    plan.rooms.push_back(std::move(room));
  }
  return plan;
}

nlohmann::json PointJson(const Vec2& p) { return nlohmann::json::array({p.x(), p.y()}); }

}  // namespace

bool IsVerdictWord(const std::string& word) { return word == "good" || word == "check" || word == "unreliable"; }

const char* OpeningKindName(OpeningKind kind) { return kind == OpeningKind::kDoor ? "door" : "window"; }

std::string Plan::ToString() const {
  double area = 0.0;
  for (const PlanRoom& r : rooms) area += r.area_m2;
  return fmt::format("Plan({} walls, {} openings, {} rooms, {:.2f} m²)", walls.size(), openings.size(), rooms.size(),
                     area);
}

Plan PlanFromJson(const nlohmann::json& json, const std::string& name) {
  JsonDiagnostics diag(name);
  Plan plan = ParsePlan(json, diag);
  diag.ThrowIfErrors();
  diag.LogWarnings();
  return plan;
}

Plan ReadPlan(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  nlohmann::json root = ParseJsonFile(path, diag);
  diag.ThrowIfErrors();
  Plan plan = ParsePlan(root, diag);
  diag.ThrowIfErrors();
  diag.LogWarnings();
  return plan;
}

FileReport CheckPlanFile(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  nlohmann::json root = ParseJsonFile(path, diag);
  if (diag.ok()) ParsePlan(root, diag);
  return {diag.errors(), diag.warnings()};
}

nlohmann::json PlanToJson(const Plan& plan) {
  nlohmann::json j;
  j["version"] = plan.version;
  j["units"] = "m";
  if (plan.verdict) {
    j["verdict"] = {{"verdict", plan.verdict->verdict},
                    {"confidence", plan.verdict->confidence},
                    {"reasons", plan.verdict->reasons}};
  }
  nlohmann::json walls = nlohmann::json::array();
  for (const PlanWall& w : plan.walls) {
    nlohmann::json jw = {{"start", PointJson(w.start)}, {"end", PointJson(w.end)}};
    if (w.thickness) jw["thickness"] = *w.thickness;
    if (w.height) jw["height"] = *w.height;
    if (w.length_sigma_m) jw["length_sigma_m"] = *w.length_sigma_m;
    if (w.verdict) jw["verdict"] = *w.verdict;
    walls.push_back(std::move(jw));
  }
  j["walls"] = std::move(walls);
  nlohmann::json openings = nlohmann::json::array();
  for (const PlanOpening& o : plan.openings) {
    nlohmann::json jo = {{"kind", OpeningKindName(o.kind)},
                         {"wall", o.wall},
                         {"start", PointJson(o.start)},
                         {"end", PointJson(o.end)},
                         {"width", o.width}};
    if (o.height) jo["height"] = *o.height;
    if (o.sill) jo["sill"] = *o.sill;
    if (o.width_sigma_m) jo["width_sigma_m"] = *o.width_sigma_m;
    if (o.height_sigma_m) jo["height_sigma_m"] = *o.height_sigma_m;
    if (o.sill_sigma_m) jo["sill_sigma_m"] = *o.sill_sigma_m;
    if (o.rooms) jo["rooms"] = {o.rooms->first, o.rooms->second};
    openings.push_back(std::move(jo));
  }
  j["openings"] = std::move(openings);
  nlohmann::json rooms = nlohmann::json::array();
  for (const PlanRoom& r : plan.rooms) {
    nlohmann::json poly = nlohmann::json::array();
    for (const Vec2& p : r.polygon) poly.push_back(PointJson(p));
    nlohmann::json jr = {{"polygon", std::move(poly)}, {"area_m2", r.area_m2}};
    if (r.area_sigma_m2) jr["area_sigma_m2"] = *r.area_sigma_m2;
    if (r.name) jr["name"] = *r.name;
    if (r.pose) jr["pose"] = {{"position_m", PointJson(r.pose->position_m)}, {"yaw_deg", r.pose->yaw_deg}};
    if (r.placed_by) jr["placed_by"] = *r.placed_by;
    rooms.push_back(std::move(jr));
  }
  j["rooms"] = std::move(rooms);
  return j;
}

void WritePlan(const Plan& plan, const fs::path& path) { WriteFileAtomic(path, PlanToJson(plan).dump(2) + "\n"); }

}  // namespace asbuilt
