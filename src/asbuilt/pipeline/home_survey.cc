#include "asbuilt/pipeline/home_survey.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numbers>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "asbuilt/pipeline/report.h"
#include "asbuilt/plan/drawing.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

int JobsFor(int asked, std::size_t rooms) {
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int jobs = asked > 0 ? asked : std::max(1, hardware / 2);
  return std::clamp(jobs, 1, static_cast<int>(std::max<std::size_t>(1, rooms)));
}

// Stage 1: each room's survey into OUT/rooms/NAME/, `jobs` at a time.
std::vector<HomeRoomSurvey> SurveyRooms(const Home& home, const fs::path& out_dir, const HomeSurveyOptions& o,
                                        const std::function<void(const std::string&)>& on_room) {
  std::vector<HomeRoomSurvey> rooms(home.rooms.size());
  std::atomic<std::size_t> next{0};
  std::mutex report;
  auto work = [&] {
    for (std::size_t i = next++; i < home.rooms.size(); i = next++) {
      const HomeRoom& room = home.rooms[i];
      HomeRoomSurvey& r = rooms[i];
      r.name = room.name;
      SurveyOptions options = o.survey;
      if (room.labels) options.labels_dir = *room.labels;
      try {
        if (!fs::exists(room.capture)) {
          throw InputError(home.file.string(), fmt::format("rooms[{}].capture", i),
                           fmt::format("{} does not exist", room.capture.string()));
        }
        SurveyResult result = RunSurvey(room.capture, out_dir / "rooms" / room.name, options);
        r.summary = std::move(result.summary);
        r.plan = std::move(result.plan);
        r.ok = true;
      } catch (const std::exception& e) {
        r.error = e.what();
      }
      if (on_room) {
        std::lock_guard<std::mutex> lock(report);
        on_room(r.ok ? fmt::format("{}: {}", r.name, r.summary.BriefReport())
                     : fmt::format("{}: failed: {}", r.name, r.error));
      }
    }
  };
  std::vector<std::thread> threads;
  const int jobs = JobsFor(o.jobs, home.rooms.size());
  for (int t = 1; t < jobs; ++t) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  return rooms;
}

std::string Metres(const Vec2& p) { return fmt::format("({:.3f}, {:.3f}) m", p.x(), p.y()); }

std::string HomeReportHtml(const HomeSurveyResult& r) {
  std::string h =
      "<!doctype html><html><head><meta charset=\"utf-8\"><title>asbuilt home survey</title><style>"
      "body{font-family:sans-serif;margin:2em;max-width:70em}table{border-collapse:collapse}"
      "td,th{border:1px solid #ccc;padding:.25em .6em;text-align:left}.check{color:#b60}.unreliable{color:#c00}"
      "img{max-width:100%;border:1px solid #ccc}</style></head><body>";
  h += fmt::format("<h1>Home survey: {}</h1>", HtmlEscape(r.home.file.filename().string()));
  if (r.plan.verdict) {
    const PlanVerdictNote& v = *r.plan.verdict;
    h += fmt::format("<h2 class=\"{0}\">Verdict: {0}</h2><ul>", HtmlEscape(v.verdict));
    for (const std::string& why : v.reasons) h += "<li>" + HtmlEscape(why) + "</li>";
    h += "</ul>";
  }
  h += "<p>" + HtmlEscape(r.BriefReport()) + "</p>";
  h += "<p><img src=\"plan.svg\" alt=\"the home's floor plan\"></p>";
  h += "<h2>Rooms</h2><table><tr><th>room</th><th>survey</th><th>verdict</th><th>placed by</th><th>pose</th></tr>";
  for (std::size_t i = 0; i < r.rooms.size(); ++i) {
    const HomeRoomSurvey& room = r.rooms[i];
    const auto it = std::find(r.surveyed.begin(), r.surveyed.end(), static_cast<int>(i));
    const RoomPlacement* p =
        it == r.surveyed.end() ? nullptr : &r.placement.best.rooms[static_cast<std::size_t>(it - r.surveyed.begin())];
    const std::string link = fmt::format("<a href=\"rooms/{0}/report.html\">{0}</a>", HtmlEscape(room.name));
    if (!room.ok) {
      h += fmt::format("<tr><td>{}</td><td class=\"unreliable\" colspan=\"4\">not surveyed: {}</td></tr>",
                       HtmlEscape(room.name), HtmlEscape(room.error));
      continue;
    }
    const std::string verdict = VerdictName(room.summary.verdict.verdict);
    h += fmt::format("<tr><td>{}</td><td>{}</td><td class=\"{}\">{}</td><td>{}</td><td>{}</td></tr>", link,
                     HtmlEscape(room.summary.BriefReport()), verdict, verdict, HtmlEscape(p ? p->placed_by : ""),
                     p && p->placed ? HtmlEscape(fmt::format("{}, {:.1f}°", Metres(p->floor_from_room.translation()),
                                                             YawOf(p->floor_from_room) * 180 / std::numbers::pi))
                                    : std::string("–"));
  }
  h += "</table>";
  h += fmt::format("<h2>Placement</h2><p>{} links, {} closing a loop; partition thickness {:.3f} m; {:.2f} s.</p>",
                   r.placement.best.links.size(), r.placement.best.loops, r.placement.best.wall_thickness_m,
                   r.placement.seconds);
  if (!r.placement.alternatives.empty()) {
    h += "<p>Other placements, if this one is wrong (rooms placed differently):</p><ol>";
    for (const HomePlacement& alt : r.placement.alternatives) {
      std::string moved;
      for (std::size_t k = 0; k < alt.rooms.size(); ++k) {
        const RoomPlacement &a = alt.rooms[k], &b = r.placement.best.rooms[k];
        if (a.placed != b.placed || (a.placed && !a.floor_from_room.isApprox(b.floor_from_room, 1e-3))) {
          moved += (moved.empty() ? "" : "; ") + r.inputs[k].name + ": " + a.placed_by;
        }
      }
      h += fmt::format("<li>score {:.1f} against {:.1f}: {}</li>", alt.score, r.placement.best.score,
                       HtmlEscape(moved.empty() ? "the same rooms, refined differently" : moved));
    }
    h += "</ol>";
  }
  h += "</body></html>\n";
  return h;
}

