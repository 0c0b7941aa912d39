#include "asbuilt/review/review_session.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/dataset/manifest.h"
#include "asbuilt/formats/plan_file.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/pipeline/review_input.h"
#include "asbuilt/plan/fit_plan.h"
#include "asbuilt/plan/room_iou.h"
#include "asbuilt/review/review_test_fixtures.h"
#include "asbuilt/review/training_example.h"
#include "asbuilt/review/view_geometry.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;
using namespace review_test;

Plan BoxTruth() {
  Plan p;
  const std::vector<Vec2> c = {{kX0, kY0}, {kX1, kY0}, {kX1, kY1}, {kX0, kY1}};
  for (int i = 0; i < 4; ++i) p.walls.push_back({.start = c[i], .end = c[(i + 1) % 4], .height = kCeiling});
  p.rooms.push_back({.polygon = c, .area_m2 = 12.0});
  return p;
}

Plan PlanOf(const nlohmann::json& state) { return PlanFromJson(state["plan"], "state.plan"); }

// The id of the state's corner nearest xy.
int CornerNear(const nlohmann::json& state, const Vec2& xy) {
  int id = -1;
  double best = INFINITY;
  for (const nlohmann::json& c : state["corners"]) {
    const double d = (Vec2(c["xy_m"][0], c["xy_m"][1]) - xy).norm();
    if (d < best) best = d, id = c["id"];
  }
  return id;
}

// The largest distance from a truth corner to the nearest plan corner.
double WorstCornerError(const Plan& plan, const std::vector<Vec2>& truth) {
  double worst = 0;
  for (const Vec2& t : truth) {
    double best = INFINITY;
    for (const Vec2& p : plan.rooms.at(0).polygon) best = std::min(best, (p - t).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

nlohmann::json Click(const char* op, const Vec2& pixel) { return {{"op", op}, {"u", pixel.x()}, {"v", pixel.y()}}; }

TEST(ReviewSession, StartsFromTheSurveysPlan) {
  const fs::path out = PanoramaSurvey("starts");
  ReviewSession session = ReviewSession::Open(out);
  const nlohmann::json state = session.State();
  EXPECT_EQ(state["kind"], "panorama");
  EXPECT_EQ(state["corners"].size(), 4u);
  EXPECT_EQ(state["edits"], 0);
  EXPECT_NEAR(state["ceiling_height_m"].get<double>(), kCeiling, 0.03);
  // The review re-fits the survey's own points with the survey's settings: the same plan.
  EXPECT_EQ(state["plan"].dump(), PlanToJson(ReadPlan(out / "plan.json")).dump());
  for (const nlohmann::json& c : state["corners"]) {
    EXPECT_EQ(c["by"], "survey");
    const Vec2 px = PanoPixel(Vec3(c["xy_m"][0], c["xy_m"][1], 0.0));
    EXPECT_NEAR(c["u"].get<double>(), px.x(), 1e-6);
    EXPECT_NEAR(c["v"].get<double>(), px.y(), 1e-6);
  }
  ASSERT_EQ(state["openings"].size(), 1u);
  EXPECT_EQ(state["openings"][0]["kind"], "door");
  // The survey kept each view's labels, and each floor contact projects back
  // onto its view's wall/floor label edge.
  const ReviewInput input = ReadReviewInput(out);
  ASSERT_EQ(input.labels.size(), 12u);
  int checked = 0;
  for (const ClassPoint& p : input.plan_input.points) {
    if (p.source != PointSource::kContact || p.position_m.z() > 0.01 || p.label != LabelClass::kWall) continue;
    const ReviewImage& view = input.labels.at(p.frame);
    const cv::Mat labels = cv::imread(view.image.string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(labels.cols, view.width_px);
    const std::optional<Vec2> px = PixelOfPoint(view, p.position_m);
    ASSERT_TRUE(px);
    const int u = static_cast<int>(std::lround(px->x())), v = static_cast<int>(std::lround(px->y()));
    if (u < 0 || u >= labels.cols || v < 2 || v + 2 >= labels.rows) continue;
    EXPECT_EQ(labels.at<unsigned char>(v - 2, u), 1) << "above a floor contact: wall";
    EXPECT_EQ(labels.at<unsigned char>(v + 2, u), 0) << "below a floor contact: floor";
    if (++checked == 50) break;
  }
  EXPECT_EQ(checked, 50);
  EXPECT_FALSE(state["lines"].empty());
  EXPECT_NE(state["svg"].get<std::string>().find("<svg"), std::string::npos);
}

TEST(ReviewSession, RefusesAFolderThatIsNotASurvey) {
  const fs::path dir = fs::temp_directory_path() / "asbuilt_review_not_a_survey";
  fs::remove_all(dir);
  fs::create_directories(dir);
  try {
    ReviewSession::Open(dir);
    FAIL() << "opened a folder with no survey";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a folder written by `asbuilt survey`"), std::string::npos) << e.what();
  }
  // A survey whose kept points were cut short: one message naming the file.
  const fs::path out = PanoramaSurvey("truncated");
  const std::string bytes = ReadFile(out / "review/points.bin");
  WriteFileAtomic(out / "review/points.bin", bytes.substr(0, bytes.size() - 5));
  try {
    ReviewSession::Open(out);
    FAIL() << "opened a survey with truncated points";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("points.bin"), std::string::npos) << e.what();
  }
}

// One click on the true corner re-places it and re-fits both walls beside it
// from the floor and ceiling edges of their columns: they come out along the
// room's axes (not along the line to the clicked point's neighbours), and
// the neighbouring corners move onto the true walls.
TEST(ReviewSession, AClickedCornerRefitsItsWallsFromTheImage) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("refit"));
  nlohmann::json state = session.State();
  const int ne = CornerNear(state, {kX1, kY1});
  // First a wrong drag in the plan: the NE corner 0.6 m out; its walls follow it.
  state = session.Edit({{"op", "move_corner"}, {"id", ne}, {"xy_m", {kX1 + 0.6, kY1 + 0.5}}});
  const Plan wrong = PlanOf(state);
  EXPECT_GT(WorstCornerError(wrong, BoxTruth().rooms[0].polygon), 0.4);
  // Then a click on the photo, 1.5 px off the true corner.
  const Vec2 px = PanoPixel(Vec3(kX1, kY1, 0.0)) + Vec2(1.5, -1.0);
  nlohmann::json edit = Click("move_corner", px);
  edit["id"] = ne;
  state = session.Edit(edit);
  const Plan fixed = PlanOf(state);
  ASSERT_EQ(fixed.walls.size(), 4u);
  EXPECT_LE(WorstCornerError(fixed, BoxTruth().rooms[0].polygon), 0.05);
  EXPECT_GE(RoomPolygonOverlap(fixed, BoxTruth())->Iou(), 0.97);
  for (const PlanWall& w : fixed.walls) {
    const Vec2 d = w.end - w.start;
    const double off_axis_deg =
        RadToDeg(std::min(std::abs(std::atan2(d.y(), d.x())), std::abs(std::atan2(d.x(), d.y()))));
    EXPECT_LE(std::min(off_axis_deg, std::abs(90 - off_axis_deg)), 1.0) << "wall off the room's axes";
  }
  int by_user = 0;
  for (const nlohmann::json& c : state["corners"]) by_user += c["by"] == "user";
  EXPECT_EQ(by_user, 1);
  EXPECT_EQ(state["edits"], 2);
  fmt::print("re-fit after a corner click: {:.2f} ms\n", state["refit_ms"].get<double>());
}

TEST(ReviewSession, ACornerAddedOnAStraightWallKeepsItStraight) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("add"));
  const double area = PlanOf(session.State()).rooms[0].area_m2;
  const nlohmann::json state = session.Edit(Click("add_corner", PanoPixel(Vec3(1.0, kY0, 0.0)) + Vec2(0.7, 0.7)));
  const Plan plan = PlanOf(state);
  EXPECT_EQ(state["corners"].size(), 5u);
  EXPECT_NEAR(plan.rooms[0].area_m2, area, 0.02 * area);
  // The two walls meeting at the new corner: both along the south wall.
  int along = 0;
  for (const PlanWall& w : plan.walls) {
    const Vec2 d = (w.end - w.start).normalized();
    if (std::abs(w.start.y() - kY0) < 0.05 && std::abs(w.end.y() - kY0) < 0.05 && std::abs(d.y()) < 0.01) ++along;
  }
  EXPECT_EQ(along, 2);
}

