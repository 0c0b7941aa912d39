#include "asbuilt/review/review_session.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/pipeline/report.h"
#include "asbuilt/pipeline/review_input.h"
#include "asbuilt/plan/drawing.h"
#include "asbuilt/plan/fit_plan.h"
#include "asbuilt/plan/plan_wall_line.h"
#include "asbuilt/plan/verdict.h"
#include "asbuilt/review/opening_finder.h"
#include "asbuilt/review/review_layout.h"
#include "asbuilt/review/training_example.h"
#include "asbuilt/review/view_geometry.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

using namespace review_layout;

using Clock = std::chrono::steady_clock;

constexpr double kMaxFloorDistanceM = 30.0;
constexpr double kMaxCeilingM = 10.0;

}  // namespace

struct ReviewSession::Impl {
  fs::path out_dir;
  ReviewInput input;
  std::unique_ptr<PlanFitter> fitter;
  nlohmann::json survey_summary;  // OUT/summary.json, when readable.
  Layout initial;
  Layout layout;
  PlanResult fit;
  std::vector<Layout> undo, redo;
  nlohmann::json log = nlohmann::json::array();  // Every edit in order (corrections.json).
  double fit_seconds = 0.0;
  std::string no_walls_note;  // Set when the survey's own plan had no walls.
  // Per image of input.images, read when an opening is first found by a click.
  mutable std::vector<std::optional<ImageGradients>> gradients;

  const ImageGradients& GradientsFor(const ReviewImage& image) const {
    const auto i = static_cast<std::size_t>(&image - input.images.data());
    if (gradients.size() != input.images.size()) gradients.assign(input.images.size(), std::nullopt);
    if (!gradients.at(i)) gradients[i] = GradientsOf(ReadGrayImage(image.image, "review image"));
    return *gradients[i];
  }

  const ReviewImage& ImageOf(const nlohmann::json& edit) const {
    if (input.kind == "panorama") return input.images.front();
    const int frame = Integer(edit, "frame");
    for (const ReviewImage& im : input.images) {
      if (im.frame == frame) return im;
    }
    throw EditError(fmt::format("{}: no frame {} in this capture", edit.value("op", ""), frame));
  }

  Vec2 PixelOf(const nlohmann::json& edit, const ReviewImage& image, const char* u_key, const char* v_key) const {
    const Vec2 pixel(Number(edit, u_key), Number(edit, v_key));
    if (!PixelInside(image, pixel)) {
      throw EditError(fmt::format("{}: ({}, {}) = ({:.1f}, {:.1f}) is outside the {}×{} image", edit.value("op", ""),
                                  u_key, v_key, pixel.x(), pixel.y(), image.width_px, image.height_px));
    }
    return pixel;
  }

  Vec2 FloorPoint(const nlohmann::json& edit) const {
    const ReviewImage& image = ImageOf(edit);
    const Vec2 pixel = PixelOf(edit, image, "u", "v");
    const std::optional<Vec2> xy = FloorPointOfPixel(image, pixel);
    if (!xy) {
      throw EditError(fmt::format("{}: ({:.1f}, {:.1f}) is at or above the horizon: a floor corner is seen below it",
                                  edit.value("op", ""), pixel.x(), pixel.y()));
    }
    const double d = (*xy - image.camera_m.head<2>()).norm();
    if (d > kMaxFloorDistanceM) {
      throw EditError(
          fmt::format("{}: ({:.1f}, {:.1f}) meets the floor {:.1f} m away (more than {:.0f} m): click "
                      "lower, on the wall's base",
                      edit.value("op", ""), pixel.x(), pixel.y(), d, kMaxFloorDistanceM));
    }
    return *xy;
  }

  // The horizontal distance to the wall seen in pixel's column: from its
  // floor edge (the median of the floor contacts within ±1.5° of its bearing,
  // which a ceiling height does not move), else from the plan's walls. Once
  // the person has set the corners, their plan comes first: the contacts are
  // the segmenter's reading.
  std::optional<double> WallDistanceInColumn(const ReviewImage& image, const Vec2& pixel, bool plan_first) const {
    if (plan_first) {
      if (const auto hit = WallOfPixel(image, fit.plan, pixel)) return hit->distance_m;
    }
    const Vec3 ray = RayOfPixel(image, pixel);
    const double bearing = std::atan2(ray.y(), ray.x());
    std::vector<double> distances;
    for (const ClassPoint& p : input.plan_input.points) {
      if (p.source != PointSource::kContact || p.label != LabelClass::kWall || p.position_m.z() > 0.1) continue;
      const Vec2 q = p.position_m.head<2>() - image.camera_m.head<2>();
      const double diff = std::remainder(std::atan2(q.y(), q.x()) - bearing, 2 * kPi);
      if (std::abs(diff) <= DegToRad(1.5)) distances.push_back(q.norm());
    }
    if (distances.size() >= 3) {
      std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
      return distances[distances.size() / 2];
    }
    const auto hit = WallOfPixel(image, fit.plan, pixel);
    if (!hit) return std::nullopt;
    return hit->distance_m;
  }

