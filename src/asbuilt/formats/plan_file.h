#ifndef ASBUILT_FORMATS_PLAN_FILE_H_
#define ASBUILT_FORMATS_PLAN_FILE_H_

// plan.json / truth.json — a floor plan (DESIGN.md). Walls are inner face
// lines; openings lie on their host wall's line. Fields a method cannot
// measure are optional. asbuilt adds optional ± uncertainties (1σ, metres)
// per dimension: `length_sigma_m` on walls, `width_sigma_m`,
// `height_sigma_m`, `sill_sigma_m` on openings, `area_sigma_m2` on rooms.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/geometry/polygon.h"
#include "asbuilt/geometry/rig.h"

namespace asbuilt {

struct PlanWall {
  Vec2 start = Vec2::Zero();
  Vec2 end = Vec2::Zero();
  std::optional<double> thickness;  // Outwards from the inner face.
  std::optional<double> height;
  std::optional<double> length_sigma_m;
  // asbuilt's verdict on this wall's length: "good", "check" or
  // "unreliable" (plan/verdict.h); an unreliable wall has no ±.
  std::optional<std::string> verdict;

  double Length() const { return (end - start).norm(); }
};

enum class OpeningKind { kDoor, kWindow };
const char* OpeningKindName(OpeningKind kind);  // "door" / "window"

struct PlanOpening {
  OpeningKind kind = OpeningKind::kDoor;
  int wall = 0;               // Index into Plan::walls.
  Vec2 start = Vec2::Zero();  // End nearer the wall's start.
  Vec2 end = Vec2::Zero();
  double width = 0.0;
  std::optional<double> height;
  std::optional<double> sill;
  std::optional<double> width_sigma_m;
  std::optional<double> height_sigma_m;
  std::optional<double> sill_sigma_m;
  // A home's plan (home/): the two rooms (indices into Plan::rooms) a door
  // between them joins; each such door is written once.
  std::optional<std::pair<int, int>> rooms;

  Vec2 Centre() const { return 0.5 * (start + end); }
};

// Where a room's capture frame lies in a home's frame (home/): its origin,
// and how far its axes are turned, counter-clockwise.
struct PlanPose {
  Vec2 position_m = Vec2::Zero();
  double yaw_deg = 0.0;
};

struct PlanRoom {
  std::vector<Vec2> polygon;
  double area_m2 = 0.0;
  std::optional<double> area_sigma_m2;
  // A home's plan (home/): the room's name, its pose and what placed it
  // ("door kitchen#1 = hall#3", "first room", "not placed: drawn beside").
  std::optional<std::string> name;
  std::optional<PlanPose> pose;
  std::optional<std::string> placed_by;
};

// asbuilt's verdict on a measured plan (plan/verdict.h): whether it can be
// used as it is. Absent in truth files and plans from elsewhere.
struct PlanVerdictNote {
  std::string verdict;  // "good", "check" or "unreliable".
  double confidence = 0.0;
  std::vector<std::string> reasons;
};
// Whether `word` is one of "good", "check", "unreliable".
bool IsVerdictWord(const std::string& word);

struct Plan {
  int version = 1;
  std::optional<PlanVerdictNote> verdict;
  std::vector<PlanWall> walls;
  std::vector<PlanOpening> openings;
  std::vector<PlanRoom> rooms;

  std::string ToString() const;
};

// Reads and validates a plan. Throws InputError listing every problem with its
// field path (wrong types, NaN/inf, negative sizes, wall index out of range,
// unknown opening kind, degenerate walls, polygons with < 3 points).
Plan ReadPlan(const std::filesystem::path& path);
FileReport CheckPlanFile(const std::filesystem::path& path);
// Same, from JSON already in memory; `name` stands for the file in messages.
Plan PlanFromJson(const nlohmann::json& json, const std::string& name);

nlohmann::json PlanToJson(const Plan& plan);
// Writes atomically.
void WritePlan(const Plan& plan, const std::filesystem::path& path);

}  // namespace asbuilt

#endif  // ASBUILT_FORMATS_PLAN_FILE_H_