// An L-shaped room seen from one wing: the corner of the far wing hides
// behind the wall y = 1.5. Clicked where it would be seen through that wall,
// it goes into the outline between its true neighbours.
TEST(ReviewSession, AHiddenCornerClickedThroughAWallGoesWhereItBelongs) {
  ReviewSession session = ReviewSession::Open(LRoomSurvey("hidden"));
  const std::vector<Vec2> truth = LRoomCorners();
  nlohmann::json state = session.State();
  // First the far wing's visible corner, then the hidden one.
  for (const Vec2& c : {truth[2], truth[3]}) {
    if (WorstCornerError(PlanOf(state), {c}) < 0.05) continue;
    state = session.Edit(Click("add_corner", LRoomPanoPixel(Vec3(c.x(), c.y(), 0.0))));
  }
  const Plan plan = PlanOf(state);
  const std::vector<Vec2>& polygon = plan.rooms[0].polygon;
  const auto at =
      std::find_if(polygon.begin(), polygon.end(), [&](const Vec2& p) { return (p - truth[3]).norm() < 0.05; });
  ASSERT_NE(at, polygon.end()) << state["corners"].dump();
  // Its neighbours in the outline: toward (2, 3.5) on one side, toward (0.5, 1.5) on the other.
  const std::size_t i = at - polygon.begin(), n = polygon.size();
  const Vec2 before = polygon[(i + n - 1) % n], after = polygon[(i + 1) % n];
  EXPECT_GT(before.x(), 1.0) << "previous corner " << before.transpose();
  EXPECT_LT(after.y(), 3.0) << "next corner " << after.transpose();
  EXPECT_EQ(PolygonCrossings(polygon), 0);
  // Then the reflex corner where the wings meet, and the survey's corner
  // that closed the room across the wing's opening goes: the L, whole.
  state = session.Edit(Click("add_corner", LRoomPanoPixel(Vec3(truth[4].x(), truth[4].y(), 0.0))));
  state = session.Edit({{"op", "delete_corner"}, {"id", CornerNear(state, {2.0, 1.5})}});
  Plan truth_plan;
  truth_plan.rooms.push_back({.polygon = truth, .area_m2 = 13.0});
  EXPECT_EQ(state["corners"].size(), 6u);
  EXPECT_LE(WorstCornerError(PlanOf(state), truth), 0.05);
  EXPECT_GE(RoomPolygonOverlap(PlanOf(state), truth_plan)->Iou(), 0.98);
}

