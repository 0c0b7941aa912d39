// bench_review: a scripted surveyor corrects the shipped model's panorama
// surveys of the ZInD sample tour's primary rooms through the review's API
// (review/review_session.h, the same edits the page and the HTTP API make).
// ZInD (../shared/data/zind_sample_tour) is read at run time: academic use
// only, a test set, never training data; surveys and reviews go under the
// build folder (bench/review/), never into the repository.
//
// The surveyor sees the truth corners (pixels of the room's raw layout in the
// panorama, with 1 px of noise) and makes, at each step, the one edit a person
// would: set the ceiling line once where it is off by more than 5 cm; trace the
// outline afresh (a click per corner and Enter, counted as that many edits)
// when its IoU is under 0.5 or fewer than half the room's corners have a
// plan corner within 1 m; then,
// with truth and plan corners paired one to one (nearest first, within 1 m),
// add a missing corner (an unpaired truth corner), else straighten a run of
// two or more spurious corners between two paired ones into one wall, else
// delete a spurious one (an unpaired plan corner), else move the worst-placed one onto its truth
// corner (a refused edit is followed by the next on this list) — until the room's 2D
// IoU with the truth reaches 0.95 or 12 edits. Reports per room the edits
// until IoU ≥ 0.95 (NoC@0.95) and every re-fit's time.
//
//   bench_review [RESULTS.md]
//   env ASBUILT_BENCH_REVIEW_PANORAMAS  at most N panoramas (default all)
//       ASBUILT_BENCH_REVIEW_REUSE      1: reuse surveys already in the build folder
//       ASBUILT_BENCH_REVIEW_MODEL      only this model (a shipped model's name or a file); default: the
//                                       default model, then `real`
//       ASBUILT_BENCH_REVIEW_TRACE      1: print the corners after every edit

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "asbuilt/formats/zind.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/plan/room_iou.h"
#include "asbuilt/review/review_session.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/file.h"
#include "bench/bench_util.h"
#include "bench/zind_capture.h"

