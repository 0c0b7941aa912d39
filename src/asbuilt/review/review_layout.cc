#include "asbuilt/review/review_layout.h"

#include <fmt/format.h>

#include <cmath>

#include "asbuilt/review/review_backend.h"
#include "asbuilt/util/error.h"

namespace asbuilt::review_layout {
namespace {

Vec2 XyFrom(const nlohmann::json& v, const std::string& what) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
    throw InputError(what, "", "expected [x, y]");
  }
  return Vec2(v[0].get<double>(), v[1].get<double>());
}

}  // namespace

nlohmann::json Xy(const Vec2& v) { return {v.x(), v.y()}; }

nlohmann::json LayoutJson(const Layout& l) {
  nlohmann::json js = {{"corners", nlohmann::json::array()},
                       {"corners_edited", l.corners_edited},
                       {"openings", nlohmann::json::array()},
                       {"openings_edited", l.openings_edited},
                       {"next_id", l.next_id}};
  js["ceiling_height_m"] = l.ceiling_m ? nlohmann::json(*l.ceiling_m) : nlohmann::json();
  for (const Corner& c : l.corners) {
    js["corners"].push_back({{"id", c.id}, {"xy_m", Xy(c.xy_m)}, {"by", c.user ? "user" : "survey"}});
  }
  for (const Opening& o : l.openings) {
    js["openings"].push_back({{"id", o.id},
                              {"kind", OpeningKindName(o.kind)},
                              {"start_m", Xy(o.start_m)},
                              {"end_m", Xy(o.end_m)},
                              {"bottom_m", o.bottom_m},
                              {"top_m", o.top_m},
                              {"by", o.user ? "user" : "survey"}});
  }
  return js;
}

Layout LayoutFromJson(const nlohmann::json& js, const std::string& name) {
  Layout l;
  try {
    l.corners_edited = js.at("corners_edited").get<bool>();
    l.openings_edited = js.at("openings_edited").get<bool>();
    l.next_id = js.at("next_id").get<int>();
    if (js.at("ceiling_height_m").is_number()) l.ceiling_m = js["ceiling_height_m"].get<double>();
    for (const nlohmann::json& c : js.at("corners")) {
      l.corners.push_back({.id = c.at("id").get<int>(),
                           .xy_m = XyFrom(c.at("xy_m"), name),
                           .user = c.at("by").get<std::string>() == "user"});
    }
    for (const nlohmann::json& o : js.at("openings")) {
      l.openings.push_back(
          {.id = o.at("id").get<int>(),
           .kind = o.at("kind").get<std::string>() == "window" ? OpeningKind::kWindow : OpeningKind::kDoor,
           .start_m = XyFrom(o.at("start_m"), name),
           .end_m = XyFrom(o.at("end_m"), name),
           .bottom_m = o.at("bottom_m").get<double>(),
           .top_m = o.at("top_m").get<double>(),
           .user = o.at("by").get<std::string>() == "user"});
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(name, "layout", fmt::format("unexpected value: {}", e.what()));
  }
  return l;
}

PlanConstraints ConstraintsOf(const Layout& l) {
  PlanConstraints c;
  if (l.corners_edited) {
    for (const Corner& k : l.corners) c.corners.push_back({.xy_m = k.xy_m, .fixed = k.user});
  }
  if (l.openings_edited) {
    c.openings.emplace();
    for (const Opening& o : l.openings) {
      c.openings->push_back(
          {.kind = o.kind, .start_m = o.start_m, .end_m = o.end_m, .bottom_m = o.bottom_m, .top_m = o.top_m});
    }
  }
  c.ceiling_height_m = l.ceiling_m;
  return c;
}

std::vector<Vec2> CornerPoints(const Layout& l) {
  std::vector<Vec2> out;
  for (const Corner& c : l.corners) out.push_back(c.xy_m);
  return out;
}

// Reads a finite number field of an edit.
// A plan point [x, y] (metres) from edit[key]; EditError naming `what` when it is not two finite numbers.
Vec2 PlanPoint(const nlohmann::json& edit, const char* key, const std::string& what) {
  const nlohmann::json* v = edit.contains(key) ? &edit[key] : nullptr;
  if (v == nullptr || !v->is_array() || v->size() != 2 || !(*v)[0].is_number() || !(*v)[1].is_number() ||
      !std::isfinite((*v)[0].get<double>()) || !std::isfinite((*v)[1].get<double>())) {
    throw EditError(fmt::format("{}: \"{}\" must be [x, y], two finite numbers", what, key));
  }
  return Vec2((*v)[0].get<double>(), (*v)[1].get<double>());
}

double Number(const nlohmann::json& edit, const char* key) {
  const std::string op = edit.value("op", "");
  if (!edit.contains(key)) throw EditError(fmt::format("{}: \"{}\" is missing", op, key));
  const nlohmann::json& v = edit[key];
  if (!v.is_number() || !std::isfinite(v.get<double>())) {
    throw EditError(fmt::format("{}: \"{}\" must be a finite number, got {}", op, key, v.dump()));
  }
  return v.get<double>();
}

int Integer(const nlohmann::json& edit, const char* key) {
  const std::string op = edit.value("op", "");
  if (!edit.contains(key)) throw EditError(fmt::format("{}: \"{}\" is missing", op, key));
  const nlohmann::json& v = edit[key];
  if (!v.is_number_integer()) throw EditError(fmt::format("{}: \"{}\" must be an integer, got {}", op, key, v.dump()));
  return v.get<int>();
}

}  // namespace asbuilt::review_layout