// Two corners put on the south wall, then "straighten" from its west end
// to its east end: one wall again, re-fitted from the photo.
TEST(ReviewSession, StraightenMakesOneWallOfTheCornersBetween) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("straighten"));
  const nlohmann::json start = session.State();
  const int sw = CornerNear(start, {kX0, kY0}), se = CornerNear(start, {kX1, kY0});
  nlohmann::json state = session.Edit(Click("add_corner", PanoPixel(Vec3(-0.5, kY0, 0.0))));
  // Traced: the second one follows the first.
  const int first = CornerNear(state, {-0.5, kY0});
  state = session.Edit({{"op", "add_corner"},
                        {"after", first},
                        {"u", PanoPixel(Vec3(0.8, kY0, 0.0)).x()},
                        {"v", PanoPixel(Vec3(0.8, kY0, 0.0)).y()}});
  ASSERT_EQ(state["corners"].size(), 6u);
  std::vector<int> ids;
  for (const nlohmann::json& c : state["corners"]) ids.push_back(c["id"]);
  const auto at = std::find(ids.begin(), ids.end(), first);
  ASSERT_NE(at, ids.end());
  const nlohmann::json& next = state["corners"][(at - ids.begin() + 1) % 6];
  EXPECT_NEAR(next["xy_m"][0].get<double>(), 0.8, 0.05) << state["corners"].dump();
  state = session.Edit({{"op", "straighten"}, {"from", sw}, {"to", se}});
  EXPECT_EQ(state["corners"].size(), 4u);
  EXPECT_LE(WorstCornerError(PlanOf(state), {{kX0, kY0}, {kX1, kY0}, {kX1, kY1}, {kX0, kY1}}), 0.05);
  // Nothing between two neighbours; a room of fewer than 3 corners; an unknown corner.
  const int ne = CornerNear(state, {kX1, kY1});
  for (const nlohmann::json& bad : {nlohmann::json{{"op", "straighten"}, {"from", sw}, {"to", se}},
                                    nlohmann::json{{"op", "straighten"}, {"from", se}, {"to", sw}},
                                    nlohmann::json{{"op", "straighten"}, {"from", ne}, {"to", 999}}}) {
    EXPECT_THROW(session.Edit(bad), EditError) << bad.dump();
  }
  EXPECT_EQ(session.State()["corners"].size(), 4u);
  state = session.Edit({{"op", "undo"}});
  EXPECT_EQ(state["corners"].size(), 6u);
}