  int CornerIndex(const Layout& l, int id, const std::string& op) const {
    for (std::size_t i = 0; i < l.corners.size(); ++i) {
      if (l.corners[i].id == id) return static_cast<int>(i);
    }
    throw EditError(fmt::format("{}: no corner with id {}", op, id));
  }
  int OpeningIndex(const Layout& l, int id, const std::string& op) const {
    for (std::size_t i = 0; i < l.openings.size(); ++i) {
      if (l.openings[i].id == id) return static_cast<int>(i);
    }
    throw EditError(fmt::format("{}: no opening with id {}", op, id));
  }

  // An opening from its two end columns, head and sill rows, on the walls of the current plan.
  Opening OpeningFrom(const nlohmann::json& edit, int id) const {
    const std::string op = edit.value("op", "");
    if (!edit.contains("kind") || !edit["kind"].is_string() || (edit["kind"] != "door" && edit["kind"] != "window")) {
      throw EditError(fmt::format("{}: \"kind\" must be \"door\" or \"window\"", op));
    }
    if (edit.contains("start_m")) {  // In plan metres (scripts): ends on the floor, sill and head heights.
      Opening o{.id = id,
                .kind = edit["kind"] == "window" ? OpeningKind::kWindow : OpeningKind::kDoor,
                .start_m = PlanPoint(edit, "start_m", op),
                .end_m = PlanPoint(edit, "end_m", op),
                .bottom_m = Number(edit, "bottom_m"),
                .top_m = Number(edit, "top_m"),
                .user = true};
      if (!((o.end_m - o.start_m).norm() >= 0.05))
        throw EditError(fmt::format("{}: start_m and end_m must be 5 cm or more apart", op));
      if (!(o.bottom_m >= 0 && o.top_m > o.bottom_m + 0.05 && o.top_m < kMaxCeilingM)) {
        throw EditError(fmt::format("{}: bottom_m ({}) and top_m ({}) leave no opening", op, o.bottom_m, o.top_m));
      }
      return o;
    }
    const ReviewImage& image = ImageOf(edit);
    if (!edit.contains("u0") && edit.contains("u")) return OpeningAtClick(edit, image, id);
    const double v_top = Number(edit, "v_top"), v_bottom = Number(edit, "v_bottom");
    const Vec2 p0 = PixelOf(edit, image, "u0", "v_top"), p1 = PixelOf(edit, image, "u1", "v_bottom");
    if (!(v_top < v_bottom))
      throw EditError(fmt::format("{}: v_top ({}) must be above v_bottom ({})", op, v_top, v_bottom));
    if (std::abs(p0.x() - p1.x()) < 1.0)
      throw EditError(fmt::format("{}: u0 and u1 must differ by a pixel or more", op));
    const double v_mid = 0.5 * (v_top + v_bottom);
    double u_mid = 0.5 * (p0.x() + p1.x());
    if (image.frame < 0 && std::abs(p0.x() - p1.x()) > 0.5 * image.width_px) {
      u_mid = std::fmod(u_mid + 0.5 * image.width_px, image.width_px);  // Across the panorama's seam.
    }
    const auto a = WallOfPixel(image, fit.plan, {p0.x(), v_mid});
    const auto b = WallOfPixel(image, fit.plan, {p1.x(), v_mid});
    const auto m = WallOfPixel(image, fit.plan, {u_mid, v_mid});
    if (!a || !b || !m) throw EditError(fmt::format("{}: the columns u0..u1 do not all meet a wall of the plan", op));
    Opening o{.id = id,
              .kind = edit["kind"] == "window" ? OpeningKind::kWindow : OpeningKind::kDoor,
              .start_m = a->xy_m,
              .end_m = b->xy_m,
              .user = true};
    o.top_m = HeightAtDistance(image, {u_mid, v_top}, m->distance_m);
    o.bottom_m = std::max(0.0, HeightAtDistance(image, {u_mid, v_bottom}, m->distance_m));
    if (o.kind == OpeningKind::kDoor && o.bottom_m < 0.1) o.bottom_m = 0.0;
    if (!(o.top_m > o.bottom_m + 0.05)) {
      throw EditError(fmt::format("{}: head ({:.2f} m) and sill ({:.2f} m) leave no opening", op, o.top_m, o.bottom_m));
    }
    return o;
  }

  // An opening found around one click on it (review/opening_finder.h).
  Opening OpeningAtClick(const nlohmann::json& edit, const ReviewImage& image, int id) const {
    const std::string op = edit.value("op", "");
    const Vec2 pixel = PixelOf(edit, image, "u", "v");
    const OpeningKind kind = edit["kind"] == "window" ? OpeningKind::kWindow : OpeningKind::kDoor;
    std::string why;
    const std::optional<FoundOpening> found =
        FindOpeningAt(GradientsFor(image), image, fit.plan, pixel, kind, CeilingM(), &why);
    if (!found) {
      throw EditError(fmt::format("{}: ({:.1f}, {:.1f}): {}; draw the {} as a box instead", op, pixel.x(), pixel.y(),
                                  why, OpeningKindName(kind)));
    }
    return {.id = id,
            .kind = kind,
            .start_m = found->start_m,
            .end_m = found->end_m,
            .bottom_m = found->bottom_m,
            .top_m = found->top_m,
            .user = true};
  }

