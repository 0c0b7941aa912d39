#include "asbuilt/util/json_reader.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {

std::string JoinPath(const std::string& parent, std::string_view key) {
  if (parent.empty()) return std::string(key);
  return fmt::format("{}.{}", parent, key);
}

// Line and column (1-based) of a byte offset in text.
std::pair<int, int> LineColumn(std::string_view text, std::size_t offset) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

const char* TypeName(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null:
      return "null";
    case nlohmann::json::value_t::object:
      return "an object";
    case nlohmann::json::value_t::array:
      return "an array";
    case nlohmann::json::value_t::string:
      return "a string";
    case nlohmann::json::value_t::boolean:
      return "a boolean";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
      return "an integer";
    case nlohmann::json::value_t::number_float:
      return "a number";
    default:
      return "an unknown value";
  }
}

}  // namespace

void JsonDiagnostics::AddError(std::string field_path, std::string message) {
  errors_.push_back({file_, std::move(field_path), std::move(message)});
}

void JsonDiagnostics::AddWarning(std::string field_path, std::string message) {
  warnings_.push_back({file_, std::move(field_path), std::move(message)});
}

void JsonDiagnostics::ThrowIfErrors() const {
  if (!errors_.empty()) throw InputError(errors_);
}

void JsonDiagnostics::LogWarnings() const {
  for (const Problem& w : warnings_) spdlog::warn("{}", w.ToString());
}

nlohmann::json ParseJsonText(std::string_view text, JsonDiagnostics& diag) {
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    auto [line, column] = LineColumn(text, e.byte > 0 ? e.byte - 1 : 0);
    std::string what = e.what();
    // nlohmann's message is "[json.exception.parse_error.101] parse error at
    // line 1, column 2: syntax error while parsing ..."; keep the tail.
    auto colon = what.find(": ");
    std::string detail = colon == std::string::npos ? what : what.substr(colon + 2);
    diag.AddError("", fmt::format("invalid JSON at line {}, column {}: {}", line, column, detail));
    return nullptr;
  } catch (const nlohmann::json::exception& e) {
    // E.g. out_of_range.406 "number overflow parsing '1e999'".
    std::string what = e.what();
    auto bracket = what.find("] ");
    diag.AddError("", fmt::format("invalid JSON: {} (numbers must be finite)",
                                  bracket == std::string::npos ? what : what.substr(bracket + 2)));
    return nullptr;
  }
}

nlohmann::json ParseJsonFile(const std::filesystem::path& path, JsonDiagnostics& diag) {
  std::string text;
  try {
    text = ReadFile(path);
  } catch (const InputError& e) {
    diag.AddError("", e.problems().front().message);
    return nullptr;
  }
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    diag.AddError("", "file is empty");
    return nullptr;
  }
  return ParseJsonText(text, diag);
}