// A far-off outline clicked afresh: the corners in either turn, the room on the left.
TEST(ReviewSession, TraceReplacesTheOutlineWithTheClickedCorners) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("trace"));
  session.Edit({{"op", "move_corner"}, {"id", CornerNear(session.State(), {kX1, kY1})}, {"xy_m", {3.5, 2.8}}});
  const std::vector<Vec2> truth = {{kX0, kY0}, {kX1, kY0}, {kX1, kY1}, {kX0, kY1}};
  nlohmann::json points = nlohmann::json::array();
  for (auto it = truth.rbegin(); it != truth.rend(); ++it) {  // Clockwise.
    const Vec2 px = PanoPixel(Vec3(it->x(), it->y(), 0.0));
    points.push_back({{"u", px.x()}, {"v", px.y()}});
  }
  const nlohmann::json state = session.Edit({{"op", "trace"}, {"points", points}});
  ASSERT_EQ(state["corners"].size(), 4u);
  for (const nlohmann::json& c : state["corners"]) EXPECT_EQ(c["by"], "user");
  EXPECT_LE(WorstCornerError(PlanOf(state), truth), 0.02);
  EXPECT_NEAR(PlanOf(state).rooms[0].area_m2, 12.0, 0.1);
  // Refused: two points, corners out of order, a point above the horizon.
  const nlohmann::json crossed = {points[0], points[2], points[1], points[3]};
  nlohmann::json high = points;
  high[1]["v"] = 100;
  for (const auto& [bad, message] : std::vector<std::pair<nlohmann::json, std::string>>{
           {{{"op", "trace"}, {"points", {points[0], points[1]}}}, "3 or more"},
           {{{"op", "trace"}, {"points", crossed}}, "cross each other"},
           {{{"op", "trace"}, {"points", high}}, "trace: point 1"}}) {
    try {
      session.Edit(bad);
      ADD_FAILURE() << "accepted " << bad.dump();
    } catch (const EditError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(session.State()["edits"], 2);
}

// The clicks of a trace of the box room's corners, scaled about the camera.
nlohmann::json BoxTracePoints(double scale) {
  nlohmann::json points = nlohmann::json::array();
  const Plan truth = BoxTruth();
  for (const Vec2& c : truth.rooms[0].polygon) {
    const Vec2 xy = kCamera.head<2>() + scale * (c - kCamera.head<2>());
    const Vec2 px = PanoPixel(Vec3(xy.x(), xy.y(), 0.0));
    points.push_back({{"u", px.x()}, {"v", px.y()}});
  }
  return points;
}

TEST(ReviewSession, ASurveyThatFoundNoWallsOpensAndIsTraced) {
  const fs::path out = PanoramaSurvey("no_walls");
  ReviewInput input = ReadReviewInput(out);
  std::erase_if(input.plan_input.points, [](const ClassPoint& p) { return p.label == LabelClass::kWall; });
  WriteReviewInput(out, input);
  ReviewSession session = ReviewSession::Open(out);
  nlohmann::json state = session.State();
  EXPECT_TRUE(state["corners"].empty());
  ASSERT_FALSE(state["notes"].empty());
  EXPECT_NE(state["notes"][0].get<std::string>().find("the survey found no walls"), std::string::npos);
  state = session.Edit({{"op", "trace"}, {"points", BoxTracePoints(1.0)}});
  EXPECT_GE(RoomPolygonOverlap(PlanOf(state), BoxTruth())->Iou(), 0.99);
  state = session.Edit(Click("ceiling", PanoPixel(Vec3(kX1, 0.3, kCeiling))));
  EXPECT_NEAR(state["ceiling_height_m"].get<double>(), kCeiling, 0.02);
  EXPECT_FALSE(session.Save().empty());
  EXPECT_TRUE(fs::is_regular_file(out / "review" / "training" / "manifest.json"));
}

TEST(ReviewSession, ACeilingClickAfterATraceReadsThePersonsWallsNotTheContacts) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("trace_ceiling"));
  // The person says every wall stands 20 % farther than the labels put it.
  session.Edit({{"op", "trace"}, {"points", BoxTracePoints(1.2)}});
  const double east_x = kCamera.x() + 1.2 * (kX1 - kCamera.x());
  const nlohmann::json state = session.Edit(Click("ceiling", PanoPixel(Vec3(east_x, 0.3, 2.8))));
  EXPECT_NEAR(state["ceiling_height_m"].get<double>(), 2.8, 0.02);
}

// The survey's own openings are addressed by the ids the state shows, also
// after a corner edit re-fitted them.
TEST(ReviewSession, ASurveyOpeningIsEditedByTheIdTheStateShows) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("survey_opening"));
  nlohmann::json state = session.Edit(
      {{"op", "move_corner"}, {"id", CornerNear(session.State(), {kX1, kY1})}, {"xy_m", {kX1 + 0.02, kY1 + 0.02}}});
  ASSERT_GE(state["openings"].size(), 1u) << "the box room's door";
  const std::size_t n = state["openings"].size();
  const int id = state["openings"][0]["id"];
  state = session.Edit({{"op", "delete_opening"}, {"id", id}});
  EXPECT_EQ(state["openings"].size(), n - 1);
  for (const nlohmann::json& o : state["openings"]) EXPECT_NE(o["id"], id);
}

// A whole outline in metres, given clockwise, is the same room as counter-clockwise.
TEST(ReviewSession, SetCornersTakesEitherTurn) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("set_turn"));
  const nlohmann::json ccw = {{kX0, kY0}, {kX1, kY0}, {kX1, kY1}, {kX0, kY1}};
  const nlohmann::json cw = {{kX0, kY1}, {kX1, kY1}, {kX1, kY0}, {kX0, kY0}};
  const double area = PlanOf(session.Edit({{"op", "set_corners"}, {"corners_m", ccw}})).rooms[0].area_m2;
  const Plan plan = PlanOf(session.Edit({{"op", "set_corners"}, {"corners_m", cw}}));
  EXPECT_NEAR(plan.rooms[0].area_m2, area, 1e-9);
  EXPECT_GT(PolygonArea(plan.rooms[0].polygon), 0);
}

TEST(ReviewSession, DeleteUndoRedo) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("undo"));
  const nlohmann::json start = session.State();
  const int ne = CornerNear(start, {kX1, kY1});
  nlohmann::json state = session.Edit({{"op", "delete_corner"}, {"id", ne}});
  EXPECT_EQ(state["corners"].size(), 3u);
  EXPECT_TRUE(state["can_undo"].get<bool>());
  state = session.Edit({{"op", "undo"}});
  EXPECT_EQ(state["corners"].size(), 4u);
  EXPECT_EQ(state["plan"].dump(), start["plan"].dump());
  EXPECT_TRUE(state["can_redo"].get<bool>());
  state = session.Edit({{"op", "redo"}});
  EXPECT_EQ(state["corners"].size(), 3u);
  EXPECT_EQ(state["edits"], 3);
  state = session.Edit({{"op", "undo"}});
  EXPECT_EQ(state["plan"].dump(), start["plan"].dump());
  EXPECT_THROW(session.Edit({{"op", "undo"}}), EditError);  // Back past the start.
}

TEST(ReviewSession, UndoPastTheStartIsRefused) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("undo_start"));
  EXPECT_THROW(session.Edit({{"op", "undo"}}), EditError);
  EXPECT_THROW(session.Edit({{"op", "redo"}}), EditError);
}

