// bench_home: a whole home from its panoramas (issue 40). The 13 primary
// panoramas of the ZInD sample tour (../shared/data/zind_sample_tour, read
// at run time: ZInD is for academic use only, a test set, never training
// data, and nothing derived from it is committed) as one home.json, each
// room's capture as in bench_pano_survey, surveyed by `asbuilt survey
// home.json` (pipeline/home_survey.h) twice:
//   - with each room's layout labels (the placement's own upper bound), and
//   - with the shipped segmenter (and `--model real`).
// Scored against ZInD's floor_plan_transformation per panorama (the truth
// pose) and its raw layouts (the truth floor), after the one rigid transform
// that best aligns the whole home (home/home_plan.h ScoreHome): a room is
// placed when its centroid is within 10 cm and its yaw within 1°; floor IoU
// of the union of the placed rooms against the union of the true ones.
// Also the placement alone, timed (the rooms surveyed once, placed again).
// Writes bench/results/home.md; captures and outputs go under the build
// folder (bench/home/), never into the repository.
//
//   bench_home [RESULTS.md]
//   env ASBUILT_BENCH_HOME_MODEL   0: skip the segmenter runs
//   env ASBUILT_BENCH_HOME_DEV     1: random homes of seeds 1–40 (to choose weights on)

#include <sys/resource.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "asbuilt/formats/zind.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/pano/layout_labels.h"
#include "asbuilt/home/synthetic_home.h"
#include "asbuilt/pipeline/home_survey.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/file.h"
#include "bench/bench_util.h"
#include "bench/zind_capture.h"

