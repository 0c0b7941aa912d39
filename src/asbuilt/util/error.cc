#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

std::string JoinProblems(const std::vector<Problem>& problems) {
  std::string out;
  for (const Problem& p : problems) {
    if (!out.empty()) out += '\n';
    out += p.ToString();
  }
  return out.empty() ? std::string("unknown input error") : out;
}

}  // namespace

std::string Problem::ToString() const {
  std::string out = file;
  if (!field_path.empty()) {
    if (!out.empty()) out += ": ";
    out += field_path;
  }
  if (!out.empty()) out += ": ";
  out += message;
  return out;
}

InputError::InputError(std::vector<Problem> problems) : Error(JoinProblems(problems)), problems_(std::move(problems)) {}

InputError::InputError(std::string file, std::string field_path, std::string message)
    : InputError(std::vector<Problem>{{std::move(file), std::move(field_path), std::move(message)}}) {}

}  // namespace asbuilt