namespace {

using namespace asbuilt;
namespace fs = std::filesystem;

constexpr double kTargetIou = 0.95;
constexpr int kMaxEdits = 12;
constexpr double kPairM = 1.0;

struct RoomResult {
  std::string pano, label;
  std::string error;
  double start_iou = 0, end_iou = 0;
  int edits = 0;
  int noc = -1;  // Edits until IoU ≥ 0.95; −1: not within kMaxEdits.
  int refused = 0;
  std::vector<double> refit_ms;
  // Openings (doors and windows of the truth on the room's walls).
  int truth_openings = 0;
  int openings_right_start = 0, openings_right_end = 0;
  int opening_edits = 0;                   // add / move / delete edits.
  int opening_clicks = 0;                  // A box (add, move) is two clicks, a delete one.
  int openings_done = -1;                  // Opening edits until every opening is right; −1: not within the budget.
  int clicks_tried = 0, clicks_right = 0;  // One-click adds, and those right at once.
};

// An opening of the state is right for a truth opening: the same kind, both
// ends within kOpeningEndM.
constexpr double kOpeningEndM = 0.15;
bool OpeningRight(const nlohmann::json& o, const PlanOpening& t) {
  if (o["kind"] != OpeningKindName(t.kind)) return false;
  const Vec2 a(o["start_m"][0], o["start_m"][1]), b(o["end_m"][0], o["end_m"][1]);
  const double same = std::max((a - t.start).norm(), (b - t.end).norm());
  const double swapped = std::max((a - t.end).norm(), (b - t.start).norm());
  return std::min(same, swapped) <= kOpeningEndM;
}

double Iou(const nlohmann::json& state, const Plan& truth) {
  const Plan plan = PlanFromJson(state["plan"], "state.plan");
  if (plan.rooms.empty()) return 0.0;
  const auto overlap = RoomPolygonOverlap(plan, truth);
  return overlap ? overlap->Iou() : 0.0;
}

// The openings, after the corners: add a missing one — with one click
// inside it (the review finds its jambs, head and sill in the photo), or,
// where that was tried or `one_click` is off, a box from its head on one
// side to its sill on the other — else redraw a wrong one as a box (the
// nearest of its kind within 1 m), else delete a spurious one of the
// survey's or of a click's; each truth opening drawn as a box once at most;
// until every opening is right, nothing is left to do, or the budget (three
// edits an opening, and four) is spent. Edits go through `edit` (false:
// refused), which keeps `state` current.
void CorrectOpenings(const Plan& truth, int width, const std::function<Vec2(const Vec3&)>& pixel,
                     const std::function<bool(nlohmann::json)>& edit, const nlohmann::json& state, bool one_click,
                     RoomResult& r) {
  r.truth_openings = static_cast<int>(truth.openings.size());
  const int budget = 3 * r.truth_openings + 4;
  auto count_right = [&] {
    int right = 0;
    for (const PlanOpening& t : truth.openings) {
      right += std::any_of(state["openings"].begin(), state["openings"].end(),
                           [&](const nlohmann::json& o) { return OpeningRight(o, t); });
    }
    return right;
  };
  r.openings_right_start = count_right();
  // A truth opening drawn once is where the photo shows it: a person does
  // not draw it again (its ends can still be off where the walls are).
  std::vector<bool> drawn(truth.openings.size(), false), clicked(truth.openings.size(), false);
  std::vector<int> found_by_click;  // Ids of the openings one click added.
  struct Candidate {
    int clicks = 1;
    nlohmann::json edit;
    int draws = -1, clicks_on = -1;  // The truth opening it draws as a box, or finds by a click.
  };
  while (r.opening_edits < budget) {
    std::vector<bool> used(state["openings"].size(), false);
    std::vector<int> wrong;
    for (std::size_t t = 0; t < truth.openings.size(); ++t) {
      bool right = false;
      for (std::size_t i = 0; i < used.size() && !right; ++i) {
        if (!used[i] && OpeningRight(state["openings"][i], truth.openings[t])) used[i] = right = true;
      }
      if (!right) wrong.push_back(static_cast<int>(t));
    }
    const bool spurious = std::find(used.begin(), used.end(), false) != used.end();
    if (wrong.empty() && !spurious) {
      r.openings_done = r.opening_edits;
      break;
    }
    std::vector<Candidate> candidates;
    for (int t : wrong) {
      if (drawn[t]) continue;
      const PlanOpening& o = truth.openings[t];
      const double sill = o.sill.value_or(0.0), top = sill + o.height.value_or(2.0);
      const Vec2 mid = o.Centre();
      const Vec2 p0 = pixel(Vec3(o.start.x(), o.start.y(), 0.5 * (sill + top)));
      const Vec2 p1 = pixel(Vec3(o.end.x(), o.end.y(), 0.5 * (sill + top)));
      nlohmann::json box = {{"kind", OpeningKindName(o.kind)},
                            {"u0", std::clamp(p0.x(), 0.0, width - 1.0)},
                            {"u1", std::clamp(p1.x(), 0.0, width - 1.0)},
                            {"v_top", pixel(Vec3(mid.x(), mid.y(), top)).y()},
                            {"v_bottom", pixel(Vec3(mid.x(), mid.y(), sill)).y()}};
      int nearest = -1;
      double best = 1.0;
      for (std::size_t i = 0; i < used.size(); ++i) {
        const nlohmann::json& p = state["openings"][i];
        const Vec2 c = 0.5 * (Vec2(p["start_m"][0], p["start_m"][1]) + Vec2(p["end_m"][0], p["end_m"][1]));
        if (!used[i] && p["kind"] == box["kind"] && (c - mid).norm() < best) best = (c - mid).norm(), nearest = int(i);
      }
      if (nearest < 0 && one_click && !clicked[t]) {
        const Vec2 c = pixel(Vec3(mid.x(), mid.y(), 0.5 * (sill + top)));
        candidates.push_back({.clicks = 1,
                              .edit = {{"op", "add_opening"},
                                       {"kind", OpeningKindName(o.kind)},
                                       {"u", std::clamp(c.x(), 0.0, width - 1.0)},
                                       {"v", c.y()}},
                              .clicks_on = t});
        continue;
      }
      box["op"] = nearest >= 0 ? "move_opening" : "add_opening";
      if (nearest >= 0) {
        box["id"] = state["openings"][nearest]["id"];
        used[nearest] = true;
      }
      candidates.push_back({.clicks = 2, .edit = box, .draws = t});
    }
    for (std::size_t i = 0; i < used.size(); ++i) {
      const int id = state["openings"][i]["id"];
      if (!used[i] && (state["openings"][i]["by"] != "user" ||
                       std::find(found_by_click.begin(), found_by_click.end(), id) != found_by_click.end())) {
        candidates.push_back({.clicks = 1, .edit = {{"op", "delete_opening"}, {"id", id}}});
      }
    }
    bool done = false;
    for (std::size_t c = 0; c < candidates.size() && r.opening_edits < budget && !done; ++c) {
      r.opening_clicks += candidates[c].clicks;
      done = edit(candidates[c].edit);
      if (candidates[c].draws >= 0) drawn[candidates[c].draws] = true;
      if (candidates[c].clicks_on >= 0) {
        clicked[candidates[c].clicks_on] = true;
        ++r.clicks_tried;
        if (done) {
          found_by_click.push_back(state["openings"].back()["id"]);
          r.clicks_right += OpeningRight(state["openings"].back(), truth.openings[candidates[c].clicks_on]);
          if (std::getenv("ASBUILT_BENCH_REVIEW_TRACE")) {
            const PlanOpening& t = truth.openings[candidates[c].clicks_on];
            std::fprintf(stderr, "  one click %s: truth (%.2f,%.2f)-(%.2f,%.2f) %.2f m, %.2f–%.2f; found %s\n",
                         OpeningKindName(t.kind), t.start.x(), t.start.y(), t.end.x(), t.end.y(), t.width,
                         t.sill.value_or(0.0), t.sill.value_or(0.0) + t.height.value_or(2.0),
                         state["openings"].back().dump().c_str());
          }
        }
      }
    }
    if (!done) break;
  }
  r.openings_right_end = count_right();
}

RoomResult Correct(const fs::path& survey, const ZindPanorama& pano, std::mt19937& rng, bool one_click) {
  RoomResult r{.pano = pano.pano_id, .label = pano.label};
  ReviewSession session = ReviewSession::Open(survey);
  nlohmann::json state = session.State();
  const Plan truth = ZindTruthPlan(pano);
  const std::vector<Vec2>& corners = truth.rooms.at(0).polygon;
  const int width = state["images"][0]["width"], height = state["images"][0]["height"];
  const Vec3 camera(0, 0, pano.camera_height_m);
  std::normal_distribution<double> noise(0.0, 1.0);
  auto pixel = [&](const Vec3& p) -> Vec2 {  // A Vec2, not an Eigen expression of temporaries.
    return EquirectPixelFromDirection(p - camera, width, height) + Vec2(noise(rng), noise(rng));
  };
  int* counter = &r.edits;  // Corner edits, then opening edits.
  auto edit = [&](nlohmann::json e) {
    ++*counter;
    try {
      state = session.Edit(e);
      r.refit_ms.push_back(state["refit_ms"].get<double>());
      std::fprintf(stderr, "bench_review: %s: %s → %zu corners, IoU %.3f, %.1f ms\n", pano.pano_id.c_str(),
                   e["op"].get<std::string>().c_str(), state["corners"].size(), Iou(state, truth), r.refit_ms.back());
      if (std::getenv("ASBUILT_BENCH_REVIEW_TRACE")) {
        std::string line;
        for (const nlohmann::json& c : state["corners"])
          line += fmt::format(" {}{}({:.2f},{:.2f})", c["by"] == "user" ? "*" : "", c["id"].get<int>(),
                              c["xy_m"][0].get<double>(), c["xy_m"][1].get<double>());
        std::fprintf(stderr, "    %s\n", line.c_str());
      }
      return true;
    } catch (const EditError& error) {
      std::fprintf(stderr, "bench_review: %s: %s refused: %s\n", pano.pano_id.c_str(), e.dump().c_str(), error.what());
      ++r.refused;
      return false;
    }
  };
  r.start_iou = Iou(state, truth);
  if (std::getenv("ASBUILT_BENCH_REVIEW_TRACE")) {
    std::string line;
    for (const Vec2& c : corners) line += fmt::format(" ({:.2f},{:.2f})", c.x(), c.y());
    std::fprintf(stderr, "  truth:%s\n", line.c_str());
  }
  double iou = r.start_iou;
  // The ceiling line, once, on the middle of the longest truth wall.
  if (std::abs(state["ceiling_height_m"].get<double>() - pano.ceiling_height_m) > 0.05) {
    const PlanWall* longest = &truth.walls.front();
    for (const PlanWall& w : truth.walls) longest = w.Length() > longest->Length() ? &w : longest;
    const Vec2 mid = 0.5 * (longest->start + longest->end);
    const Vec2 px = pixel(Vec3(mid.x(), mid.y(), pano.ceiling_height_m));
    edit({{"op", "ceiling"}, {"u", std::clamp(px.x(), 0.0, width - 1.0)}, {"v", px.y()}});
    iou = Iou(state, truth);
  }
  if (iou >= kTargetIou) r.noc = r.edits;
  bool traced = false;
  while (r.noc < 0 && r.edits < kMaxEdits) {
    std::vector<Vec2> plan_corners;
    std::vector<int> ids;
    for (const nlohmann::json& c : state["corners"]) {
      plan_corners.emplace_back(c["xy_m"][0], c["xy_m"][1]);
      ids.push_back(c["id"]);
    }
    auto nearest = [](const std::vector<Vec2>& set, const Vec2& p) {
      int best = -1;
      double d = INFINITY;
      for (std::size_t i = 0; i < set.size(); ++i) {
        if ((set[i] - p).norm() < d) d = (set[i] - p).norm(), best = static_cast<int>(i);
      }
      return std::pair{best, d};
    };
    // Truth and plan corners paired one to one, nearest first, within kPairM:
    // an unpaired truth corner is missing, an unpaired plan corner spurious,
    // a paired one misplaced by its distance.
    std::vector<std::tuple<double, int, int>> pairs;
    for (std::size_t i = 0; i < plan_corners.size(); ++i) {
      for (std::size_t t = 0; t < corners.size(); ++t) {
        const double d = (plan_corners[i] - corners[t]).norm();
        if (d <= kPairM) pairs.emplace_back(d, static_cast<int>(i), static_cast<int>(t));
      }
    }
    std::sort(pairs.begin(), pairs.end());
    std::vector<int> truth_of(plan_corners.size(), -1), plan_of(corners.size(), -1);
    for (const auto& [d, i, t] : pairs) {
      if (truth_of[i] < 0 && plan_of[t] < 0) truth_of[i] = t, plan_of[t] = i;
    }
    // An outline far off (IoU under 0.5, or fewer than half the room's
    // corners within 1 m of one of its own) is traced afresh: a click per
    // corner and Enter.
    const int m = static_cast<int>(corners.size());
    const int paired = static_cast<int>(std::count_if(plan_of.begin(), plan_of.end(), [](int i) { return i >= 0; }));
    if (!traced && (iou < 0.5 || 2 * paired < m) && r.edits + m + 1 <= kMaxEdits) {
      traced = true;
      nlohmann::json points = nlohmann::json::array();
      for (const Vec2& c : corners) {
        const Vec2 px = pixel(Vec3(c.x(), c.y(), 0.0));
        points.push_back({{"u", std::clamp(px.x(), 0.0, width - 1.0)}, {"v", px.y()}});
      }
      if (edit({{"op", "trace"}, {"points", points}})) {
        r.edits += m;  // The clicks; edit() counted the Enter.
        iou = Iou(state, truth);
        if (iou >= kTargetIou) r.noc = r.edits;
        continue;
      }
    }
    // The edits a person would make, best first; a refused one (the page
    // says why) is followed by the next.
    std::vector<nlohmann::json> candidates;
    for (int t = 0; t < m; ++t) {  // Missing corners.
      if (plan_of[t] < 0) {
        const Vec2 px = pixel(Vec3(corners[t].x(), corners[t].y(), 0.0));
        nlohmann::json e = {{"op", "add_corner"}, {"u", std::clamp(px.x(), 0.0, width - 1.0)}, {"v", px.y()}};
        candidates.push_back(e);
      }
    }
    // Runs of two or more spurious corners between two paired ones: one
    // straighten edit each, longest run first.
    std::vector<std::pair<int, nlohmann::json>> runs;
    const int n = static_cast<int>(plan_corners.size());
    for (int a = 0; a < n; ++a) {
      if (truth_of[a] < 0) continue;
      int b = (a + 1) % n, between = 0;
      while (b != a && truth_of[b] < 0) b = (b + 1) % n, ++between;
      if (b != a && between >= 2 && n - between >= 3)
        runs.push_back({between, {{"op", "straighten"}, {"from", ids[a]}, {"to", ids[b]}}});
    }
    std::stable_sort(runs.begin(), runs.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    for (const auto& run : runs) candidates.push_back(run.second);
    for (std::size_t i = 0; i < plan_corners.size() && plan_corners.size() > 3; ++i) {  // Spurious ones.
      if (truth_of[i] < 0) candidates.push_back({{"op", "delete_corner"}, {"id", ids[i]}});
    }
    std::vector<std::pair<double, nlohmann::json>> moves;  // Misplaced ones, worst first.
    for (std::size_t i = 0; i < plan_corners.size(); ++i) {
      const int t = truth_of[i] >= 0 ? truth_of[i] : nearest(corners, plan_corners[i]).first;
      const Vec2 px = pixel(Vec3(corners[t].x(), corners[t].y(), 0.0));
      moves.push_back(
          {(plan_corners[i] - corners[t]).norm(),
           {{"op", "move_corner"}, {"id", ids[i]}, {"u", std::clamp(px.x(), 0.0, width - 1.0)}, {"v", px.y()}}});
    }
    std::stable_sort(moves.begin(), moves.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& m : moves) candidates.push_back(m.second);
    for (const nlohmann::json& e : candidates) {
      if (r.edits >= kMaxEdits || edit(e)) break;
    }
    iou = Iou(state, truth);
    if (iou >= kTargetIou) r.noc = r.edits;
  }
  r.end_iou = iou;

  counter = &r.opening_edits;
  CorrectOpenings(truth, width, pixel, edit, state, one_click, r);
  return r;
}

// Surveys every panorama with `model` and corrects each survey.
std::vector<RoomResult> RunModel(const fs::path& model, const std::vector<const ZindPanorama*>& panos,
                                 const fs::path& out, bool reuse, bool one_click) {
  std::mt19937 rng(1);
  std::vector<RoomResult> rooms;
  for (const ZindPanorama* pano : panos) {
    const std::string name = pano->complete_room_id + "_" + pano->partial_room_id + "_" + pano->pano_id;
    const fs::path dir = out / model.stem() / name;
    asbuilt::bench::WriteZindCapture(*pano, dir);
    RoomResult r{.pano = pano->pano_id, .label = pano->label};
    try {
      if (!reuse || !fs::exists(dir / "survey" / "review" / "input.json")) {
        fs::remove_all(dir / "survey");
        RunSurvey(dir / "capture.json", dir / "survey", {.model_path = model, .write_report = false});
      }
      r = Correct(dir / "survey", *pano, rng, one_click);
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    std::fprintf(stderr, "bench_review: %s %s: IoU %.3f → %.3f, NoC@0.95 %d, %d edits\n", r.pano.c_str(),
                 r.label.c_str(), r.start_iou, r.end_iou, r.noc, r.edits);
    rooms.push_back(r);
  }
  return rooms;
}

// The figures against the targets, then a row per room.
std::string ModelSection(const std::string& title, const std::vector<RoomResult>& rooms,
                         const std::vector<RoomResult>& boxes) {
  std::vector<double> noc, refits;
  int within = 0, total_edits = 0, opening_clicks = 0, truth_openings = 0, right_start = 0, right_end = 0,
      openings_done = 0, clicks_tried = 0, clicks_right = 0;
  std::string table =
      "| panorama | room | IoU start | IoU end | NoC@0.95 | edits (refused) | openings right, start → end | "
      "opening edits (clicks) | re-fit median ms |\n"
      "|---|---|---|---|---|---|---|---|---|\n";
  for (const RoomResult& r : rooms) {
    if (!r.error.empty()) {
      table += fmt::format("| {} | {} | error: {} ||||\n", r.pano, r.label, r.error);
      noc.push_back(kMaxEdits + 1);
      continue;
    }
    noc.push_back(r.noc >= 0 ? r.noc : kMaxEdits + 1);
    within += r.noc >= 0 && r.noc <= 10;
    total_edits += r.edits;
    refits.insert(refits.end(), r.refit_ms.begin(), r.refit_ms.end());
    opening_clicks += r.opening_clicks;
    truth_openings += r.truth_openings;
    right_start += r.openings_right_start;
    right_end += r.openings_right_end;
    openings_done += r.openings_done >= 0;
    clicks_tried += r.clicks_tried;
    clicks_right += r.clicks_right;
    table += fmt::format("| {} | {} | {:.3f} | {:.3f} | {} | {} ({}) | {} → {} of {} | {} ({}) | {:.2f} |\n", r.pano,
                         r.label, r.start_iou, r.end_iou,
                         r.noc >= 0 ? std::to_string(r.noc) : fmt::format("> {}", kMaxEdits), r.edits, r.refused,
                         r.openings_right_start, r.openings_right_end, r.truth_openings,
                         r.openings_done >= 0 ? std::to_string(r.openings_done) : fmt::format("> {}", r.opening_edits),
                         r.opening_clicks, r.refit_ms.empty() ? 0.0 : asbuilt::bench::Median(r.refit_ms));
  }
  int box_corners = 0, box_openings = 0, box_done = 0;
  for (const RoomResult& r : boxes) {
    box_corners += r.edits;
    box_openings += r.opening_clicks;
    box_done += r.openings_done >= 0;
  }
  std::sort(refits.begin(), refits.end());
  const double p95 = refits.empty() ? 0.0 : refits[std::min(refits.size() - 1, std::size_t(0.95 * refits.size()))];
  double mean = 0;
  for (double v : noc) mean += v;
  mean = noc.empty() ? 0 : mean / noc.size();
  return fmt::format(
             "### {}\n\n"
             "| figure | value | target |\n|---|---|---|\n"
             "| NoC@0.95, median | {:.1f} | ≤ 2 |\n| NoC@0.95, mean | {:.2f} | ≤ 3 |\n"
             "| rooms at IoU ≥ 0.95 within 10 edits | {}/{} | all |\n"
             "| openings right (ends within {:.2f} m), before → after | {} → {} of {} | all |\n"
             "| rooms with every opening right | {}/{} | all |\n"
             "| clicks, all rooms: corners and ceiling + openings | {} + {} = {} | ≤ 40 % of 153 = 61 |\n"
             "| one-click openings right at once | {} of {} | – |\n"
             "| the same surveyor drawing every opening as a box (same run) | {} + {} = {} clicks, {}/{} rooms with "
             "every opening right | – |\n"
             "| re-fit, p95 over {} edits | {:.2f} ms | ≤ 100 ms |\n\n",
             title, asbuilt::bench::Median(noc), mean, within, rooms.size(), kOpeningEndM, right_start, right_end,
             truth_openings, openings_done, rooms.size(), total_edits, opening_clicks, total_edits + opening_clicks,
             clicks_right, clicks_tried, box_corners, box_openings, box_corners + box_openings, box_done, boxes.size(),
             refits.size(), p95) +
         table + "\n";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace asbuilt::bench;
  const std::string results = ResultsPath(argc, argv, "review");
  const fs::path tour_dir = fs::path(ASBUILT_SHARED_DATA_DIR) / "zind_sample_tour";
  if (!fs::exists(tour_dir / "zind_data.json") || !SegmenterAvailable() || !fs::exists(DefaultModelPath())) {
    std::fprintf(stderr, "bench_review: needs %s and the shipped model; %s left as it was\n", tour_dir.c_str(),
                 results.c_str());
    return 0;
  }
  std::fprintf(stderr, "bench_review: %s\n", kZindNotice);
  const fs::path out = fs::path(ASBUILT_BINARY_DIR) / "bench" / "review";
  const ZindTour tour = ReadZindTour(tour_dir);
  std::vector<const ZindPanorama*> panos = tour.BenchmarkPanoramas();
  if (const int n = EnvPositiveInt("ASBUILT_BENCH_REVIEW_PANORAMAS", 0); n > 0 && n < int(panos.size()))
    panos.resize(n);
  const bool reuse = EnvPositiveInt("ASBUILT_BENCH_REVIEW_REUSE", 0) > 0;
  // The default model, and the one the survey recommends for real panoramas.
  std::vector<std::pair<std::string, fs::path>> models;
  if (const char* env = std::getenv("ASBUILT_BENCH_REVIEW_MODEL"); env != nullptr && *env != 0) {
    models.push_back({env, ModelPathFor(env)});
  } else {
    models.push_back({"the default model", DefaultModelPath()});
    const fs::path real = ModelPathFor("real");
    if (fs::exists(real) && !fs::equivalent(real, DefaultModelPath())) models.push_back({"`--model real`", real});
  }
  std::string md = fmt::format(
      "## Review: a scripted surveyor corrects panorama surveys (ZInD sample tour)\n\n"
      "Research measurement (ZInD: academic use only, a test set). Measured {} on the 2-core development machine. "
      "{} rooms; a room not at IoU 0.95 within "
      "{} edits counts as {}. The surveyor traces the outline afresh where fewer than half the corners are near the "
      "truth (a click per corner and Enter, counted as that many edits), else adds a missing corner, else straightens "
      "a run of spurious corners into "
      "one wall, else deletes one, else moves the worst-placed one; then it adds each missing door or window with one "
      "click inside it "
      "(asbuilt finds its jambs, head and sill in the photo; where that comes out wrong, it redraws it as a box: two "
      "more clicks), redraws a wrong one of the survey's as a box, deletes a spurious one, until every opening has "
      "both ends within 0.15 m of "
      "the truth (bench/review/review_bench.cc).\n\n",
      Today(), panos.size(), kMaxEdits, kMaxEdits + 1);
  for (const auto& [title, model] : models) {
    const std::vector<RoomResult> rooms = RunModel(model, panos, out, reuse, /*one_click=*/true);
    const std::vector<RoomResult> boxes = RunModel(model, panos, out, /*reuse=*/true, /*one_click=*/false);
    md += ModelSection(fmt::format("From {} ({})", title, model.filename().string()), rooms, boxes);
  }
  WriteSection(results, md);
  return 0;
}