  // Where a new corner at xy goes in l's corners: of the places where the
  // room crosses itself no more than it does now, the one of least cost, in
  // metres: how much longer the outline gets, plus how far the two new
  // walls stray from the room's dominant directions (length × |sin| of the
  // angle off), plus kOffBearingM when its bearing from the viewpoint is not
  // between its two neighbours' (the order a turn around the room sees them in).
  int InsertionIndex(const Layout& l, const Vec2& xy) const {
    constexpr double kOffBearingM = 0.5;
    const int n = static_cast<int>(l.corners.size());
    const std::vector<Vec2>& at = fit.plan.rooms.at(0).polygon;
    const Vec2 v = fitter->viewpoint();
    auto bearing = [&](const Vec2& p) { return std::atan2(p.y() - v.y(), p.x() - v.x()); };
    auto stray = [&](const Vec2& a, const Vec2& b) {
      const std::vector<double>& directions = fit.summary.dominant_directions_deg;
      if (directions.empty()) return 0.0;
      const double theta = std::atan2(b.y() - a.y(), b.x() - a.x());
      double off = kPi;
      for (double d : directions) {
        for (double turn : {0.0, 0.5 * kPi}) off = std::min(off, std::abs(AngleDiffModPi(theta, DegToRad(d) + turn)));
      }
      return (b - a).norm() * std::sin(off);
    };
    std::vector<std::pair<double, int>> order;
    for (int i = 0; i < n; ++i) {
      const Vec2 a = at[i], b = at[(i + 1) % n];
      const double ccw = std::remainder(bearing(b) - bearing(a), 2 * kPi);
      const double into = std::remainder(bearing(xy) - bearing(a), 2 * kPi);
      const bool holds = ccw > 0 && into >= 0 && into <= ccw;
      const double detour = (xy - a).norm() + (xy - b).norm() - (b - a).norm();
      order.push_back({detour + stray(a, xy) + stray(xy, b) + (holds ? 0.0 : kOffBearingM), i + 1});
    }
    std::sort(order.begin(), order.end());
    const std::vector<Vec2> hints = CornerPoints(l);
    const int crossings = PolygonCrossings(hints);
    for (const auto& [cost, index] : order) {
      std::vector<Vec2> with = hints;
      with.insert(with.begin() + index, xy);
      if (PolygonCrossings(with) <= crossings) return index;
    }
    return order.front().second;
  }

  // The whole outline replaced by `xy`, every corner the person's, turned
  // counter-clockwise (the room on the left, as the plan's rings) whichever
  // way it was given.
  static void SetOutline(Layout& l, std::vector<Vec2> xy) {
    if (PolygonArea(xy) < 0) std::reverse(xy.begin(), xy.end());
    l.corners.clear();
    for (const Vec2& p : xy) l.corners.push_back(Corner{.id = l.next_id++, .xy_m = p, .user = true});
    l.corners_edited = true;
  }