nlohmann::json HomeSummaryJson(const HomeSurveyResult& r) {
  nlohmann::json rooms = nlohmann::json::array();
  for (std::size_t i = 0; i < r.rooms.size(); ++i) {
    const HomeRoomSurvey& room = r.rooms[i];
    nlohmann::json j = {{"name", room.name}, {"surveyed", room.ok}};
    if (!room.ok) j["error"] = room.error;
    const auto it = std::find(r.surveyed.begin(), r.surveyed.end(), static_cast<int>(i));
    if (room.ok && it != r.surveyed.end()) {
      const RoomPlacement& p = r.placement.best.rooms[static_cast<std::size_t>(it - r.surveyed.begin())];
      j["placed"] = p.placed;
      j["placed_by"] = p.placed_by;
      if (p.placed) {
        const PlanPose pose = TransformPose(p.floor_from_room);
        j["pose"] = {{"position_m", {pose.position_m.x(), pose.position_m.y()}}, {"yaw_deg", pose.yaw_deg}};
      }
      j["verdict"] = VerdictName(room.summary.verdict.verdict);
      j["summary"] = room.summary.BriefReport();
    }
    rooms.push_back(std::move(j));
  }
  nlohmann::json s = {{"kind", "home"},
                      {"rooms", std::move(rooms)},
                      {"placed", r.placement.best.Placed()},
                      {"links", r.placement.best.links.size()},
                      {"loops", r.placement.best.loops},
                      {"wall_thickness_m", r.placement.best.wall_thickness_m},
                      {"placement_seconds", r.placement.seconds},
                      {"seconds", r.seconds}};
  if (r.plan.verdict) s["verdict"] = r.plan.verdict->verdict;
  return s;
}

}  // namespace

void HomeSurveyOptions::Check() const {
  survey.Check();
  placement.Check();
  plan.Check();
  if (jobs < 0 || jobs > 256) throw InvalidArgument("HomeSurveyOptions: jobs must be in [0, 256]");
}

std::string HomeSurveyResult::BriefReport() const {
  const int ok =
      static_cast<int>(std::count_if(rooms.begin(), rooms.end(), [](const HomeRoomSurvey& r) { return r.ok; }));
  double area = 0;
  for (const PlanRoom& room : plan.rooms) {
    if (room.pose) area += room.area_m2;
  }
  int by_doors = 0;
  for (const RoomPlacement& p : placement.best.rooms) by_doors += p.link >= 0;
  return fmt::format("{} rooms: {} surveyed, {} placed ({} by doors, {} loops); {:.2f} m² placed; {:.0f} s",
                     rooms.size(), ok, placement.best.Placed(), by_doors, placement.best.loops, area, seconds);
}

