#include "asbuilt/review/home_review.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "asbuilt/pipeline/home_survey.h"
#include "asbuilt/plan/drawing.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

using Pose = Eigen::Isometry2d;

nlohmann::json PointJson(const Vec2& p) { return {p.x(), p.y()}; }
nlohmann::json PoseJson(const Pose& t) {
  const PlanPose p = TransformPose(t);
  return {{"position_m", PointJson(p.position_m)}, {"yaw_deg", p.yaw_deg}};
}
nlohmann::json RefJson(const OpeningRef& r) { return {{"room", r.room}, {"opening", r.opening}}; }

double Number(const nlohmann::json& edit, const char* key, bool required = true) {
  if (!edit.contains(key)) {
    if (required) throw EditError(fmt::format("{}: \"{}\" is missing", edit.value("op", ""), key));
    return 0.0;
  }
  const nlohmann::json& v = edit[key];
  if (!v.is_number() || !std::isfinite(v.get<double>())) {
    throw EditError(
        fmt::format("{}: \"{}\" must be a finite number, got {}", edit.value("op", ""), key, DescribeJsonValue(v)));
  }
  return v.get<double>();
}

// The room's middle: the mean of its outline's corners (or its walls' ends).
Vec2 Middle(const Plan& plan) {
  Vec2 sum = Vec2::Zero();
  int n = 0;
  for (const PlanRoom& r : plan.rooms) {
    for (const Vec2& p : r.polygon) sum += p, ++n;
    if (n > 0) break;
  }
  if (n == 0) {
    for (const PlanWall& w : plan.walls) sum += w.start, ++n;
  }
  return n ? Vec2(sum / n) : Vec2::Zero();
}

template <typename T>
void Erase(std::vector<std::pair<T, T>>& list, const T& a, const T& b) {
  std::erase_if(list,
                [&](const auto& p) { return (p.first == a && p.second == b) || (p.first == b && p.second == a); });
}

}  // namespace

// The page (review/home_page.html), compiled in by CMake (cmake/embed_text.cmake).
extern const char kHomeReviewPageHtml[];

bool HomeReviewSession::IsHomeSurvey(const fs::path& out_dir) { return fs::exists(HomeReviewInputPath(out_dir)); }

HomeReviewSession HomeReviewSession::Open(const fs::path& out_dir) {
  HomeReviewSession s;
  s.out_ = out_dir;
  s.rooms_ = ReadHomeReviewInput(out_dir);
  for (const HomeRoomInput& room : s.rooms_) {
    // The room's photo: the first image its own review shows.
    int index = -1;
    const fs::path input = out_dir / "rooms" / room.name / "review" / "input.json";
    if (fs::exists(input)) {
      const nlohmann::json j = nlohmann::json::parse(ReadFile(input), nullptr, false);
      if (j.is_object() && j.contains("images") && j["images"].is_array() && !j["images"].empty() &&
          j["images"][0].is_string()) {
        fs::path image = j["images"][0].get<std::string>();
        if (image.is_relative()) image = input.parent_path() / image;
        if (fs::exists(image)) {
          index = static_cast<int>(s.images_.size());
          s.images_.push_back(image);
        }
      }
    }
    s.image_of_room_.push_back(index);
  }
  const fs::path saved = out_dir / "review" / "home_state.json";
  if (fs::exists(saved)) {
    JsonDiagnostics diag(saved.string());
    const nlohmann::json j = ParseJsonFile(saved, diag);
    diag.ThrowIfErrors();
    if (j.contains("edits") && j["edits"].is_array()) {
      for (const nlohmann::json& e : j["edits"]) s.edits_.push_back(e);
    }
  }
  try {
    s.Replace();
  } catch (const EditError& e) {
    throw InputError(saved.string(), "edits", fmt::format("a saved edit no longer applies: {}", e.what()));
  }
  return s;
}