  Layout Apply(const nlohmann::json& edit) const {
    if (!edit.is_object()) throw EditError("an edit is a JSON object with \"op\"");
    if (!edit.contains("op") || !edit["op"].is_string()) throw EditError("an edit needs \"op\" (a string)");
    const std::string op = edit["op"];
    Layout l = layout;
    if (op == "add_corner") {
      const Vec2 xy = FloorPoint(edit);
      // "after" / "before": the person says which corner it follows or
      // precedes in the room's order (tracing the outline); else asbuilt decides.
      int index = 0;
      if (edit.contains("after")) {
        index = CornerIndex(l, Integer(edit, "after"), op) + 1;
      } else if (edit.contains("before")) {
        index = CornerIndex(l, Integer(edit, "before"), op);
      } else {
        index = InsertionIndex(l, xy);
      }
      l.corners_edited = true;
      l.corners.insert(l.corners.begin() + index, Corner{.id = l.next_id++, .xy_m = xy, .user = true});
    } else if (op == "move_corner") {
      const int i = CornerIndex(l, Integer(edit, "id"), op);
      const Vec2 xy = edit.contains("xy_m") ? PlanPoint(edit, "xy_m", op) : FloorPoint(edit);
      l.corners_edited = true;
      l.corners[i].xy_m = xy;
      l.corners[i].user = true;
    } else if (op == "set_corners") {  // The whole outline at once (scripts): every corner the person's.
      if (!edit.contains("corners_m") || !edit["corners_m"].is_array() || edit["corners_m"].size() < 3) {
        throw EditError("set_corners: \"corners_m\" must be a list of 3 or more [x, y] floor points, in room order");
      }
      std::vector<Vec2> xy;
      for (std::size_t k = 0; k < edit["corners_m"].size(); ++k) {
        const nlohmann::json point = {{"xy", edit["corners_m"][k]}};
        xy.push_back(PlanPoint(point, "xy", fmt::format("set_corners: corner {}", k)));
      }
      if (PolygonCrossings(xy) > 0)
        throw EditError("set_corners: the corners cross each other: give them in the room's order");
      SetOutline(l, std::move(xy));
    } else if (op == "trace") {  // The outline clicked afresh on the photo, corner by corner.
      if (!edit.contains("points") || !edit["points"].is_array() || edit["points"].size() < 3) {
        throw EditError(
            "trace: \"points\" must be a list of 3 or more floor corners {\"u\", \"v\"}, in the room's order");
      }
      std::vector<Vec2> xy;
      for (std::size_t k = 0; k < edit["points"].size(); ++k) {
        nlohmann::json point = edit["points"][k];
        if (!point.is_object()) throw EditError(fmt::format("trace: point {} must be {{\"u\", \"v\"}}", k));
        point["op"] = fmt::format("trace: point {}", k);
        xy.push_back(FloorPoint(point));
      }
      if (PolygonCrossings(xy) > 0)
        throw EditError("trace: the corners cross each other: click them in the room's order");
      SetOutline(l, std::move(xy));
    } else if (op == "straighten") {  // One wall from corner "from" to corner "to": the corners between go.
      const int n = static_cast<int>(l.corners.size());
      const int from = CornerIndex(l, Integer(edit, "from"), op), to = CornerIndex(l, Integer(edit, "to"), op);
      const int between = (to - from + n) % n - 1;
      if (from == to || between < 1) {
        throw EditError(fmt::format("straighten: no corners between corner {} and corner {} (in the room's order)",
                                    l.corners[from].id, l.corners[to].id));
      }
      if (n - between < 3) throw EditError("straighten: a room needs at least 3 corners");
      std::vector<Corner> kept;
      for (int k = 0; k < n; ++k) {
        if ((k - from + n) % n == 0 || (k - from + n) % n > between) kept.push_back(l.corners[k]);
      }
      l.corners = std::move(kept);
      l.corners_edited = true;
    } else if (op == "delete_corner") {
      const int i = CornerIndex(l, Integer(edit, "id"), op);
      if (l.corners.size() <= 3) throw EditError("delete_corner: a room needs at least 3 corners");
      l.corners_edited = true;
      l.corners.erase(l.corners.begin() + i);
    } else if (op == "ceiling" && edit.contains("height_m")) {  // A number (scripts), not a click.
      const double h = Number(edit, "height_m");
      if (!(h > 0.5 && h < kMaxCeilingM)) throw EditError(fmt::format("ceiling: height_m {} is not a room's", h));
      l.ceiling_m = h;
    } else if (op == "ceiling") {
      const ReviewImage& image = ImageOf(edit);
      const Vec2 pixel = PixelOf(edit, image, "u", "v");
      const std::optional<double> distance = WallDistanceInColumn(image, pixel, l.corners_edited);
      if (!distance) {
        throw EditError(
            fmt::format("ceiling: ({:.1f}, {:.1f}) does not look at a wall of the plan", pixel.x(), pixel.y()));
      }
      const double h = HeightAtDistance(image, pixel, *distance);
      if (h < image.camera_m.z() + 0.1 || h > kMaxCeilingM) {
        throw EditError(
            fmt::format("ceiling: ({:.1f}, {:.1f}) puts the ceiling at {:.2f} m; a wall–ceiling line is "
                        "above the camera ({:.2f} m) and below {:.0f} m",
                        pixel.x(), pixel.y(), h, image.camera_m.z(), kMaxCeilingM));
      }
      l.ceiling_m = h;
    } else if (op == "add_opening" || op == "move_opening" || op == "delete_opening") {
      // The openings become the person's list. Until now FollowFit kept them
      // the fit's own under the ids the state shows, so an edit names a
      // survey opening by the id the person saw.
      l.openings_edited = true;
      if (op == "add_opening") {
        l.openings.push_back(OpeningFrom(edit, l.next_id++));
      } else if (op == "move_opening") {
        const int i = OpeningIndex(l, Integer(edit, "id"), op);
        l.openings[i] = OpeningFrom(edit, l.openings[i].id);
      } else {
        const int i = OpeningIndex(l, Integer(edit, "id"), op);
        l.openings.erase(l.openings.begin() + i);
      }
    } else {
      throw EditError(fmt::format(
          "unknown op \"{}\" (add_corner, move_corner, set_corners, trace, delete_corner, straighten, ceiling, "
          "add_opening, "
          "move_opening, delete_opening, undo, redo)",
          op));
    }
    return l;
  }

  // The plan under `l`; throws EditError when its corners cross each other
  // where the current ones do not, or when it cannot be fitted.
  PlanResult FitUnder(const Layout& l, bool new_edit) const {
    if (new_edit && l.corners_edited && PolygonCrossings(CornerPoints(l)) > PolygonCrossings(CornerPoints(layout))) {
      throw EditError("the room would cross itself: put the corner where it follows its neighbours along the walls");
    }
    PlanResult r;
    try {
      r = fitter->Fit(ConstraintsOf(l));
    } catch (const InvalidArgument& e) {
      throw EditError(e.what());
    } catch (const Error& e) {
      throw EditError(fmt::format("no plan under this edit: {}", e.what()));
    }
    if (r.plan.rooms.empty()) throw EditError("no room under this edit");
    return r;
  }