HomeSurveyResult RunHomeSurvey(const fs::path& home_json, const fs::path& out_dir, const HomeSurveyOptions& options,
                               const std::function<void(const std::string&)>& on_room) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  HomeSurveyResult r;
  r.home = ReadHome(home_json);
  r.rooms = SurveyRooms(r.home, out_dir, options, on_room);
  for (std::size_t i = 0; i < r.rooms.size(); ++i) {
    if (!r.rooms[i].ok) continue;
    const HomeRoom& room = r.home.rooms[i];
    r.inputs.push_back({.name = room.name, .plan = r.rooms[i].plan, .hint = std::nullopt});
    if (room.hint) r.inputs.back().hint = PlanPose{room.hint->position_m, room.hint->yaw_deg};
    r.surveyed.push_back(static_cast<int>(i));
  }
  if (r.inputs.empty()) {
    throw InputError(home_json.string(), "rooms",
                     fmt::format("no room could be surveyed (the first: {})", r.rooms.front().error));
  }
  r.placement = PlaceRooms(r.inputs, options.placement);
  r.plan = HomePlan(r.inputs, r.placement.best, options.plan);
  WritePlanFiles(r.plan, out_dir);
  WriteHomeReviewInput(out_dir, r.inputs);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  WriteFileAtomic(out_dir / "summary.json", HomeSummaryJson(r).dump(2) + "\n");
  if (options.survey.write_report) WriteFileAtomic(out_dir / "report.html", HomeReportHtml(r));
  return r;
}

fs::path HomeReviewInputPath(const fs::path& out_dir) { return out_dir / "review" / "home.json"; }

void WriteHomeReviewInput(const fs::path& out_dir, const std::vector<HomeRoomInput>& rooms) {
  nlohmann::json list = nlohmann::json::array();
  for (const HomeRoomInput& r : rooms) {
    nlohmann::json j = {{"name", r.name}, {"plan", PlanToJson(r.plan)}};
    if (r.hint)
      j["hint"] = {{"position_m", {r.hint->position_m.x(), r.hint->position_m.y()}}, {"yaw_deg", r.hint->yaw_deg}};
    list.push_back(std::move(j));
  }
  fs::create_directories(out_dir / "review");
  WriteFileAtomic(HomeReviewInputPath(out_dir),
                  nlohmann::json{{"version", 1}, {"kind", "home"}, {"rooms", std::move(list)}}.dump(1) + "\n");
}

std::vector<HomeRoomInput> ReadHomeReviewInput(const fs::path& out_dir) {
  const fs::path path = HomeReviewInputPath(out_dir);
  JsonDiagnostics diag(path.string());
  const nlohmann::json root = ParseJsonFile(path, diag);
  std::vector<HomeRoomInput> rooms;
  JsonField doc(root, diag);
  if (diag.ok() && doc.Object({"version", "kind", "rooms"})) {
    if (auto k = doc.Required("kind").String(); k && *k != "home") doc.Required("kind").AddError("expected \"home\"");
    JsonField list = doc.Required("rooms");
    for (std::size_t i = 0, n = list.ArraySize(1).value_or(0); i < n; ++i) {
      JsonField r = list.At(i);
      if (!r.Object({"name", "plan", "hint"})) continue;
      HomeRoomInput room;
      room.name = r.Required("name").String().value_or("");
      if (const nlohmann::json* plan = r.Required("plan").raw()) {
        try {
          room.plan = PlanFromJson(*plan, fmt::format("{} rooms[{}].plan", path.string(), i));
        } catch (const InputError& e) {
          r.Required("plan").AddError(e.what());
        }
      }
      if (JsonField h = r.Optional("hint"); h.present() && h.Object({"position_m", "yaw_deg"})) {
        PlanPose hint;
        if (auto p = h.Required("position_m").NumberArray(2)) hint.position_m = Vec2((*p)[0], (*p)[1]);
        hint.yaw_deg = h.Required("yaw_deg").Number().value_or(0.0);
        room.hint = hint;
      }
      rooms.push_back(std::move(room));
    }
  }
  diag.ThrowIfErrors();
  return rooms;
}

}  // namespace asbuilt
