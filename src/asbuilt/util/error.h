#ifndef ASBUILT_UTIL_ERROR_H_
#define ASBUILT_UTIL_ERROR_H_

// asbuilt's error vocabulary (STYLE.md 7). Library code throws; only the CLI
// (`cli/main.cc`) and the MCP server catch and translate:
//   InvalidArgument → exit 2 / JSON-RPC invalid params,
//   InputError, Error → exit 1 / tool error.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace asbuilt {

// Base of every error asbuilt throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad options or arguments from the caller (a programming or usage error):
// `RenderOptions.samples_per_pixel = 0, must be > 0`.
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

// One problem found in an input file: which file, which field, what is wrong.
// Prints as `capture.json: frames[3].yaw_deg: expected a number, got "abc"`.
struct Problem {
  std::string file;        // As given by the user (may be relative).
  std::string field_path;  // JSON-style path; empty for the whole file.
  std::string message;

  std::string ToString() const;
};

// A bad input file. Carries every problem found (at least one); what() is
// the first problem, followed by the others on separate lines.
class InputError : public Error {
 public:
  explicit InputError(std::vector<Problem> problems);
  InputError(std::string file, std::string field_path, std::string message);

  const std::vector<Problem>& problems() const { return problems_; }

 private:
  std::vector<Problem> problems_;
};

// Throws InvalidArgument with `message` unless `condition` holds. For Check()
// methods of Options structs.
inline void CheckArgument(bool condition, const std::string& message) {
  if (!condition) throw InvalidArgument(message);
}

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_ERROR_H_