  // The fit's own corners and openings where the person has not edited them.
  void FollowFit(Layout& l) const {
    if (!l.corners_edited) {
      static const std::vector<Vec2> kNone;
      const std::vector<Vec2>& polygon = fit.plan.rooms.empty() ? kNone : fit.plan.rooms.front().polygon;
      if (l.corners.size() != polygon.size()) {
        l.corners.clear();
        for (const Vec2& p : polygon) l.corners.push_back({.id = l.next_id++, .xy_m = p});
      } else {
        for (std::size_t i = 0; i < polygon.size(); ++i) l.corners[i].xy_m = polygon[i];
      }
    }
    if (!l.openings_edited) {
      l.openings.clear();
      for (const PlanOpening& o : fit.plan.openings) {
        l.openings.push_back({.id = l.next_id++,
                              .kind = o.kind,
                              .start_m = o.start,
                              .end_m = o.end,
                              .bottom_m = o.sill.value_or(0.0),
                              .top_m = o.sill.value_or(0.0) + o.height.value_or(2.0)});
      }
    }
  }

  void Refit(const Layout& l, bool new_edit = false) {
    const auto t = Clock::now();
    PlanResult r = FitUnder(l, new_edit);
    fit_seconds = std::chrono::duration<double>(Clock::now() - t).count();
    fit = std::move(r);
    layout = l;
    FollowFit(layout);
  }

  // The verdict on the current plan (plan/verdict.h); a wall between two
  // corners the person set is theirs, and good.
  PlanVerdict Judge() const {
    VerdictContext context;
    if (layout.corners_edited) {
      auto by_user = [&](const Vec2& p) {
        return std::any_of(layout.corners.begin(), layout.corners.end(),
                           [&](const Corner& c) { return c.user && (c.xy_m - p).norm() < 0.01; });
      };
      for (const PlanWall& w : fit.plan.walls) context.confirmed_walls.push_back(by_user(w.start) && by_user(w.end));
    }
    return JudgePlan(input.plan_input, fit, {}, context);
  }

  double CeilingM() const {
    if (layout.ceiling_m) return *layout.ceiling_m;
    if (std::isfinite(input.plan_input.ceiling_height_m)) return input.plan_input.ceiling_height_m;
    for (const PlanWall& w : fit.plan.walls) {
      if (w.height) return *w.height;
    }
    return 2.5;
  }

  // The floor and ceiling lines of the plan's walls in each image, as polylines of pixels.
  nlohmann::json LinesInImages() const {
    nlohmann::json out = nlohmann::json::array();
    const double ceiling = CeilingM();
    for (std::size_t i = 0; i < input.images.size(); ++i) {
      const ReviewImage& im = input.images[i];
      for (std::size_t w = 0; w < fit.plan.walls.size(); ++w) {
        const PlanWall& wall = fit.plan.walls[w];
        for (const char* kind : {"floor", "ceiling"}) {
          const double z = std::string(kind) == "floor" ? 0.0 : ceiling;
          std::vector<std::vector<std::array<double, 2>>> runs(1);
          std::optional<Vec2> last;
          constexpr int kSamples = 48;
          for (int s = 0; s <= kSamples; ++s) {
            const Vec2 xy = wall.start + (wall.end - wall.start) * (double(s) / kSamples);
            const std::optional<Vec2> px = PixelOfPoint(im, Vec3(xy.x(), xy.y(), z));
            const bool usable =
                px && std::abs(px->x()) < 4.0 * im.width_px + 1 && std::abs(px->y()) < 4.0 * im.height_px + 1;
            if (!usable || (last && im.frame < 0 && std::abs(px->x() - last->x()) > 0.5 * im.width_px)) {
              if (!runs.back().empty()) runs.emplace_back();
            }
            if (usable) runs.back().push_back({px->x(), px->y()});
            last = usable ? px : std::nullopt;
          }
          for (const auto& run : runs) {
            if (run.size() < 2) continue;
            out.push_back({{"image", i}, {"kind", kind}, {"wall", w}, {"points", run}});
          }
        }
      }
    }
    return out;
  }

  nlohmann::json CornerJson(std::size_t i) const {
    const Corner& c = layout.corners[i];
    const Vec2 xy =
        fit.plan.rooms.at(0).polygon.size() == layout.corners.size() ? fit.plan.rooms[0].polygon[i] : c.xy_m;
    const Vec3 p(xy.x(), xy.y(), 0.0);
    const int k = BestImageFor(input.images, p);
    const ReviewImage& im = input.images[k];
    nlohmann::json js = {{"id", c.id}, {"xy_m", Xy(xy)}, {"by", c.user ? "user" : "survey"}, {"image", k}};
    if (const auto px = PixelOfPoint(im, p)) {
      js["u"] = px->x();
      js["v"] = px->y();
    }
    if (im.frame >= 0) js["frame"] = im.frame;
    // Every image that sees it (a stereo or mono capture's frames overlap).
    js["views"] = nlohmann::json::array();
    for (std::size_t j = 0; j < input.images.size(); ++j) {
      const auto px = PixelOfPoint(input.images[j], p);
      if (px && PixelInside(input.images[j], *px))
        js["views"].push_back({{"image", j}, {"u", px->x()}, {"v", px->y()}});
    }
    // How sure the fit is of it: the larger ± of the two walls it joins.
    const int n = static_cast<int>(fit.plan.walls.size());
    if (n == static_cast<int>(layout.corners.size())) {
      const double s = std::max(fit.plan.walls[(i + n - 1) % n].length_sigma_m.value_or(0),
                                fit.plan.walls[i].length_sigma_m.value_or(0));
      js["sigma_m"] = s;
    }
    return js;
  }

