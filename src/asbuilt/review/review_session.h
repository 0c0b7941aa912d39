#ifndef ASBUILT_REVIEW_REVIEW_SESSION_H_
#define ASBUILT_REVIEW_REVIEW_SESSION_H_

// `asbuilt review`'s editable survey state, without HTTP (review/http.h is
// the thin layer over it): a survey's evidence (pipeline/review_input.h)
// plus a person's constraints — corners, the ceiling, the openings — and
// the plan FitPlan (plan/fit_plan.h) gives under them, re-fitted after every
// edit. Edits, their JSON and the state's JSON are those of docs/review.md.
//
//   ReviewSession session = ReviewSession::Open("out/");
//   session.Edit({{"op", "move_corner"}, {"id", 2}, {"u", 812.0}, {"v", 655.0}});
//   session.Save();  // plan.json/.svg/.dxf/.pdf/.png/.ifc, report.html, review/corrections.json
//
// A bad edit throws EditError with one message and leaves the state as it
// was. Reopening a folder whose review was saved starts from the saved state.

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "asbuilt/review/review_backend.h"
#include "asbuilt/review/training_example.h"
#include "asbuilt/util/error.h"

namespace asbuilt {

struct ReviewSaveOptions {
  // Test hook: stop (throw Error) after this many output files have been
  // moved into place, as a kill would (−1: never). The next Open finishes
  // the save (the outputs are then all new).
  int stop_after_files = -1;
  // Test hook: stop before any file is moved (the outputs stay all old).
  bool stop_before_commit = false;
};

class ReviewSession : public ReviewBackend {
 public:
  // Reads OUT (ReadReviewInput: throws InputError when OUT is not a survey
  // output), finishes an interrupted save, fits the plan, and starts from
  // OUT/review/state.json when a review was saved there.
  static ReviewSession Open(const std::filesystem::path& out_dir);
  ~ReviewSession() override;
  ReviewSession(ReviewSession&&) noexcept;
  ReviewSession& operator=(ReviewSession&&) noexcept;

  // {"plan", "corners", "openings", "ceiling_height_m", "edits", "kind",
  // "images", "walls", "notes", "refit_ms"} (docs/review.md).
  nlohmann::json State() const override;

  // Applies one edit ({"op": …}) and re-fits; returns State(). Throws
  // EditError (state unchanged).
  nlohmann::json Edit(const nlohmann::json& edit) override;

  // Writes OUT's plan outputs from the current plan, report.html,
  // OUT/review/corrections.json and OUT/review/state.json — as one
  // all-or-nothing step (staged in OUT/review/.save/, committed by a journal
  // file, then moved into place; an interrupted move is finished by the next
  // Open). Returns the files written, relative to OUT.
  std::vector<std::string> Save(const ReviewSaveOptions& options = {});
  std::vector<std::string> SaveAll() override { return Save(); }
  // Writes the saved review as a labelled real example into
  // OUT/review/training/ (review/training_example.h; Save writes it too).
  // Throws InputError when OUT holds no saved review.
  TrainingExample ExportTraining() const;

  const std::filesystem::path& out_dir() const;
  // The image files the page shows, in State()'s "images" order.
  std::vector<std::filesystem::path> ImagePaths() const override;
  const char* PageHtml() const override;
  // Seconds the last fit took.
  double last_fit_seconds() const;

 private:
  ReviewSession();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace asbuilt

#endif  // ASBUILT_REVIEW_REVIEW_SESSION_H_