OpeningRef HomeReviewSession::Opening(const nlohmann::json& edit, const char* key) const {
  const std::string op = edit.value("op", "");
  if (!edit.contains(key) || !edit[key].is_object()) {
    throw EditError(fmt::format("{}: \"{}\" must be {{\"room\": i, \"opening\": j}}", op, key));
  }
  const nlohmann::json& r = edit[key];
  if (!r.contains("room") || !r["room"].is_number_integer() || !r.contains("opening") ||
      !r["opening"].is_number_integer()) {
    throw EditError(fmt::format("{}: \"{}\" must be {{\"room\": i, \"opening\": j}} with whole numbers", op, key));
  }
  const OpeningRef ref{r["room"].get<int>(), r["opening"].get<int>()};
  if (ref.room < 0 || ref.room >= static_cast<int>(rooms_.size())) {
    throw EditError(fmt::format("{}: no room {} (the home has {})", op, ref.room, rooms_.size()));
  }
  const Plan& plan = rooms_[ref.room].plan;
  if (ref.opening < 0 || ref.opening >= static_cast<int>(plan.openings.size())) {
    throw EditError(fmt::format("{}: {} has no opening {}", op, rooms_[ref.room].name, ref.opening));
  }
  if (plan.openings[ref.opening].kind != OpeningKind::kDoor) {
    throw EditError(fmt::format("{}: {}#{} is a window, not a door", op, rooms_[ref.room].name, ref.opening));
  }
  return ref;
}

nlohmann::json HomeReviewSession::Absolute(const nlohmann::json& edit) const {
  if (!edit.is_object() || !edit.contains("op") || !edit["op"].is_string()) {
    throw EditError("an edit is a JSON object with an \"op\"");
  }
  if (edit["op"] != "move_room") return edit;
  if (!edit.contains("room") || !edit["room"].is_number_integer())
    throw EditError("move_room: \"room\" must be a whole number");
  const int room = edit["room"].get<int>();
  if (room < 0 || room >= static_cast<int>(rooms_.size())) {
    throw EditError(fmt::format("move_room: no room {} (the home has {})", room, rooms_.size()));
  }
  const double dx = Number(edit, "dx", false), dy = Number(edit, "dy", false), dyaw = Number(edit, "dyaw_deg", false);
  if (std::abs(dx) > 1000 || std::abs(dy) > 1000) throw EditError("move_room: a move of more than 1 km");
  const Pose& now = drawn_[room];
  const Vec2 middle = now * Middle(rooms_[room].plan);
  Pose turn = Pose::Identity();
  turn.linear() = Eigen::Rotation2Dd(dyaw * std::numbers::pi / 180).toRotationMatrix();
  turn.translation() = middle - turn.linear() * middle + Vec2(dx, dy);
  nlohmann::json absolute = edit;
  absolute["pose"] = PoseJson(turn * now);
  return absolute;
}

void HomeReviewSession::Apply(const nlohmann::json& edit, PlacementConstraints& c) const {
  const std::string op = edit.value("op", "");
  if (op == "move_room") {
    const int room = edit["room"].get<int>();
    const nlohmann::json& p = edit["pose"];
    const PlanPose pose{Vec2(p["position_m"][0].get<double>(), p["position_m"][1].get<double>()),
                        p["yaw_deg"].get<double>()};
    std::erase_if(c.fixed, [&](const auto& f) { return f.first == room; });
    c.fixed.push_back({room, pose});
  } else if (op == "release_room") {
    if (!edit.contains("room") || !edit["room"].is_number_integer()) {
      throw EditError("release_room: \"room\" must be a whole number");
    }
    const int room = edit["room"].get<int>();
    if (std::erase_if(c.fixed, [&](const auto& f) { return f.first == room; }) == 0) {
      throw EditError(fmt::format("release_room: room {} was not moved by hand", room));
    }
  } else if (op == "link_openings" || op == "unlink_openings") {
    const OpeningRef a = Opening(edit, "a"), b = Opening(edit, "b");
    if (a.room == b.room) throw EditError(fmt::format("{}: two openings of one room cannot be one door", op));
    Erase(c.same, a, b);
    Erase(c.different, a, b);
    if (op == "link_openings") {
      // A door is one door: its other links go.
      std::erase_if(c.same,
                    [&](const auto& p) { return p.first == a || p.second == a || p.first == b || p.second == b; });
      c.same.push_back({a, b});
    } else {
      c.different.push_back({a, b});
    }
  } else {
    throw EditError(
        fmt::format("unknown op \"{}\" (move_room, release_room, link_openings, unlink_openings, undo, "
                    "redo)",
                    op));
  }
}