  nlohmann::json OpeningJson(std::size_t i) const {
    const Opening& o = layout.openings[i];
    const Vec2 mid = 0.5 * (o.start_m + o.end_m);
    const double z_mid = 0.5 * (o.bottom_m + o.top_m);
    const int k = BestImageFor(input.images, Vec3(mid.x(), mid.y(), z_mid));
    const ReviewImage& im = input.images[k];
    nlohmann::json js = {{"id", o.id},
                         {"kind", OpeningKindName(o.kind)},
                         {"by", o.user ? "user" : "survey"},
                         {"image", k},
                         {"start_m", Xy(o.start_m)},
                         {"end_m", Xy(o.end_m)},
                         {"bottom_m", o.bottom_m},
                         {"top_m", o.top_m}};
    const auto a = PixelOfPoint(im, Vec3(o.start_m.x(), o.start_m.y(), z_mid));
    const auto b = PixelOfPoint(im, Vec3(o.end_m.x(), o.end_m.y(), z_mid));
    const auto top = PixelOfPoint(im, Vec3(mid.x(), mid.y(), o.top_m));
    const auto bottom = PixelOfPoint(im, Vec3(mid.x(), mid.y(), o.bottom_m));
    if (a && b && top && bottom) {
      js["u0"] = a->x();
      js["u1"] = b->x();
      js["v_top"] = top->y();
      js["v_bottom"] = bottom->y();
    }
    if (im.frame >= 0) js["frame"] = im.frame;
    // The wall it lies on in the plan.
    for (const PlanOpening& p : fit.plan.openings) {
      if ((p.Centre() - mid).norm() < 0.05 + 0.5 * (o.end_m - o.start_m).norm()) {
        js["wall"] = p.wall;
        break;
      }
    }
    if (!js.contains("wall")) js["wall"] = nullptr;
    return js;
  }

  nlohmann::json StateJson() const {
    nlohmann::json js;
    js["kind"] = input.kind;
    const PlanVerdict verdict = Judge();
    Plan marked = fit.plan;
    MarkPlan(verdict, marked);
    js["plan"] = PlanToJson(marked);
    js["corners"] = nlohmann::json::array();
    for (std::size_t i = 0; i < layout.corners.size(); ++i) js["corners"].push_back(CornerJson(i));
    js["openings"] = nlohmann::json::array();
    for (std::size_t i = 0; i < layout.openings.size(); ++i) js["openings"].push_back(OpeningJson(i));
    js["ceiling_height_m"] = CeilingM();
    js["ceiling_by"] = layout.ceiling_m ? "user" : "survey";
    js["edits"] = log.size();
    js["can_undo"] = !undo.empty();
    js["can_redo"] = !redo.empty();
    js["refit_ms"] = 1000.0 * fit_seconds;
    js["summary"] = fit.summary.BriefReport();
    js["images"] = nlohmann::json::array();
    for (std::size_t i = 0; i < input.images.size(); ++i) {
      const ReviewImage& im = input.images[i];
      nlohmann::json image = {{"index", i}, {"width", im.width_px}, {"height", im.height_px}, {"yaw_deg", im.yaw_deg}};
      if (im.frame >= 0) image["frame"] = im.frame;
      js["images"].push_back(image);
    }
    js["lines"] = LinesInImages();
    js["verdict"] = {
        {"verdict", VerdictName(verdict.verdict)}, {"confidence", verdict.confidence}, {"reasons", verdict.reasons}};
    js["walls"] = nlohmann::json::array();
    for (std::size_t w = 0; w < marked.walls.size(); ++w) {
      const PlanWall& wall = marked.walls[w];
      nlohmann::json wj = {{"index", w},
                           {"length_m", wall.Length()},
                           {"inferred", w < fit.summary.wall_inferred.size() && fit.summary.wall_inferred[w]}};
      if (w < verdict.walls.size()) {
        wj["verdict"] = VerdictName(verdict.walls[w].verdict);
        wj["confidence"] = verdict.walls[w].confidence;
        wj["reasons"] = verdict.walls[w].reasons;
      }
      wj["sigma_m"] = wall.length_sigma_m ? nlohmann::json(*wall.length_sigma_m) : nlohmann::json();
      js["walls"].push_back(wj);
    }
    js["notes"] = survey_summary.value("notes", nlohmann::json::array());
    if (!no_walls_note.empty() && layout.corners.empty()) js["notes"].insert(js["notes"].begin(), no_walls_note);
    js["wall_cues"] = survey_summary.value("wall_cues", nlohmann::json::array());
    try {
      js["svg"] = marked.walls.empty() ? std::string() : PlanToSvg(marked);
    } catch (const Error& e) {
      js["svg"] = "";
    }
    return js;
  }

