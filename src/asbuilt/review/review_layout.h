#ifndef ASBUILT_REVIEW_REVIEW_LAYOUT_H_
#define ASBUILT_REVIEW_REVIEW_LAYOUT_H_

// Internal to review/: what a person has said about a room — its corners,
// openings and ceiling, the constraints of the plan fit — as the review
// session keeps it, writes it to state.json and reads it back; and the
// readers of an edit's fields, each refusing with one EditError.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/plan/fit_plan.h"

namespace asbuilt::review_layout {

// A corner: the person's point (user) or the survey's (a hint the fit re-places).
struct Corner {
  int id = 0;
  Vec2 xy_m = Vec2::Zero();
  bool user = false;
};

struct Opening {
  int id = 0;
  OpeningKind kind = OpeningKind::kDoor;
  Vec2 start_m = Vec2::Zero(), end_m = Vec2::Zero();
  double bottom_m = 0.0, top_m = 2.0;
  bool user = false;
};

// What the person has said: the constraints of the fit.
struct Layout {
  std::vector<Corner> corners;
  bool corners_edited = false;  // Else the corners are the fit's own (no corner constraint).
  std::vector<Opening> openings;
  bool openings_edited = false;  // Else the openings are the fit's own.
  std::optional<double> ceiling_m;
  int next_id = 0;
};

// A plan point as JSON: [x, y].
nlohmann::json Xy(const Vec2& v);

// The layout as state.json keeps it, and back (InputError naming `name`).
nlohmann::json LayoutJson(const Layout& l);
Layout LayoutFromJson(const nlohmann::json& js, const std::string& name);

// The constraints of the fit: the corners and openings the person edited, the ceiling.
PlanConstraints ConstraintsOf(const Layout& l);

std::vector<Vec2> CornerPoints(const Layout& l);

// An edit's fields. EditError when missing or not finite (a plan point: not
// two finite numbers; `what` starts its message).
Vec2 PlanPoint(const nlohmann::json& edit, const char* key, const std::string& what);
double Number(const nlohmann::json& edit, const char* key);
int Integer(const nlohmann::json& edit, const char* key);

}  // namespace asbuilt::review_layout

#endif  // ASBUILT_REVIEW_REVIEW_LAYOUT_H_