namespace {

using namespace asbuilt;
namespace fs = std::filesystem;

struct Run {
  std::string name;
  HomeSurveyResult result;
  HomeScore score;
  std::vector<double> placement_seconds;
  int misplaced = 0, edits = 0;  // The scripted surveyor's.
};

// The review's scripted surveyor for a home: while a room is not within the
// tolerances, it moves the first such room to its true place (move_room,
// held there) and the home is placed again, the other rooms kept where they
// were where they fit as well (as the review does). It judges and moves rooms
// in the frame it first saw the home in (the truth aligned on the rooms then
// right), as a person keeps the drawing they look at. Returns the edits it
// took (capped at twice the rooms), with the rooms misplaced at first.
int ScriptedEdits(const std::vector<HomeRoomInput>& rooms, const std::vector<Eigen::Isometry2d>& truth,
                  const std::vector<std::vector<Vec2>>& outlines, int* misplaced_at_start) {
  PlacementConstraints c;
  const int n = static_cast<int>(rooms.size());
  std::vector<Vec2> centre(rooms.size(), Vec2::Zero());
  for (int k = 0; k < n; ++k) {
    if (rooms[k].plan.rooms.empty()) continue;
    const std::vector<Vec2>& polygon = rooms[k].plan.rooms.front().polygon;
    for (const Vec2& v : polygon) centre[k] += v / static_cast<double>(polygon.size());
  }
  Eigen::Isometry2d home_from_truth = Eigen::Isometry2d::Identity();
  for (int edits = 0; edits <= 2 * n; ++edits) {
    const PlacementResult r = PlaceRooms(rooms, {}, c);
    const HomeScore s = ScoreHome(rooms, r.best, truth, outlines);
    if (edits == 0) {
      *misplaced_at_start = n - s.within;
      home_from_truth = s.truth_from_home.inverse();
    }
    if (s.within == n) return edits;
    c.previous.clear();
    for (const RoomPlacement& p : r.best.rooms) {
      c.previous.push_back(p.placed ? std::optional<PlanPose>(TransformPose(p.floor_from_room)) : std::nullopt);
    }
    for (int k = 0; k < n; ++k) {
      const Eigen::Isometry2d want = home_from_truth * truth[k], got = r.best.rooms[k].floor_from_room;
      const double dp = (want * centre[k] - got * centre[k]).norm();
      const double dyaw =
          std::abs(std::remainder(YawOf(want) - YawOf(got), 2 * std::numbers::pi)) * 180 / std::numbers::pi;
      if (r.best.rooms[k].placed && dp <= 0.10 && dyaw <= 1.0) continue;
      std::erase_if(c.fixed, [&](const auto& f) { return f.first == k; });
      c.fixed.push_back({k, TransformPose(want)});
      break;
    }
  }
  return 2 * n + 1;
}

// The truth per surveyed room, in the order of result.inputs.
HomeScore Score(const HomeSurveyResult& r, const std::vector<const ZindPanorama*>& panos) {
  std::vector<Eigen::Isometry2d> truth;
  std::vector<std::vector<Vec2>> outline;
  for (int i : r.surveyed) {
    const ZindPanorama& p = *panos[static_cast<std::size_t>(i)];
    truth.push_back(p.floor_from_pano);
    std::vector<Vec2> o;
    for (const Vec2& v : p.layout_raw.vertices_m) o.push_back(p.floor_from_pano * v);
    outline.push_back(std::move(o));
  }
  return ScoreHome(r.inputs, r.placement.best, truth, outline);
}

std::string RoomTable(const Run& run) {
  std::string md = "| room | survey | placed by | centroid error | yaw error |\n|---|---|---|---|---|\n";
  for (std::size_t k = 0; k < run.result.surveyed.size(); ++k) {
    const HomeRoomSurvey& room = run.result.rooms[static_cast<std::size_t>(run.result.surveyed[k])];
    const double dp = run.score.centroid_error_m[k], dy = run.score.yaw_error_deg[k];
    md += fmt::format("| {} | {} walls, {} openings | {} | {} | {} |\n", room.name, room.summary.plan.walls,
                      room.summary.plan.openings, run.result.placement.best.rooms[k].placed_by,
                      std::isfinite(dp) ? fmt::format("{:.3f} m", dp) : "–",
                      std::isfinite(dy) ? fmt::format("{:.2f}°", dy) : "–");
  }
  for (const HomeRoomSurvey& room : run.result.rooms) {
    if (!room.ok) md += fmt::format("| {} | not surveyed: {} | | | |\n", room.name, room.error);
  }
  return md;
}

// Random homes the placement's weights were not chosen on (seeds 101–140;
// the tests' 1–20 were): rooms placed within 10 cm and 1°, per condition.
std::string SyntheticSection() {
  std::string md =
      "### Random homes (home/synthetic_home.h), held out\n\n"
      "40 homes of 5–10 rectangular rooms (seeds 101–140; the placement's weights were chosen on seeds 1–20), "
      "each room in a random frame, walls and openings jittered 1 cm; with every door found by both of its "
      "rooms, with a share of the door faces missed by the rooms' surveys, and with doors to the outside (a "
      "quarter of each home's exterior walls of 1.5 m or more, in place of a window; a quarter of those 1.5–2.4 m "
      "wide): a door of one room that no other room's door meets, as the front, patio and garage doors and the "
      "doors to unsurveyed closets of a real home.\n\n"
      "| doors missed | doors to the outside | rooms placed (10 cm, 1°) | homes all placed | floor IoU, median | "
      "placement time, median | scripted surveyor: edits / misplaced rooms |\n"
      "|---|---|---|---|---|---|---|\n";
  for (const auto [missed, outside] : {std::pair{0.0, 0.0}, {0.1, 0.0}, {0.2, 0.0}, {0.0, 0.25}, {0.1, 0.25}}) {
    int within = 0, rooms = 0, complete = 0, edits = 0, misplaced = 0;
    std::vector<double> iou, seconds;
    // ASBUILT_BENCH_HOME_DEV=1: the seeds the weights are chosen on (1–40) instead.
    const unsigned first = std::getenv("ASBUILT_BENCH_HOME_DEV") != nullptr ? 1 : 101;
    for (unsigned seed = first; seed < first + 40; ++seed) {
      SyntheticHomeOptions options{.missed_door = missed};
      options.layout.exterior_door = outside;
      const SyntheticHome home = MakeSyntheticHome(seed, options);
      const PlacementResult r = PlaceRooms(home.rooms);
      const HomeScore s = ScoreHome(home.rooms, r.best, home.floor_from_room, home.outlines);
      within += s.within;
      rooms += s.rooms;
      complete += s.within == s.rooms;
      iou.push_back(s.floor_iou);
      seconds.push_back(r.seconds);
      int m = 0;
      edits += ScriptedEdits(home.rooms, home.floor_from_room, home.outlines, &m);
      misplaced += m;
    }
    md += fmt::format("| {:.0f} % | {} | {}/{} = {:.1f} % | {}/40 | {:.3f} | {:.3f} s | {} / {} |\n", 100 * missed,
                      outside > 0 ? "yes" : "no", within, rooms, 100.0 * within / rooms, complete,
                      asbuilt::bench::Median(iou), asbuilt::bench::Median(seconds), edits, misplaced);
  }
  return md + "\n";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace asbuilt::bench;
  const std::string results = ResultsPath(argc, argv, "home");
  const fs::path tour_dir = fs::path(ASBUILT_SHARED_DATA_DIR) / "zind_sample_tour";
  if (!fs::exists(tour_dir / "zind_data.json")) {
    std::fprintf(stderr, "bench_home: %s not present; only the random homes measured\n", tour_dir.c_str());
    WriteSection(results,
                 "## a whole home (bench_home)\n\nThe ZInD sample tour was not present.\n\n" + SyntheticSection());
    return 0;
  }
  const char* model_env = std::getenv("ASBUILT_BENCH_HOME_MODEL");
  const bool with_model = !(model_env != nullptr && std::string(model_env) == "0") && SegmenterAvailable() &&
                          fs::exists(DefaultModelPath());
  const fs::path out = fs::path(ASBUILT_BINARY_DIR) / "bench" / "home";
  const ZindTour tour = ReadZindTour(tour_dir);
  const std::vector<const ZindPanorama*> panos = tour.BenchmarkPanoramas();
  std::fprintf(stderr, "bench_home: %s\n", kZindNotice);

  HomeSurveyOptions base;
  base.survey.report_frames = 4;
  const std::vector<PanoView> views = TurnInPlaceViews(base.survey.panorama_views);
  nlohmann::json with_labels = {{"version", 1}, {"kind", "home"}, {"rooms", nlohmann::json::array()}};
  nlohmann::json without = with_labels;
  for (const ZindPanorama* pano : panos) {
    const std::string name = pano->label + " " + pano->pano_id;
    const fs::path dir = out / "captures" / pano->pano_id;
    // Each room in a frame of its own: the pano frame, as a user's capture would be.
    WriteZindCapture(*pano, dir);
    // ZInD's passages between the parts of one open space are the openings
    // the rooms share there: drawn as door labels here (a doorway without a
    // leaf), where bench_pano_survey ignores them.
    ZindPanorama with_passages = *pano;
    for (ZindOpening& o : with_passages.layout_raw.openings) {
      if (o.kind == ZindOpeningKind::kOpening) o.kind = ZindOpeningKind::kDoor;
    }
    for (std::size_t i = 0; i < views.size(); ++i) {
      WriteImageAtomic(dir / "labels" / fmt::format("{:03d}.png", i), LayoutLabels(with_passages, views[i]));
    }
    with_labels["rooms"].push_back({{"name", name}, {"capture", dir / "capture.json"}, {"labels", dir / "labels"}});
    without["rooms"].push_back({{"name", name}, {"capture", dir / "capture.json"}});
  }
  WriteFileAtomic(out / "home_labels.json", with_labels.dump(2) + "\n");
  WriteFileAtomic(out / "home_model.json", without.dump(2) + "\n");

  double load[1] = {0};
  const bool have_load = ::getloadavg(load, 1) == 1;
  std::vector<Run> runs;
  auto run = [&](const std::string& what, const fs::path& home, HomeSurveyOptions options) {
    Run r{.name = what};
    const auto t0 = std::chrono::steady_clock::now();
    r.result = RunHomeSurvey(home, out / fs::path(home).stem(), options, [&](const std::string& line) {
      std::fprintf(stderr, "bench_home: %s: %s\n", what.c_str(), line.c_str());
    });
    std::fprintf(stderr, "bench_home: %s: %.0f s\n", what.c_str(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    r.score = Score(r.result, panos);
    {
      std::vector<Eigen::Isometry2d> truth;
      std::vector<std::vector<Vec2>> outlines;
      for (int i : r.result.surveyed) {
        const ZindPanorama& p = *panos[static_cast<std::size_t>(i)];
        truth.push_back(p.floor_from_pano);
        std::vector<Vec2> o;
        for (const Vec2& v : p.layout_raw.vertices_m) o.push_back(p.floor_from_pano * v);
        outlines.push_back(std::move(o));
      }
      r.edits = ScriptedEdits(r.result.inputs, truth, outlines, &r.misplaced);
    }
    if (std::getenv("ASBUILT_BENCH_HOME_DEBUG") != nullptr) {
      std::vector<Eigen::Isometry2d> truth, found;
      std::vector<char> all(r.result.inputs.size(), 1), placed;
      for (std::size_t k = 0; k < r.result.surveyed.size(); ++k) {
        truth.push_back(panos[static_cast<std::size_t>(r.result.surveyed[k])]->floor_from_pano);
        found.push_back(r.result.placement.best.rooms[k].floor_from_room);
        placed.push_back(r.result.placement.best.rooms[k].placed);
      }
      std::vector<std::string> dt, df;
      const double st = FitScore(r.result.inputs, truth, all, options.placement, &dt);
      const double sf = FitScore(r.result.inputs, found, placed, options.placement, &df);
      std::fprintf(stderr, "fit of the truth %.2f:\n", st);
      for (const std::string& l : dt) std::fprintf(stderr, "  %s\n", l.c_str());
      std::fprintf(stderr, "fit of the placement %.2f:\n", sf);
      for (const std::string& l : df) std::fprintf(stderr, "  %s\n", l.c_str());
    }
    for (int k = 0; k < 5; ++k) r.placement_seconds.push_back(PlaceRooms(r.result.inputs, options.placement).seconds);
    std::fprintf(stderr, "bench_home: %s: %s\n%s\n", what.c_str(), r.score.ToString().c_str(),
                 r.result.placement.best.ToString(r.result.inputs).c_str());
    runs.push_back(std::move(r));
  };
  HomeSurveyOptions labels = base;
  // Layout labels mark the clear opening and the wall's face (bench_pano_survey).
  labels.survey.plan.door_casing_m = labels.survey.plan.window_casing_m = 0.0;
  labels.survey.points.contact_snap_px = 0;
  labels.survey.points.skirting_depth_m = 0.0;
  run("layout labels", out / "home_labels.json", labels);
  if (with_model) {
    run("shipped model", out / "home_model.json", base);
    HomeSurveyOptions real = base;
    real.survey.model_path = ModelPathFor("real");
    if (fs::exists(real.survey.model_path)) run("`--model real`", out / "home_model.json", real);
  }

  std::string md = "## a whole home from its panoramas: ZInD sample tour (bench_home)\n\n";
  md += fmt::format("**{}.** ", kZindNotice);
  md += fmt::format(
      "Issue 40. The {} primary panoramas of `../shared/data/zind_sample_tour` as one home.json, each room's capture "
      "in its own frame (`asbuilt survey home.json`, docs/home.md): every room surveyed, then placed from the doors "
      "the rooms share. A room is placed when, after the one rigid transform that best aligns the whole home, its "
      "centroid is within 10 cm and its yaw within 1° of ZInD's pose; floor IoU is the union of the placed rooms' "
      "outlines against the union of the true ones. ZInD's passages between parts of one open space are drawn as "
      "door labels in the layout-label run. Measured {} on {} hardware threads{}.\n\n",
      panos.size(), Today(), std::thread::hardware_concurrency(),
      have_load ? fmt::format(", load average {:.1f} at start", load[0]) : std::string());
  md +=
      "| labels from | rooms placed (10 cm, 1°) | floor IoU | links (loops) | partition | placement time, median of 5 "
      "| "
      "scripted surveyor: edits / misplaced rooms | targets |\n|---|---|---|---|---|---|---|---|\n";
  for (const Run& r : runs) {
    const bool exact = r.name == "layout labels";
    const int need = exact ? 12 : 9;
    const double iou = exact ? 0.93 : 0.80;
    const double t = Median(r.placement_seconds);
    md += fmt::format(
        "| {} | {}/{} | {:.3f} | {} ({}) | {:.3f} m | {:.3f} s | {} / {} | ≥ {} rooms {}, IoU ≥ {:.2f} {}, ≤ 2 s {}, "
        "≤ 1 edit per misplaced room {} |\n",
        r.name, r.score.within, r.score.rooms, r.score.floor_iou, r.result.placement.best.links.size(),
        r.result.placement.best.loops, r.result.placement.best.wall_thickness_m, t, r.edits, r.misplaced, need,
        r.score.within >= need ? "✓" : "✗", iou, r.score.floor_iou >= iou ? "✓" : "✗", t <= 2.0 ? "✓" : "✗",
        r.edits <= r.misplaced ? "✓" : "✗");
  }
  md += "\n";
  for (const Run& r : runs) md += fmt::format("### {}\n\n{}\n", r.name, RoomTable(r));
  md += SyntheticSection();
  if (!with_model) md += "The segmenter runs were skipped (no LibTorch, no model, or ASBUILT_BENCH_HOME_MODEL=0).\n\n";
  WriteSection(results, md);
  return 0;
}