  // The corrected layout in image coordinates, for corrections.json.
  nlohmann::json LayoutInImages() const {
    nlohmann::json js = StateJson();
    return {{"corners", js["corners"]},
            {"openings", js["openings"]},
            {"ceiling_height_m", js["ceiling_height_m"]},
            {"lines", js["lines"]}};
  }
};

ReviewSession::ReviewSession() : impl_(std::make_unique<Impl>()) {}
ReviewSession::~ReviewSession() = default;
ReviewSession::ReviewSession(ReviewSession&&) noexcept = default;
ReviewSession& ReviewSession::operator=(ReviewSession&&) noexcept = default;

const fs::path& ReviewSession::out_dir() const { return impl_->out_dir; }
double ReviewSession::last_fit_seconds() const { return impl_->fit_seconds; }
// The page (review/page.html), compiled in by CMake (cmake/embed_text.cmake).
extern const char kReviewPageHtml[];
const char* ReviewSession::PageHtml() const { return kReviewPageHtml; }

std::vector<fs::path> ReviewSession::ImagePaths() const {
  std::vector<fs::path> out;
  for (const ReviewImage& im : impl_->input.images) out.push_back(im.image);
  return out;
}

namespace {

constexpr char kJournal[] = "save-journal.json";
constexpr char kStaging[] = ".save";

// Finishes a save whose journal was written (moves what is left of its
// files into place), or drops one whose journal was not (the old outputs stay).
void RecoverSave(const fs::path& out_dir) {
  const fs::path review = out_dir / "review";
  const fs::path journal = review / kJournal;
  std::error_code ec;
  if (fs::exists(journal, ec)) {
    JsonDiagnostics diag(journal.string());
    const nlohmann::json js = ParseJsonFile(journal, diag);
    diag.ThrowIfErrors();
    for (const nlohmann::json& f : js.at("files")) {
      const fs::path from = review / kStaging / f.get<std::string>();
      if (fs::exists(from, ec)) {
        fs::create_directories((out_dir / f.get<std::string>()).parent_path(), ec);
        fs::rename(from, out_dir / f.get<std::string>());
      }
    }
    spdlog::info("review: finished the save interrupted in {}", out_dir.string());
    fs::remove(journal, ec);
  }
  fs::remove_all(review / kStaging, ec);
}

}  // namespace

ReviewSession ReviewSession::Open(const fs::path& out_dir) {
  ReviewSession session;
  Impl& s = *session.impl_;
  s.out_dir = out_dir;
  s.input = ReadReviewInput(out_dir);
  RecoverSave(out_dir);
  std::error_code ec;
  if (fs::is_regular_file(out_dir / "summary.json", ec)) {
    JsonDiagnostics diag((out_dir / "summary.json").string());
    nlohmann::json js = ParseJsonFile(out_dir / "summary.json", diag);
    if (diag.ok() && js.is_object()) s.survey_summary = js;
  }
  const auto t = Clock::now();
  try {
    s.fitter = std::make_unique<PlanFitter>(s.input.plan_input, s.input.plan_options);
    s.fit = s.fitter->Fit();
  } catch (const InvalidArgument& e) {
    throw InputError(s.input.plan_input.source, "", fmt::format("the survey's plan cannot be fitted: {}", e.what()));
  } catch (const Error& e) {
    // The survey found no walls: the person traces the room from nothing.
    s.fit = {};
    s.no_walls_note = fmt::format("the survey found no walls ({}): trace the room's floor corners (t)", e.what());
  }
  s.fit_seconds = std::chrono::duration<double>(Clock::now() - t).count();
  s.FollowFit(s.initial);
  s.layout = s.initial;
  const fs::path state = out_dir / "review" / "state.json";
  if (fs::is_regular_file(state, ec)) {
    JsonDiagnostics diag(state.string());
    const nlohmann::json js = ParseJsonFile(state, diag);
    diag.ThrowIfErrors();
    if (!js.is_object() || !js.contains("layout") || !js.contains("edits") || !js["edits"].is_array()) {
      throw InputError(state.string(), "", "expected {\"layout\": …, \"edits\": […]}");
    }
    const Layout saved = LayoutFromJson(js["layout"], state.string());
    try {
      s.Refit(saved);
    } catch (const EditError& e) {
      throw InputError(state.string(), "layout", fmt::format("the saved review cannot be re-fitted: {}", e.what()));
    }
    s.log = js["edits"];
    if (js.contains("initial")) s.initial = LayoutFromJson(js["initial"], state.string());
  }
  return session;
}

nlohmann::json ReviewSession::State() const { return impl_->StateJson(); }