TEST(ReviewSession, ACeilingClickSetsTheCeilingAndMovesItsContacts) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("ceiling"));
  // A point on the east wall's ceiling line as it would be at 2.8 m.
  nlohmann::json state = session.Edit(Click("ceiling", PanoPixel(Vec3(kX1, 0.3, 2.8))));
  EXPECT_NEAR(state["ceiling_height_m"].get<double>(), 2.8, 0.03);
  EXPECT_EQ(state["ceiling_by"], "user");
  const Plan plan = PlanOf(state);
  for (const PlanWall& w : plan.walls) EXPECT_NEAR(w.height.value_or(0), 2.8, 0.03);
  // Back on the true line: the room as before.
  state = session.Edit(Click("ceiling", PanoPixel(Vec3(kX1, 0.3, kCeiling))));
  EXPECT_NEAR(state["ceiling_height_m"].get<double>(), kCeiling, 0.03);
  EXPECT_GE(RoomPolygonOverlap(PlanOf(state), BoxTruth())->Iou(), 0.97);
}

TEST(ReviewSession, OpeningsAreAddedMovedAndDeleted) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("openings"));
  // A window on the south wall from x = −1.0 to 0.0, sill 0.9 m, head 2.0 m.
  // Head and sill are read in the box's middle column (docs/review.md).
  auto window = [](const char* op, double x0, double x1) {
    const Vec2 a = PanoPixel(Vec3(x0, kY0, 1.45)), b = PanoPixel(Vec3(x1, kY0, 1.45));
    const Vec3 ray = DirectionFromEquirectPixel(Vec2(0.5 * (a.x() + b.x()), 100.0), kPanoWidth, kPanoHeight);
    const double x_mid = kCamera.x() + (kY0 - kCamera.y()) / ray.y() * ray.x();
    const Vec2 top = PanoPixel(Vec3(x_mid, kY0, 2.0)), bottom = PanoPixel(Vec3(x_mid, kY0, 0.9));
    return nlohmann::json{{"op", op},    {"kind", "window"}, {"u0", a.x()},
                          {"u1", b.x()}, {"v_top", top.y()}, {"v_bottom", bottom.y()}};
  };
  nlohmann::json state = session.Edit(window("add_opening", -1.0, 0.0));
  ASSERT_EQ(state["openings"].size(), 2u);  // The survey's door and the new window.
  const Plan plan = PlanOf(state);
  const auto found = std::find_if(plan.openings.begin(), plan.openings.end(),
                                  [](const PlanOpening& o) { return o.kind == OpeningKind::kWindow; });
  ASSERT_NE(found, plan.openings.end());
  EXPECT_NEAR(found->width, 1.0, 0.03);
  EXPECT_NEAR(found->sill.value_or(0), 0.9, 0.03);
  EXPECT_NEAR(found->height.value_or(0), 1.1, 0.03);
  EXPECT_NEAR(found->Centre().y(), kY0, 0.03);
  int id = -1;
  for (const nlohmann::json& o : state["openings"]) {
    if (o["kind"] == "window") id = o["id"];
  }
  nlohmann::json move = window("move_opening", -1.5, 0.0);
  move["id"] = id;
  state = session.Edit(move);
  for (const PlanOpening& o : PlanOf(state).openings) {
    if (o.kind == OpeningKind::kWindow) {
      EXPECT_NEAR(o.width, 1.5, 0.03);
    }
  }
  state = session.Edit({{"op", "delete_opening"}, {"id", id}});
  EXPECT_EQ(state["openings"].size(), 1u);
  EXPECT_EQ(PlanOf(state).openings.size(), 1u);
}

TEST(ReviewSession, BadEditsAreRefusedAndLeaveTheStateAsItWas) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("bad"));
  const std::string before = session.State().dump();
  const int ne = CornerNear(session.State(), {kX1, kY1});
  const std::vector<std::pair<nlohmann::json, std::string>> bad = {
      {{{"op", "fly"}}, "unknown op \"fly\""},
      {{{"nop", 1}}, "needs \"op\""},
      {{{"op", "move_corner"}, {"id", 999}, {"u", 10}, {"v", 400}}, "no corner with id 999"},
      {{{"op", "add_corner"}, {"v", 400}}, "\"u\" is missing"},
      {{{"op", "add_corner"}, {"u", "abc"}, {"v", 400}}, "\"u\" must be a finite number"},
      {{{"op", "add_corner"}, {"u", 5000}, {"v", 400}}, "outside the 1024×512 image"},
      {{{"op", "add_corner"}, {"u", 100}, {"v", 100}}, "above the horizon"},
      {{{"op", "move_corner"}, {"id", ne}, {"xy_m", {-2.5, 0.0}}}, "cross"},
      {{{"op", "move_corner"}, {"id", ne}, {"xy_m", {1.0}}}, "\"xy_m\" must be [x, y]"},
      {{{"op", "delete_opening"}, {"id", 12345}}, "no opening with id 12345"},
      {{{"op", "add_opening"}, {"kind", "hatch"}}, "\"kind\" must be \"door\" or \"window\""},
      {{{"op", "ceiling"}, {"u", 100}, {"v", 400}}, "ceiling"},
  };
  for (const auto& [edit, message] : bad) {
    try {
      session.Edit(edit);
      ADD_FAILURE() << "accepted " << edit.dump();
    } catch (const EditError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << edit.dump() << " → " << e.what();
    }
    EXPECT_EQ(session.State().dump(), before) << edit.dump();
  }
}

