// bench_real_rooms: surveys of the real rooms that people annotated by hand
// (data/real-rooms/*.json: floor corners, a ceiling point, doors and windows
// clicked on CC0 360° photos), scored against the room those clicks make.
// With the three annotated CC0 rooms of bench_verdict these are the real
// rooms with truth that ZInD is not: what survey accuracy, the verdict and
// the ± on real photos can be judged and chosen on.
//
// The truth is the clicks' geometry at the photo's assumed camera height
// (1.6 m, as the annotations were made): each corner's floor point, walls
// between consecutive corners, the ceiling from its point on the nearest
// wall, each opening's ends where the rays of its columns meet the wall its
// middle sees. The clicks are pixels of the survey's levelled panorama, so
// the truth lies in the survey's own frame.
//
//   env ASBUILT_BENCH_REAL_ROOMS_MODELS  models to survey with (default "default,real")

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/seg/segmenter.h"
#include "bench/bench_util.h"
#include "bench/verdict_stats.h"

namespace fs = std::filesystem;
using namespace asbuilt;
using namespace asbuilt::bench;

namespace {

constexpr double kCameraHeightM = 1.6;
// Rooms `real` was fine-tuned on (scripts/finetune-real-reviewed.sh).
const std::vector<std::string> kTrainedOnByReal = {"artist_workshop",    "pmndrs_apartment", "pmndrs_hall",
                                                   "st_fagans_interior", "studio_small_03",  "studio_small_08"};

struct Photo {
  fs::path path;
  int width = 0, height = 0;
};

// The photo a room's clicks were made on: a Poly Haven panorama of
// ../shared/data/cc0-panoramas, or an HDRI of npm @pmndrs/assets 1.7.0
// (unpacked once into `cache`; nullopt when npm cannot fetch it).
std::optional<Photo> FindPhoto(const std::string& room, const fs::path& data, const fs::path& cache) {
  fs::path path = data / "cc0-panoramas" / (room + ".hdr");
  if (room.rfind("pmndrs_", 0) == 0) {
    path = cache / (room + ".exr");
    if (!fs::exists(path)) {
      const std::string fetch = fmt::format("'{}/scripts/pmndrs-hdri.sh' '{}' '{}' '{}'", ASBUILT_SOURCE_DIR,
                                            room.substr(7), path.string(), cache.string());
      if (std::system(fetch.c_str()) != 0) return std::nullopt;
    }
  }
  if (!fs::exists(path)) return std::nullopt;
  const cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (image.empty()) return std::nullopt;
  return Photo{path, image.cols, image.rows};
}

// A pixel's viewing direction in plan and its elevation (docs/formats.md:
// yaw ψ = −360°·(u + 0.5)/W, 0 looking along +y, counter-clockwise).
struct Ray {
  Vec2 dir;
  double elevation;
};
Ray RayOf(double u, double v, const Photo& photo) {
  const double yaw = -2 * M_PI * (u + 0.5) / photo.width;
  const double elevation = M_PI * (0.5 - (v + 0.5) / photo.height);
  return {Vec2(-std::sin(yaw), std::cos(yaw)), elevation};
}

// Where a ray from the camera first meets a wall: (wall, distance).
std::optional<std::pair<int, double>> FirstWall(const Vec2& dir, const std::vector<PlanWall>& walls) {
  std::optional<std::pair<int, double>> best;
  for (int i = 0; i < static_cast<int>(walls.size()); ++i) {
    const Vec2 a = walls[i].start, e = walls[i].end - walls[i].start;
    const double den = dir.x() * e.y() - dir.y() * e.x();
    if (std::abs(den) < 1e-12) continue;
    const double t = (a.x() * e.y() - a.y() * e.x()) / den;      // Along the ray.
    const double s = (a.x() * dir.y() - a.y() * dir.x()) / den;  // Along the wall.
    if (t > 0 && s >= -1e-6 && s <= 1 + 1e-6 && (!best || t < best->second)) best = std::pair{i, t};
  }
  return best;
}

// The room a person's clicks make (see the file comment).
Plan TruthFromClicks(const nlohmann::json& clicks, const Photo& photo) {
  Plan plan;
  std::vector<Vec2> corners;
  for (const nlohmann::json& c : clicks.at("corners")) {
    const Ray r = RayOf(c.at("u").get<double>(), c.at("v").get<double>(), photo);
    corners.push_back(r.dir * kCameraHeightM / std::tan(-r.elevation));
  }
  double area2 = 0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Vec2 &a = corners[i], &b = corners[(i + 1) % corners.size()];
    area2 += a.x() * b.y() - a.y() * b.x();
  }
  if (area2 < 0) std::reverse(corners.begin(), corners.end());  // Room on the walls' left.
  for (std::size_t i = 0; i < corners.size(); ++i) {
    plan.walls.push_back({.start = corners[i], .end = corners[(i + 1) % corners.size()]});
  }
  plan.rooms.push_back({.polygon = corners, .area_m2 = 0.5 * std::abs(area2)});
  if (const auto it = clicks.find("ceiling"); it != clicks.end() && !it->is_null()) {
    const Ray r = RayOf(it->at("u").get<double>(), it->at("v").get<double>(), photo);
    if (const auto hit = FirstWall(r.dir, plan.walls)) {
      const double ceiling = kCameraHeightM + hit->second * std::tan(r.elevation);
      for (PlanWall& w : plan.walls) w.height = ceiling;
    }
  }
  for (const nlohmann::json& o : clicks.value("openings", nlohmann::json::array())) {
    const double u0 = o.at("u0").get<double>(), u1 = o.at("u1").get<double>();
    const auto mid = FirstWall(RayOf(0.5 * (u0 + u1), 0, photo).dir, plan.walls);
    if (!mid) continue;
    const PlanWall& w = plan.walls[mid->first];
    const Vec2 d = (w.end - w.start).normalized(), n(-d.y(), d.x());
    auto on_wall = [&](double u) -> std::optional<Vec2> {
      const Vec2 dir = RayOf(u, 0, photo).dir;
      const double den = n.dot(dir);
      if (std::abs(den) < 1e-9) return std::nullopt;
      return dir * (n.dot(w.start) / den);
    };
    const auto a = on_wall(u0), b = on_wall(u1);
    if (!a || !b) continue;
    PlanOpening op{.kind = o.at("kind").get<std::string>() == "window" ? OpeningKind::kWindow : OpeningKind::kDoor,
                   .wall = mid->first};
    const bool a_first = (*a - w.start).dot(d) <= (*b - w.start).dot(d);
    op.start = a_first ? *a : *b;
    op.end = a_first ? *b : *a;
    op.width = (op.end - op.start).norm();
    const double range = mid->second;
    const double top = kCameraHeightM + range * std::tan(RayOf(0, o.at("v_top").get<double>(), photo).elevation);
    const double bottom =
        op.kind == OpeningKind::kDoor
            ? 0.0
            : kCameraHeightM + range * std::tan(RayOf(0, o.at("v_bottom").get<double>(), photo).elevation);
    op.sill = bottom;
    op.height = top - bottom;
    plan.openings.push_back(op);
  }
  return plan;
}

