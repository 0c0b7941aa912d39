#ifndef ASBUILT_PIPELINE_HOME_SURVEY_H_
#define ASBUILT_PIPELINE_HOME_SURVEY_H_

// `asbuilt survey home.json -o OUT/`: every room of a home surveyed, the
// rooms placed from the doors they share, one floor plan (docs/home.md).
//   survey each room (OUT/rooms/NAME/, in parallel) → place (home/) →
//   one plan (plan.json/.svg/.dxf/.pdf/.png/.ifc) → report.html, summary.json
// A room whose capture cannot be surveyed is named in the report and the
// summary; the others are surveyed and placed all the same.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "asbuilt/formats/home_file.h"
#include "asbuilt/home/home_plan.h"
#include "asbuilt/home/placement.h"
#include "asbuilt/pipeline/survey.h"

namespace asbuilt {

struct HomeSurveyOptions {
  SurveyOptions survey;  // For every room (a room's own `labels` wins over survey.labels_dir).
  PlacementOptions placement;
  HomePlanOptions plan;
  int jobs = 0;  // Rooms surveyed at once; 0: one per two hardware threads, at least one.
  void Check() const;
};

struct HomeRoomSurvey {
  std::string name;
  bool ok = false;
  std::string error;  // When !ok: why the room has no plan.
  SurveySummary summary;
  Plan plan;
};

struct HomeSurveyResult {
  Home home;
  std::vector<HomeRoomSurvey> rooms;  // In home.json's order.
  // The rooms that have a plan, as placed (indices into `rooms` in `surveyed`).
  std::vector<HomeRoomInput> inputs;
  std::vector<int> surveyed;
  PlacementResult placement;
  Plan plan;
  double seconds = 0.0;
  // "13 rooms: 13 surveyed, 12 placed (11 by doors, 1 loop); 142.3 m²; 71 s → OUT/report.html".
  std::string BriefReport() const;
};

// Calls `on_room` once per room as its survey ends ("kitchen: 4 walls, …" or
// "kitchen: failed: …"), from the thread that surveyed it, one at a time.
// Throws InputError for a bad home.json (nothing is written then).
HomeSurveyResult RunHomeSurvey(const std::filesystem::path& home_json, const std::filesystem::path& out_dir,
                               const HomeSurveyOptions& options = {},
                               const std::function<void(const std::string&)>& on_room = {});

// What `asbuilt review OUT/` re-places a home from: OUT/review/home.json,
// each surveyed room's name, plan (its own frame) and hint. Read throws
// InputError naming the file when OUT holds no home survey.
void WriteHomeReviewInput(const std::filesystem::path& out_dir, const std::vector<HomeRoomInput>& rooms);
std::vector<HomeRoomInput> ReadHomeReviewInput(const std::filesystem::path& out_dir);
std::filesystem::path HomeReviewInputPath(const std::filesystem::path& out_dir);  // OUT/review/home.json

}  // namespace asbuilt

#endif  // ASBUILT_PIPELINE_HOME_SURVEY_H_