TEST(ReviewSession, SaveWritesThePlanAndTheCorrectionsAndReopensThere) {
  const fs::path out = PanoramaSurvey("save");
  nlohmann::json state;
  {
    ReviewSession session = ReviewSession::Open(out);
    nlohmann::json edit = Click("move_corner", PanoPixel(Vec3(kX1 - 0.3, kY1, 0.0)));
    edit["id"] = CornerNear(session.State(), {kX1, kY1});
    state = session.Edit(edit);
    const std::vector<std::string> files = session.Save();
    for (const char* f : {"plan.json", "plan.svg", "plan.dxf", "plan.pdf", "plan.ifc", "report.html",
                          "review/corrections.json", "review/state.json"}) {
      EXPECT_NE(std::find(files.begin(), files.end(), f), files.end()) << f;
      EXPECT_TRUE(fs::exists(out / f)) << f;
    }
  }
  EXPECT_EQ(PlanToJson(ReadPlan(out / "plan.json")).dump(), state["plan"].dump());
  const nlohmann::json corrections = nlohmann::json::parse(ReadFile(out / "review/corrections.json"));
  ASSERT_EQ(corrections["edits"].size(), 1u);
  EXPECT_EQ(corrections["edits"][0]["edit"]["op"], "move_corner");
  EXPECT_EQ(corrections["edits"][0]["before"]["corners"].size(), 4u);
  EXPECT_EQ(corrections["edits"][0]["after"]["corners"].size(), 4u);
  EXPECT_EQ(corrections["layout_in_images"]["corners"].size(), 4u);
  EXPECT_TRUE(corrections["layout_in_images"]["corners"][0].contains("u"));
  EXPECT_NE(ReadFile(out / "report.html").find("reviewed"), std::string::npos);
  ReviewSession again = ReviewSession::Open(out);
  const nlohmann::json reopened = again.State();
  EXPECT_EQ(reopened["plan"].dump(), state["plan"].dump());
  EXPECT_EQ(reopened["edits"], 1);
  EXPECT_EQ(reopened["corners"].dump(), state["corners"].dump());
}

TEST(ReviewSession, AScriptSetsTheWholeLayoutInMetres) {
  const fs::path out = PanoramaSurvey("set_corners");
  ReviewSession session = ReviewSession::Open(out);
  // A room 0.2 m narrower than the survey's, 2.40 m high, a window on the south wall.
  const nlohmann::json corners = {{kX0, kY0}, {kX1 - 0.2, kY0}, {kX1 - 0.2, kY1}, {kX0, kY1}};
  nlohmann::json state = session.Edit({{"op", "set_corners"}, {"corners_m", corners}});
  state = session.Edit({{"op", "ceiling"}, {"height_m", 2.4}});
  state = session.Edit({{"op", "add_opening"},
                        {"kind", "window"},
                        {"start_m", {-1.0, kY0}},
                        {"end_m", {0.2, kY0}},
                        {"bottom_m", 0.9},
                        {"top_m", 2.1}});
  const Plan plan = PlanFromJson(state["plan"], "state");
  ASSERT_EQ(plan.rooms.size(), 1u);
  EXPECT_NEAR(plan.rooms[0].area_m2, (kX1 - 0.2 - kX0) * (kY1 - kY0), 0.01);
  EXPECT_NEAR(state["ceiling_height_m"].get<double>(), 2.4, 1e-9);
  bool window = false;
  for (const PlanOpening& o : plan.openings) window |= o.kind == OpeningKind::kWindow && std::abs(o.width - 1.2) < 0.01;
  EXPECT_TRUE(window) << state["plan"].dump();
  for (const nlohmann::json& w : state["walls"]) {  // Each between two corners the script set: theirs.
    EXPECT_EQ(w["verdict"], "good") << w.dump();
  }
  // Corners that cross, or too few, are refused and change nothing.
  const nlohmann::json crossing = {{kX0, kY0}, {kX1, kY1}, {kX1, kY0}, {kX0, kY1}};
  EXPECT_THROW(session.Edit({{"op", "set_corners"}, {"corners_m", crossing}}), EditError);
  EXPECT_THROW(session.Edit({{"op", "set_corners"}, {"corners_m", {{0, 0}, {1, 0}}}}), EditError);
  EXPECT_THROW(session.Edit({{"op", "ceiling"}, {"height_m", 40.0}}), EditError);
  EXPECT_EQ(session.State()["edits"], 3);
}