struct RoomRun {
  std::string room, model;
  std::optional<SurveySummary> summary;
  std::string error;
};

std::string Cell(const RoomRun& r) {
  if (!r.summary) return "– (" + r.error + ")";
  const SurveySummary& s = *r.summary;
  if (!s.score) return "no score";
  const auto median = s.score->wall_length.Median();
  return fmt::format("walls {}/{}{}; openings {}/{}; IoU {:.3f}; {}", s.score->walls.matched, s.score->walls.truth,
                     median ? fmt::format(", {:.1f} %", 100 * *median) : "",
                     s.score->doors.matched + s.score->windows.matched, s.score->doors.truth + s.score->windows.truth,
                     s.room_overlap ? s.room_overlap->Iou() : 0.0, VerdictName(s.verdict.verdict));
}

// One summary row per model: room IoU median, walls and openings pooled.
std::string ModelRow(const std::string& model, const std::vector<RoomRun>& runs) {
  std::vector<double> iou, wall_errors;
  int walls = 0, walls_truth = 0, openings = 0, openings_truth = 0, rooms = 0;
  for (const RoomRun& r : runs) {
    if (r.model != model) continue;
    ++rooms;
    if (!r.summary || !r.summary->score) {
      iou.push_back(0.0);
      continue;
    }
    const PlanScore& s = *r.summary->score;
    iou.push_back(r.summary->room_overlap ? r.summary->room_overlap->Iou() : 0.0);
    walls += s.walls.matched, walls_truth += s.walls.truth;
    openings += s.doors.matched + s.windows.matched, openings_truth += s.doors.truth + s.windows.truth;
    wall_errors.insert(wall_errors.end(), s.wall_length.values.begin(), s.wall_length.values.end());
  }
  return fmt::format("| {} | {} | {:.3f} | {}/{} | {} | {}/{} |\n", model, rooms, iou.empty() ? 0.0 : Median(iou),
                     walls, walls_truth, wall_errors.empty() ? "–" : fmt::format("{:.1f} %", 100 * Median(wall_errors)),
                     openings, openings_truth);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string results = ResultsPath(argc, argv, "real_rooms");
  const fs::path data = ASBUILT_SHARED_DATA_DIR;
  const fs::path annotations = fs::path(ASBUILT_SOURCE_DIR) / "data" / "real-rooms";
  const fs::path out = fs::path(ASBUILT_BINARY_DIR) / "bench" / "real_rooms";
  setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 0);
  if (!SegmenterAvailable() || !fs::exists(DefaultModelPath())) {
    std::fprintf(stderr, "bench_real_rooms: no segmenter in this build; %s left as it was\n", results.c_str());
    return 0;
  }
  std::vector<std::string> models;
  {
    const char* env = std::getenv("ASBUILT_BENCH_REAL_ROOMS_MODELS");
    std::stringstream list(env ? env : "default,real");
    for (std::string m; std::getline(list, m, ',');) models.push_back(m);
  }
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(annotations)) {
    if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());

  const auto start = std::chrono::steady_clock::now();
  std::vector<RoomRun> runs;
  std::vector<VerdictSample> samples;
  std::string skipped;
  for (const fs::path& file : files) {
    const nlohmann::json clicks = nlohmann::json::parse(std::ifstream(file));
    const std::string room = file.stem().string();
    const std::optional<Photo> photo = FindPhoto(room, data, out / "photos");
    if (!photo) {
      skipped += " " + room;
      continue;
    }
    const fs::path dir = out / room;
    fs::create_directories(dir);
    WritePlan(TruthFromClicks(clicks, *photo), dir / "truth.json");
    std::ofstream(dir / "capture.json") << nlohmann::json{
        {"version", 1},
        {"kind", "panorama"},
        {"panorama", fs::absolute(photo->path).string()},
        {"position_m",
         {0.0, 0.0, kCameraHeightM}}}.dump();
    for (const std::string& model : models) {
      RoomRun run{.room = room, .model = model};
      SurveyOptions options{.truth_path = dir / "truth.json", .report_frames = 4};
      if (model != "default") options.model_path = ModelPathFor(model);
      try {
        run.summary = RunSurvey(dir / "capture.json", dir / model, options).summary;
        std::fprintf(stderr, "bench_real_rooms: %s %s: %s\n", room.c_str(), model.c_str(),
                     run.summary->BriefReport().c_str());
        samples.push_back(SampleOf(room + "_" + model, *run.summary));
      } catch (const std::exception& e) {
        run.error = e.what();
        std::fprintf(stderr, "bench_real_rooms: %s %s: %s\n", room.c_str(), model.c_str(), e.what());
      }
      runs.push_back(std::move(run));
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::string md = "## survey on real rooms annotated by hand (bench_real_rooms)\n\n";
  md += fmt::format(
      "Issues 42 and 43. The CC0 360° photos of `data/real-rooms/` (Poly Haven, npm `@pmndrs/assets`; sources and "
      "licences there), each surveyed as a panorama capture at the 1.6 m its annotation assumed, and scored against "
      "the room its clicks make: corners on the floor at that height, the ceiling from its point, each opening where "
      "its columns' rays meet the wall its middle sees (bench/real_rooms/real_rooms_bench.cc). Annotated once by eye "
      "(data/real-rooms/README.md says how and where each is unsure), so a few percent of any figure here is the "
      "annotation's. `real` was fine-tuned on six of these rooms (marked *): its figures there are not held out. "
      "Measured {} on {} hardware threads, {:.0f} s.{}\n\n",
      Today(), std::thread::hardware_concurrency(), seconds,
      skipped.empty() ? "" : " Not run (photo not found):" + skipped + ".");
  md +=
      "| model | rooms | room IoU median | walls matched | wall length error median | openings matched |\n"
      "|---|---|---|---|---|---|\n";
  for (const std::string& model : models) md += ModelRow(model, runs);
  md += "\nThe verdict on these plans (issue 42; the columns of bench_verdict):\n\n";
  md += VerdictTableHeader();
  for (const std::string& model : models) {
    std::vector<VerdictSample> of_model;
    for (const VerdictSample& s : samples) {
      if (s.name.size() > model.size() && s.name.compare(s.name.size() - model.size(), model.size(), model) == 0)
        of_model.push_back(s);
    }
    md += VerdictRow(model, of_model);
  }
  md += "\nPer room (walls matched/truth, wall length error median; openings; room IoU; verdict):\n\n| room |";
  for (const std::string& model : models) md += " " + model + " |";
  md += "\n|---|";
  for (std::size_t i = 0; i < models.size(); ++i) md += "---|";
  md += "\n";
  for (std::size_t i = 0; i < runs.size(); i += models.size()) {
    const bool trained =
        std::find(kTrainedOnByReal.begin(), kTrainedOnByReal.end(), runs[i].room) != kTrainedOnByReal.end();
    md += fmt::format("| {}{} |", runs[i].room, trained ? " *" : "");
    for (std::size_t k = 0; k < models.size(); ++k) md += " " + Cell(runs[i + k]) + " |";
    md += "\n";
  }
  WriteSection(results, md);
  return 0;
}
