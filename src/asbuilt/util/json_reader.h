#ifndef ASBUILT_UTIL_JSON_READER_H_
#define ASBUILT_UTIL_JSON_READER_H_

// Reading JSON input files with validation that names the file and the field
// path of every problem (`capture.json: frames[3].yaw_deg: expected a number,
// got "abc"`), collecting all problems rather than stopping at the first, so
// `asbuilt validate` can report them all.
//
//   JsonDiagnostics diag("capture.json");
//   nlohmann::json root = ParseJsonFile(path, diag);
//   JsonField doc(root, diag);
//   double b = doc.Required("camera").Required("baseline_m").Positive().value_or(0);
//   diag.ThrowIfErrors();   // InputError listing every problem

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt {

// Collects errors and warnings found in one file.
class JsonDiagnostics {
 public:
  explicit JsonDiagnostics(std::string file) : file_(std::move(file)) {}

  void AddError(std::string field_path, std::string message);
  void AddWarning(std::string field_path, std::string message);

  const std::string& file() const { return file_; }
  const std::vector<Problem>& errors() const { return errors_; }
  const std::vector<Problem>& warnings() const { return warnings_; }
  bool ok() const { return errors_.empty(); }

  // Throws InputError with every error collected so far, if any.
  void ThrowIfErrors() const;
  // Logs every warning at warn level (spdlog, stderr).
  void LogWarnings() const;

 private:
  std::string file_;
  std::vector<Problem> errors_;
  std::vector<Problem> warnings_;
};

// Reads and parses a JSON file. A missing/unreadable file or a syntax error is
// recorded in `diag` (with line and column) and a null value returned.
nlohmann::json ParseJsonFile(const std::filesystem::path& path, JsonDiagnostics& diag);
// Same for JSON text already in memory (e.g. an MCP message or LLM answer).
nlohmann::json ParseJsonText(std::string_view text, JsonDiagnostics& diag);

// A view of one value inside a document, with its path. A field that is
// absent (missing, or under a wrong-typed parent) reads as nullopt without
// adding more errors, so one mistake gives one message.
class JsonField {
 public:
  JsonField(const nlohmann::json& root, JsonDiagnostics& diag) : value_(&root), diag_(&diag) {}

  // A member that must exist; records "missing required field" otherwise.
  JsonField Required(std::string_view key) const;
  // A member that may be absent (absent reads as nullopt, no error).
  JsonField Optional(std::string_view key) const;
  // Element i of an array (caller checks the size first).
  JsonField At(std::size_t i) const;

  bool present() const { return value_ != nullptr && !value_->is_null(); }
  bool is_object() const { return value_ && value_->is_object(); }
  const nlohmann::json* raw() const { return value_; }
  const std::string& path() const { return path_; }
  JsonDiagnostics& diagnostics() const { return *diag_; }

  // Typed reads. Each records an error (naming what was expected and what was
  // found) and returns nullopt on a mismatch. Numbers must be finite.
  std::optional<double> Number() const;
  std::optional<double> Positive() const;     // > 0
  std::optional<double> NonNegative() const;  // >= 0
  std::optional<std::int64_t> Integer() const;
  std::optional<std::string> String() const;
  std::optional<bool> Bool() const;
  // An array; checks its length is within [min_size, max_size].
  std::optional<std::size_t> ArraySize(std::size_t min_size = 0, std::size_t max_size = SIZE_MAX) const;
  // An array of exactly n finite numbers.
  std::optional<std::vector<double>> NumberArray(std::size_t n) const;
  // Requires an object; warns about members not in `known` ("unknown key,
  // ignored"), so files can grow without silent typos.
  bool Object(std::initializer_list<std::string_view> known) const;

  void AddError(std::string message) const;
  void AddWarning(std::string message) const;

 private:
  JsonField(const nlohmann::json* value, std::string path, JsonDiagnostics* diag)
      : value_(value), path_(std::move(path)), diag_(diag) {}
  void TypeError(std::string_view expected) const;

  const nlohmann::json* value_ = nullptr;  // nullptr: absent.
  std::string path_;
  JsonDiagnostics* diag_;
};

// Short printable form of a JSON value for messages: `"abc"`, `12`, `{…}`.
std::string DescribeJsonValue(const nlohmann::json& value);

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_JSON_READER_H_