std::string DescribeJsonValue(const nlohmann::json& value) {
  if (value.is_object()) return value.empty() ? "{}" : "{...}";
  if (value.is_array()) return value.empty() ? "[]" : "[...]";
  std::string s = value.dump();
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

JsonField JsonField::Required(std::string_view key) const {
  std::string child_path = JoinPath(path_, key);
  if (value_ == nullptr) return JsonField(nullptr, child_path, diag_);
  if (!value_->is_object()) {
    TypeError("an object");
    return JsonField(nullptr, child_path, diag_);
  }
  auto it = value_->find(key);
  if (it == value_->end()) {
    diag_->AddError(child_path, "missing required field");
    return JsonField(nullptr, child_path, diag_);
  }
  return JsonField(&*it, child_path, diag_);
}

JsonField JsonField::Optional(std::string_view key) const {
  std::string child_path = JoinPath(path_, key);
  if (value_ == nullptr || !value_->is_object()) {
    if (value_ != nullptr) TypeError("an object");
    return JsonField(nullptr, child_path, diag_);
  }
  auto it = value_->find(key);
  if (it == value_->end() || it->is_null()) {
    return JsonField(nullptr, child_path, diag_);
  }
  return JsonField(&*it, child_path, diag_);
}

JsonField JsonField::At(std::size_t i) const {
  std::string child_path = fmt::format("{}[{}]", path_, i);
  if (value_ == nullptr || !value_->is_array() || i >= value_->size()) {
    return JsonField(nullptr, child_path, diag_);
  }
  return JsonField(&(*value_)[i], child_path, diag_);
}

void JsonField::AddError(std::string message) const { diag_->AddError(path_, std::move(message)); }

void JsonField::AddWarning(std::string message) const { diag_->AddWarning(path_, std::move(message)); }

void JsonField::TypeError(std::string_view expected) const {
  AddError(fmt::format(
      "expected {}, got {}", expected,
      value_->is_object() || value_->is_array() ? std::string(TypeName(*value_)) : DescribeJsonValue(*value_)));
}

std::optional<double> JsonField::Number() const {
  if (value_ == nullptr) return std::nullopt;
  if (!value_->is_number()) {
    TypeError("a number");
    return std::nullopt;
  }
  double v = value_->get<double>();
  if (!std::isfinite(v)) {
    AddError(fmt::format("expected a finite number, got {}", v));
    return std::nullopt;
  }
  return v;
}

std::optional<double> JsonField::Positive() const {
  auto v = Number();
  if (v && !(*v > 0)) {
    AddError(fmt::format("must be > 0, got {}", DescribeJsonValue(*value_)));
    return std::nullopt;
  }
  return v;
}

std::optional<double> JsonField::NonNegative() const {
  auto v = Number();
  if (v && *v < 0) {
    AddError(fmt::format("must be >= 0, got {}", DescribeJsonValue(*value_)));
    return std::nullopt;
  }
  return v;
}

std::optional<std::int64_t> JsonField::Integer() const {
  if (value_ == nullptr) return std::nullopt;
  if (value_->is_number_integer() || value_->is_number_unsigned()) {
    if (value_->is_number_unsigned() && value_->get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX)) {
      AddError("integer out of range");
      return std::nullopt;
    }
    return value_->get<std::int64_t>();
  }
  if (value_->is_number_float()) {
    double v = value_->get<double>();
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 9e15) {
      return static_cast<std::int64_t>(v);
    }
  }
  TypeError("an integer");
  return std::nullopt;
}

std::optional<std::string> JsonField::String() const {
  if (value_ == nullptr) return std::nullopt;
  if (!value_->is_string()) {
    TypeError("a string");
    return std::nullopt;
  }
  return value_->get<std::string>();
}

std::optional<bool> JsonField::Bool() const {
  if (value_ == nullptr) return std::nullopt;
  if (!value_->is_boolean()) {
    TypeError("true or false");
    return std::nullopt;
  }
  return value_->get<bool>();
}

std::optional<std::size_t> JsonField::ArraySize(std::size_t min_size, std::size_t max_size) const {
  if (value_ == nullptr) return std::nullopt;
  if (!value_->is_array()) {
    TypeError("an array");
    return std::nullopt;
  }
  std::size_t n = value_->size();
  if (n < min_size || n > max_size) {
    if (min_size == max_size) {
      AddError(fmt::format("expected {} elements, got {}", min_size, n));
    } else if (n < min_size) {
      AddError(fmt::format("expected at least {} elements, got {}", min_size, n));
    } else {
      AddError(fmt::format("expected at most {} elements, got {}", max_size, n));
    }
    return std::nullopt;
  }
  return n;
}

std::optional<std::vector<double>> JsonField::NumberArray(std::size_t n) const {
  if (!ArraySize(n, n)) return std::nullopt;
  std::vector<double> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    auto v = At(i).Number();
    if (!v) return std::nullopt;
    out.push_back(*v);
  }
  return out;
}

bool JsonField::Object(std::initializer_list<std::string_view> known) const {
  if (value_ == nullptr) return false;
  if (!value_->is_object()) {
    TypeError("an object");
    return false;
  }
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    bool is_known = false;
    for (std::string_view k : known) is_known = is_known || it.key() == k;
    if (!is_known) {
      diag_->AddWarning(JoinPath(path_, it.key()), "unknown key, ignored");
    }
  }
  return true;
}

}  // namespace asbuilt