nlohmann::json ReviewSession::Edit(const nlohmann::json& edit) {
  Impl& s = *impl_;
  const std::string op = edit.is_object() && edit.contains("op") && edit["op"].is_string() ? edit["op"] : "";
  const Layout before = s.layout;
  if (op == "undo" || op == "redo") {
    std::vector<Layout>& from = op == "undo" ? s.undo : s.redo;
    std::vector<Layout>& to = op == "undo" ? s.redo : s.undo;
    if (from.empty()) throw EditError(fmt::format("{}: nothing to {}", op, op));
    s.Refit(from.back());
    from.pop_back();
    to.push_back(before);
  } else {
    s.Refit(s.Apply(edit), /*new_edit=*/true);
    s.undo.push_back(before);
    s.redo.clear();
  }
  s.log.push_back({{"edit", edit},
                   {"before", LayoutJson(before)},
                   {"after", LayoutJson(s.layout)},
                   {"refit_ms", 1000.0 * s.fit_seconds},
                   {"area_m2", s.fit.plan.rooms.empty() ? 0.0 : s.fit.plan.rooms[0].area_m2}});
  return s.StateJson();
}

TrainingExample ReviewSession::ExportTraining() const {
  const Impl& s = *impl_;
  const fs::path corrections = s.out_dir / "review" / "corrections.json";
  if (!fs::exists(corrections)) {
    throw InputError(s.out_dir.string(), "",
                     "has no review/corrections.json: no review was saved here (open it with `asbuilt review` and "
                     "save first)");
  }
  Plan plan = s.fit.plan;
  MarkPlan(s.Judge(), plan);
  return WriteTrainingExample(s.input, plan, s.CeilingM(), s.out_dir / "review" / "training");
}

std::vector<std::string> ReviewSession::Save(const ReviewSaveOptions& options) {
  Impl& s = *impl_;
  const fs::path review = s.out_dir / "review";
  const fs::path staging = review / kStaging;
  std::error_code ec;
  fs::remove_all(staging, ec);
  fs::create_directories(staging / "review");

  // 1. Every output, staged, marked with the verdict the page shows.
  const PlanVerdict verdict = s.Judge();
  Plan plan = s.fit.plan;
  MarkPlan(verdict, plan);
  if (plan.walls.empty()) {
    WritePlan(plan, staging / "plan.json");
  } else {
    WritePlanFiles(plan, staging);
  }
  SurveySummary summary;
  summary.capture_kind = s.input.kind;
  summary.labels_source = s.input.labels_source;
  summary.plan = s.fit.summary;
  summary.verdict = verdict;
  summary.ceiling_height_m = s.CeilingM();
  summary.ceiling_height_sigma_m = s.layout.ceiling_m ? 0.0 : s.input.plan_input.ceiling_height_sigma_m;
  summary.frames = static_cast<int>(s.input.plan_input.frames.size());
  summary.points = static_cast<int>(s.input.plan_input.points.size());
  summary.notes.push_back(
      fmt::format("corrected by a person in asbuilt review: {} edit(s), review/corrections.json", s.log.size()));
  for (const nlohmann::json& n : s.survey_summary.value("notes", nlohmann::json::array())) {
    if (n.is_string()) summary.notes.push_back("survey: " + n.get<std::string>());
  }
  WriteSurveyReport({.title = fmt::format("Survey of {} (reviewed)", s.input.capture_json.filename().string()),
                     .capture_path = s.input.capture_json,
                     .summary = summary,
                     .plan = plan,
                     .plan_svg = plan.walls.empty() ? std::string() : PlanToSvg(plan)},
                    staging / "report.html");
  const nlohmann::json corrections = {{"version", 1},
                                      {"kind", s.input.kind},
                                      {"capture", s.input.capture_json.string()},
                                      {"images", s.StateJson()["images"]},
                                      {"initial", LayoutJson(s.initial)},
                                      {"edits", s.log},
                                      {"final", LayoutJson(s.layout)},
                                      {"layout_in_images", s.LayoutInImages()},
                                      {"plan", PlanToJson(plan)}};
  WriteFileAtomic(staging / "review" / "corrections.json", corrections.dump(1) + "\n");
  // The corrected survey as a labelled real example (review/training_example.h).
  if (!plan.walls.empty()) WriteTrainingExample(s.input, plan, s.CeilingM(), staging / "review" / "training");
  WriteFileAtomic(
      staging / "review" / "state.json",
      nlohmann::json({{"layout", LayoutJson(s.layout)}, {"initial", LayoutJson(s.initial)}, {"edits", s.log}}).dump(1) +
          "\n");
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(staging)) {
    if (entry.is_regular_file() && !IsAtomicTempName(entry.path())) {
      files.push_back(entry.path().lexically_relative(staging).string());
    }
  }
  std::sort(files.begin(), files.end());
  if (options.stop_before_commit) throw Error("review save stopped before its commit (test)");

  // 2. The commit: the journal names the files; from here on the save is done.
  WriteFileAtomic(review / kJournal, nlohmann::json({{"files", files}}).dump(1) + "\n");

  // 3. Into place.
  int moved = 0;
  for (const std::string& f : files) {
    if (moved == options.stop_after_files) throw Error("review save stopped while moving its files (test)");
    fs::create_directories((s.out_dir / f).parent_path());
    fs::rename(staging / f, s.out_dir / f);
    ++moved;
  }
  fs::remove(review / kJournal);
  fs::remove_all(staging, ec);
  return files;
}

}  // namespace asbuilt
