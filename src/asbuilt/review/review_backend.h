#ifndef ASBUILT_REVIEW_REVIEW_BACKEND_H_
#define ASBUILT_REVIEW_REVIEW_BACKEND_H_

// What review/http.h serves: one room's survey (review_session.h) or a whole
// home's placement (home_review.h), behind the same token, checks and routes.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt {

// A bad edit (unknown op or id, missing or non-finite number, a point
// outside the image, a room that would cross itself): HTTP 400.
class EditError : public InvalidArgument {
 public:
  using InvalidArgument::InvalidArgument;
};

class ReviewBackend {
 public:
  virtual ~ReviewBackend() = default;
  virtual nlohmann::json State() const = 0;
  // One edit → the new state; throws EditError and keeps the state.
  virtual nlohmann::json Edit(const nlohmann::json& edit) = 0;
  // Writes the outputs; returns the files written, relative to OUT.
  virtual std::vector<std::string> SaveAll() = 0;
  // The image files the page shows, in State()'s "images" order.
  virtual std::vector<std::filesystem::path> ImagePaths() const = 0;
  // The page (HTML with its scripts and styles), compiled in.
  virtual const char* PageHtml() const = 0;
};

}  // namespace asbuilt

#endif  // ASBUILT_REVIEW_REVIEW_BACKEND_H_