TEST(ReviewSession, SaveWritesTheCorrectedSurveyAsALabelledRealExample) {
  // Saved as surveyed (exact labels), the layout's labels are the survey's
  // own wherever the box room's walls decide the pixel.
  const fs::path out = PanoramaSurvey("training");
  ReviewSession session = ReviewSession::Open(out);
  try {
    session.ExportTraining();
    FAIL() << "exported a review that was never saved";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no review was saved here"), std::string::npos) << e.what();
  }
  const std::vector<std::string> files = session.Save();
  EXPECT_NE(std::find(files.begin(), files.end(), "review/training/manifest.json"), files.end());
  const Manifest manifest = ReadManifest(out / "review/training/manifest.json", {.verify_checksums = true});
  const ReviewInput input = ReadReviewInput(out);
  ASSERT_EQ(manifest.train.size(), input.labels.size());
  ASSERT_FALSE(manifest.train.empty());
  long agree = 0, total = 0;
  for (std::size_t i = 0; i < manifest.train.size(); ++i) {
    EXPECT_EQ(manifest.train[i].source, PairSource::kReal);
    const cv::Mat drawn = cv::imread(manifest.Resolve(manifest.train[i].label).string(), cv::IMREAD_UNCHANGED);
    const cv::Mat surveyed = cv::imread(input.labels[i].image.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat image = cv::imread(manifest.Resolve(manifest.train[i].image).string());
    ASSERT_EQ(drawn.size(), surveyed.size());
    ASSERT_EQ(image.size(), surveyed.size());
    agree += cv::countNonZero(drawn == surveyed);
    total += static_cast<long>(drawn.total());
  }
  EXPECT_GT(double(agree) / total, 0.97) << agree << " of " << total << " pixels";
  const Plan truth = ReadPlan(out / "review/training/truth.json");
  EXPECT_EQ(PlanToJson(truth).dump(), PlanToJson(ReadPlan(out / "plan.json")).dump());
  EXPECT_EQ(session.ExportTraining().views, static_cast<int>(manifest.train.size()));
  // A plan without walls makes no example.
  EXPECT_THROW(WriteTrainingExample(input, Plan{}, 2.5, out / "none"), InvalidArgument);
}

TEST(ReviewSession, AnInterruptedSaveLeavesTheOldOutputsOrTheNew) {
  const fs::path out = PanoramaSurvey("atomic");
  ReviewSession session = ReviewSession::Open(out);
  const int ne = CornerNear(session.State(), {kX1, kY1});
  session.Edit({{"op", "move_corner"}, {"id", ne}, {"xy_m", {kX1 + 0.2, kY1}}});
  session.Save();
  const std::string old_plan = ReadFile(out / "plan.json"), old_svg = ReadFile(out / "plan.svg");
  const nlohmann::json newer = session.Edit({{"op", "move_corner"}, {"id", ne}, {"xy_m", {kX1 + 0.4, kY1}}});
  // Killed before the commit: the old outputs, and reopening keeps them.
  EXPECT_THROW(session.Save({.stop_before_commit = true}), Error);
  EXPECT_EQ(ReadFile(out / "plan.json"), old_plan);
  EXPECT_EQ(PlanOf(ReviewSession::Open(out).State()).walls.size(), ReadPlan(out / "plan.json").walls.size());
  EXPECT_EQ(ReadFile(out / "plan.json"), old_plan);
  EXPECT_EQ(ReadFile(out / "plan.svg"), old_svg);
  // Killed half-way through moving the files: reopening finishes the save.
  EXPECT_THROW(session.Save({.stop_after_files = 2}), Error);
  ReviewSession reopened = ReviewSession::Open(out);
  EXPECT_EQ(PlanToJson(ReadPlan(out / "plan.json")).dump(), newer["plan"].dump());
  EXPECT_NE(ReadFile(out / "plan.svg"), old_svg);
  EXPECT_EQ(reopened.State()["plan"].dump(), newer["plan"].dump());
  EXPECT_FALSE(fs::exists(out / "review" / "save-journal.json"));
  EXPECT_FALSE(fs::exists(out / "review" / ".save"));
}

// The demo classroom, surveyed from a small stereo capture with its exact
// labels: a corner clicked in a frame's left image re-fits the plan.
TEST(ReviewSession, StereoClassroomCornerClickInAFrame) {
  ReviewSession session = ReviewSession::Open(ClassroomSurvey("stereo"));
  nlohmann::json state = session.State();
  EXPECT_EQ(state["kind"], "stereo");
  EXPECT_EQ(state["images"].size(), 12u);
  ASSERT_GE(state["corners"].size(), 4u);
  const Plan truth = ClassroomTruth();
  const nlohmann::json corner = state["corners"][0];
  ASSERT_TRUE(corner.contains("frame"));
  // Move it 0.4 m into the room in the plan, then click it back where the survey saw it.
  const Vec2 xy(corner["xy_m"][0], corner["xy_m"][1]);
  Vec2 centre = Vec2::Zero();
  for (const nlohmann::json& c : state["corners"]) centre += Vec2(c["xy_m"][0], c["xy_m"][1]);
  centre /= static_cast<double>(state["corners"].size());
  const Vec2 inside = xy + 0.4 * (centre - xy).normalized();
  state = session.Edit({{"op", "move_corner"}, {"id", corner["id"]}, {"xy_m", {inside.x(), inside.y()}}});
  EXPECT_LT(RoomPolygonOverlap(PlanOf(state), truth)->Iou(), 0.99);
  nlohmann::json click = {
      {"op", "move_corner"}, {"id", corner["id"]}, {"frame", corner["frame"]}, {"u", corner["u"]}, {"v", corner["v"]}};
  state = session.Edit(click);
  EXPECT_GE(RoomPolygonOverlap(PlanOf(state), truth)->Iou(), 0.95);
  const auto t = std::chrono::steady_clock::now();
  session.Edit({{"op", "undo"}});
  fmt::print("stereo classroom re-fit: {:.2f} ms (undo {:.2f} ms)\n", state["refit_ms"].get<double>(),
             1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count());
  EXPECT_THROW(session.Edit({{"op", "add_corner"}, {"u", 10}, {"v", 200}}), EditError);  // No frame.
  EXPECT_THROW(session.Edit({{"op", "add_corner"}, {"frame", 99}, {"u", 10}, {"v", 200}}), EditError);
}

// The opening added last in `state` against a truth opening: the worse end's
// distance (either way round) and the head's and sill's errors.
struct OpeningError {
  double ends_m = 0.0, head_m = 0.0, sill_m = 0.0;
};
OpeningError ErrorOf(const nlohmann::json& o, const PlanOpening& t) {
  const Vec2 a(o["start_m"][0], o["start_m"][1]), b(o["end_m"][0], o["end_m"][1]);
  const double ends =
      std::min(std::max((a - t.start).norm(), (b - t.end).norm()), std::max((a - t.end).norm(), (b - t.start).norm()));
  const double sill = t.sill.value_or(0.0), head = sill + t.height.value_or(2.0);
  return {ends, std::abs(o["top_m"].get<double>() - head), std::abs(o["bottom_m"].get<double>() - sill)};
}

// One click inside the box room's door finds it: its jambs and head from
// the photo, on the wall the click looks at.
TEST(ReviewSession, OneClickOnADoorFindsItsJambsAndHead) {
  ReviewSession session = ReviewSession::Open(PanoramaSurvey("one_click_door"));
  nlohmann::json state = session.State();
  while (!state["openings"].empty())
    state = session.Edit({{"op", "delete_opening"}, {"id", state["openings"][0]["id"]}});
  const Vec2 inside = PanoPixel(Vec3(-0.3, kY1, 1.2));  // Off the door's centre.
  state = session.Edit({{"op", "add_opening"}, {"kind", "door"}, {"u", inside.x()}, {"v", inside.y()}});
  ASSERT_EQ(state["openings"].size(), 1u);
  const PlanOpening truth{.kind = OpeningKind::kDoor, .start = {-0.6, kY1}, .end = {0.3, kY1}, .height = 2.0};
  const OpeningError e = ErrorOf(state["openings"][0], truth);
  EXPECT_LT(e.ends_m, 0.03);
  EXPECT_LT(e.head_m, 0.05);
  EXPECT_EQ(state["openings"][0]["bottom_m"], 0.0);
  // A click on the plain wall finds no pair of jambs there: refused, nothing added.
  const Vec2 plain = PanoPixel(Vec3(kX1, 0.5, 1.2));
  EXPECT_THROW(session.Edit({{"op", "add_opening"}, {"kind", "window"}, {"u", plain.x()}, {"v", plain.y()}}),
               EditError);
  EXPECT_EQ(session.State()["openings"].size(), 1u);
}

// On the rendered classroom (textured walls, furniture), one click inside
// each true door and window, in the frame that sees it best, finds it.
TEST(ReviewSession, OneClickFindsTheClassroomsOpeningsInItsFrames) {
  const fs::path out = ClassroomSurvey("one_click");
  ReviewSession session = ReviewSession::Open(out);
  const ReviewInput input = ReadReviewInput(out);
  const Plan truth = ClassroomTruth();
  ASSERT_GE(truth.openings.size(), 3u);
  for (const PlanOpening& t : truth.openings) {
    const double sill = t.sill.value_or(0.0), head = sill + t.height.value_or(2.0);
    const Vec3 centre(t.Centre().x(), t.Centre().y(), 0.5 * (sill + head));
    const int k = BestImageFor(input.images, centre);
    const std::optional<Vec2> pixel = PixelOfPoint(input.images[k], centre);
    ASSERT_TRUE(pixel);
    const nlohmann::json state = session.Edit({{"op", "add_opening"},
                                               {"kind", OpeningKindName(t.kind)},
                                               {"frame", input.images[k].frame},
                                               {"u", pixel->x()},
                                               {"v", pixel->y()}});
    const OpeningError e = ErrorOf(state["openings"].back(), t);
    fmt::print("classroom {} {:.2f} m (frame {}, found {:.2f}–{:.2f} m): ends {:.3f} m, head {:.3f} m, sill {:.3f} m\n",
               OpeningKindName(t.kind), t.width, k, state["openings"].back()["bottom_m"].get<double>(),
               state["openings"].back()["top_m"].get<double>(), e.ends_m, e.head_m, e.sill_m);
    // Right as bench_review counts it: both ends within 0.15 m (a window's
    // frame is an edge on either side of the clear opening); head and sill 0.1 m.
    EXPECT_LT(e.ends_m, 0.15);
    EXPECT_LT(e.head_m, 0.10);
    EXPECT_LT(e.sill_m, 0.10);
  }
}

}  // namespace
}  // namespace asbuilt