void HomeReviewSession::Replace() {
  const auto start = std::chrono::steady_clock::now();
  PlacementConstraints c;
  for (const nlohmann::json& e : edits_) Apply(e, c);
  // Where the rooms were when the last edit was made: an edit moves only
  // what it must (PlacementConstraints::previous).
  if (!edits_.empty() && edits_.back().contains("previous") && edits_.back()["previous"].is_array() &&
      edits_.back()["previous"].size() == rooms_.size()) {
    for (const nlohmann::json& p : edits_.back()["previous"]) {
      if (p.is_null()) {
        c.previous.push_back(std::nullopt);
      } else {
        c.previous.push_back(PlanPose{Vec2(p["position_m"][0].get<double>(), p["position_m"][1].get<double>()),
                                      p["yaw_deg"].get<double>()});
      }
    }
  }
  constraints_ = c;
  placement_ = PlaceRooms(rooms_, {}, constraints_);
  drawn_ = DrawnRoomPoses(rooms_, placement_.best);
  plan_ = HomePlan(rooms_, placement_.best);
  refit_ms_ = 1000 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

nlohmann::json HomeReviewSession::Edit(const nlohmann::json& edit) {
  const std::string op = edit.is_object() ? edit.value("op", "") : "";
  const std::vector<nlohmann::json> edits = edits_, undone = undone_;
  if (op == "undo") {
    if (edits_.empty()) throw EditError("undo: nothing to undo");
    undone_.push_back(edits_.back());
    edits_.pop_back();
  } else if (op == "redo") {
    if (undone_.empty()) throw EditError("redo: nothing to redo");
    edits_.push_back(undone_.back());
    undone_.pop_back();
  } else {
    nlohmann::json absolute = Absolute(edit);
    nlohmann::json previous = nlohmann::json::array();
    for (const RoomPlacement& p : placement_.best.rooms) {
      previous.push_back(p.placed ? PoseJson(p.floor_from_room) : nlohmann::json(nullptr));
    }
    absolute["previous"] = std::move(previous);
    PlacementConstraints check = constraints_;
    Apply(absolute, check);  // Throws before anything changes.
    edits_.push_back(absolute);
    undone_.clear();
  }
  try {
    Replace();
  } catch (...) {
    edits_ = edits;
    undone_ = undone;
    Replace();
    throw;
  }
  return State();
}

nlohmann::json HomeReviewSession::State() const {
  const HomePlacement& best = placement_.best;
  nlohmann::json rooms = nlohmann::json::array();
  for (std::size_t r = 0; r < rooms_.size(); ++r) {
    const Plan& p = rooms_[r].plan;
    const Pose& t = drawn_[r];
    nlohmann::json outline = nlohmann::json::array(), walls = nlohmann::json::array(),
                   openings = nlohmann::json::array();
    for (const PlanRoom& room : p.rooms) {
      for (const Vec2& q : room.polygon) outline.push_back(PointJson(t * q));
      if (!outline.empty()) break;
    }
    for (const PlanWall& w : p.walls) walls.push_back({PointJson(t * w.start), PointJson(t * w.end)});
    for (std::size_t k = 0; k < p.openings.size(); ++k) {
      const PlanOpening& o = p.openings[k];
      openings.push_back({{"index", k},
                          {"kind", OpeningKindName(o.kind)},
                          {"start", PointJson(t * o.start)},
                          {"end", PointJson(t * o.end)},
                          {"width", o.width}});
    }
    nlohmann::json j = {{"name", rooms_[r].name},
                        {"placed", best.rooms[r].placed},
                        {"placed_by", best.rooms[r].placed_by},
                        {"drawn", PoseJson(t)},
                        {"outline", std::move(outline)},
                        {"walls", std::move(walls)},
                        {"openings", std::move(openings)},
                        {"image", image_of_room_[r]},
                        {"held", std::any_of(constraints_.fixed.begin(), constraints_.fixed.end(),
                                             [&](const auto& f) { return f.first == static_cast<int>(r); })}};
    if (best.rooms[r].placed) j["pose"] = PoseJson(best.rooms[r].floor_from_room);
    if (p.verdict) j["verdict"] = p.verdict->verdict;
    rooms.push_back(std::move(j));
  }
  nlohmann::json links = nlohmann::json::array();
  for (const RoomLink& l : best.links) {
    links.push_back({{"a", RefJson(l.a)},
                     {"b", RefJson(l.b)},
                     {"wall_a", l.wall_a},
                     {"wall_b", l.wall_b},
                     {"loop", l.loop},
                     {"by_user", l.by_user}});
  }
  auto pairs = [](const std::vector<std::pair<OpeningRef, OpeningRef>>& list) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& [a, b] : list) out.push_back({{"a", RefJson(a)}, {"b", RefJson(b)}});
    return out;
  };
  nlohmann::json held = nlohmann::json::array();
  for (const auto& f : constraints_.fixed) held.push_back(f.first);
  nlohmann::json alternatives = nlohmann::json::array();
  for (const HomePlacement& alt : placement_.alternatives) {
    nlohmann::json moved = nlohmann::json::array();
    for (std::size_t r = 0; r < rooms_.size(); ++r) {
      if (alt.rooms[r].placed != best.rooms[r].placed ||
          (alt.rooms[r].placed && !alt.rooms[r].floor_from_room.isApprox(best.rooms[r].floor_from_room, 1e-3))) {
        moved.push_back({{"room", r}, {"placed_by", alt.rooms[r].placed_by}});
      }
    }
    alternatives.push_back({{"score", alt.score}, {"moved", std::move(moved)}});
  }
  nlohmann::json images = nlohmann::json::array();
  for (const fs::path& p : images_) images.push_back(p.filename().string());
  nlohmann::json state = {{"kind", "home"},
                          {"rooms", std::move(rooms)},
                          {"links", std::move(links)},
                          {"same", pairs(constraints_.same)},
                          {"different", pairs(constraints_.different)},
                          {"held", std::move(held)},
                          {"placed", best.Placed()},
                          {"score", best.score},
                          {"alternatives", std::move(alternatives)},
                          {"wall_thickness_m", best.wall_thickness_m},
                          {"edits", edits_.size()},
                          {"can_undo", !edits_.empty()},
                          {"can_redo", !undone_.empty()},
                          {"images", std::move(images)},
                          {"refit_ms", refit_ms_}};
  if (plan_.verdict) state["verdict"] = {{"verdict", plan_.verdict->verdict}, {"reasons", plan_.verdict->reasons}};
  return state;
}

std::vector<std::string> HomeReviewSession::SaveAll() {
  WritePlanFiles(plan_, out_);
  std::vector<std::string> files = {"plan.json", "plan.svg", "plan.dxf", "plan.pdf", "plan.png", "plan.ifc"};
  nlohmann::json edits = nlohmann::json::array();
  for (const nlohmann::json& e : edits_) edits.push_back(e);
  nlohmann::json corrections = State();
  corrections.erase("images");
  corrections["edits"] = edits;
  WriteFileAtomic(out_ / "review" / "home_corrections.json", corrections.dump(1) + "\n");
  WriteFileAtomic(out_ / "review" / "home_state.json", nlohmann::json{{"version", 1}, {"edits", edits}}.dump(1) + "\n");
  files.push_back("review/home_corrections.json");
  files.push_back("review/home_state.json");
  return files;
}

std::vector<fs::path> HomeReviewSession::ImagePaths() const { return images_; }

const char* HomeReviewSession::PageHtml() const { return kHomeReviewPageHtml; }

}  // namespace asbuilt
