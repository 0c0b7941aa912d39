#include "asbuilt/util/fields.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace asbuilt {
namespace {

std::string Path(std::string_view name) { return fmt::format("arguments.{}", name); }

std::string Short(const nlohmann::json& v) {
  if (v.is_object()) return v.empty() ? "{}" : "an object";
  if (v.is_array()) return v.empty() ? "[]" : fmt::format("an array of {}", v.size());
  std::string s = v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (s.size() > 40) s = s.substr(0, 37) + "...";
  return s;
}

std::string Fmt(double v) {
  // Shortest form that reads well: 2, 0.5, 1e-06.
  std::string s = fmt::format("{}", v);
  return s;
}

// "a number > 0 and <= 100" from the field's bounds.
std::string RangeText(const Field& f) {
  std::vector<std::string> parts;
  if (f.exclusive_minimum) parts.push_back("> " + Fmt(*f.exclusive_minimum));
  if (f.minimum) parts.push_back(">= " + Fmt(*f.minimum));
  if (f.maximum) parts.push_back("<= " + Fmt(*f.maximum));
  if (f.exclusive_maximum) parts.push_back("< " + Fmt(*f.exclusive_maximum));
  return fmt::format("{}", fmt::join(parts, " and "));
}

bool InRange(const Field& f, double v) {
  if (f.exclusive_minimum && !(v > *f.exclusive_minimum)) return false;
  if (f.minimum && !(v >= *f.minimum)) return false;
  if (f.maximum && !(v <= *f.maximum)) return false;
  if (f.exclusive_maximum && !(v < *f.exclusive_maximum)) return false;
  return true;
}

bool HasBounds(const Field& f) { return f.minimum || f.exclusive_minimum || f.maximum || f.exclusive_maximum; }

bool IsFiniteNumber(const nlohmann::json& v) { return v.is_number() && std::isfinite(v.get<double>()); }

void AddBounds(const Field& f, nlohmann::json& s) {
  if (f.minimum) s["minimum"] = *f.minimum;
  if (f.exclusive_minimum) s["exclusiveMinimum"] = *f.exclusive_minimum;
  if (f.maximum) s["maximum"] = *f.maximum;
  if (f.exclusive_maximum) s["exclusiveMaximum"] = *f.exclusive_maximum;
}

// "> 0", ">= 3", "in [0, 0.2)": a field's bounds as a library message says them.
std::string BoundsText(const Field& f) {
  const std::optional<double> lo = f.minimum ? f.minimum : f.exclusive_minimum;
  const std::optional<double> hi = f.maximum ? f.maximum : f.exclusive_maximum;
  if (lo && hi) {
    return fmt::format("in {}{}, {}{}", f.minimum ? "[" : "(", Fmt(*lo), Fmt(*hi), f.maximum ? "]" : ")");
  }
  if (lo) return fmt::format("{} {}", f.minimum ? ">=" : ">", Fmt(*lo));
  if (hi) return fmt::format("{} {}", f.maximum ? "<=" : "<", Fmt(*hi));
  return "finite";
}

// A value as a library message prints it: 2, 0.5, nan, [1, 2].
std::string ValueText(const nlohmann::json& v) {
  if (v.is_number_float()) return Fmt(v.get<double>());
  if (v.is_array()) {
    std::vector<std::string> parts;
    for (const nlohmann::json& e : v) parts.push_back(ValueText(e));
    return fmt::format("[{}]", fmt::join(parts, ", "));
  }
  return v.dump();
}

nlohmann::json FixedNumberArray(std::size_t n, const Field* bounds) {
  nlohmann::json item = {{"type", "number"}};
  if (bounds) AddBounds(*bounds, item);
  return {{"type", "array"}, {"items", item}, {"minItems", n}, {"maxItems", n}};
}

nlohmann::json FieldSchema(const Field& f) {
  nlohmann::json s;
  switch (f.kind) {
    case FieldKind::kNumber:
      s = {{"type", "number"}};
      AddBounds(f, s);
      break;
    case FieldKind::kInteger:
      s = {{"type", "integer"}};
      AddBounds(f, s);
      break;
    case FieldKind::kString:
      s = {{"type", "string"}};
      if (f.max_length) s["maxLength"] = f.max_length;
      break;
    case FieldKind::kBool:
      s = {{"type", "boolean"}};
      break;
    case FieldKind::kEnum: {
      nlohmann::json values = nlohmann::json::array();
      for (auto c : f.choices) values.push_back(c);
      s = {{"type", "string"}, {"enum", values}};
      break;
    }
    case FieldKind::kPoint2:
      s = FixedNumberArray(2, HasBounds(f) ? &f : nullptr);
      break;
    case FieldKind::kPoint3:
      s = FixedNumberArray(3, HasBounds(f) ? &f : nullptr);
      break;
    case FieldKind::kColor: {
      Field unit{.minimum = 0.0, .maximum = 1.0};
      s = FixedNumberArray(3, &unit);
      break;
    }
    case FieldKind::kPolygon:
      s = {{"type", "array"}, {"items", FixedNumberArray(2, nullptr)}};
      if (f.min_items) s["minItems"] = f.min_items;
      if (f.max_items) s["maxItems"] = f.max_items;
      break;
    case FieldKind::kNumberList: {
      nlohmann::json item = {{"type", "number"}};
      AddBounds(f, item);
      s = {{"type", "array"}, {"items", item}};
      if (f.min_items) s["minItems"] = f.min_items;
      if (f.max_items) s["maxItems"] = f.max_items;
      break;
    }
  }
  s["description"] = f.description;
  if (!f.default_value.is_null()) s["default"] = f.default_value;
  return s;
}

const char* TypeWord(FieldKind t) {
  switch (t) {
    case FieldKind::kNumber:
      return "number";
    case FieldKind::kInteger:
      return "integer";
    case FieldKind::kString:
      return "string";
    case FieldKind::kBool:
      return "boolean";
    case FieldKind::kEnum:
      return "string (enum)";
    case FieldKind::kPoint2:
      return "[x, y]";
    case FieldKind::kPoint3:
      return "[x, y, z]";
    case FieldKind::kColor:
      return "[r, g, b] in 0..1";
    case FieldKind::kPolygon:
      return "[[x, y], ...]";
    case FieldKind::kNumberList:
      return "[number, ...]";
  }
  return "?";
}

// Checks one argument; appends problems.
void CheckField(const Field& f, const nlohmann::json& v, std::vector<std::string>& problems) {
  std::string path = Path(f.name);
  auto problem = [&](const std::string& msg) { problems.push_back(path + ": " + msg); };
  auto number_problem = [&](const nlohmann::json& x, const std::string& where, const Field& b) {
    if (!IsFiniteNumber(x)) {
      problems.push_back(fmt::format("{}: must be a finite number, got {}", where, Short(x)));
    } else if (!InRange(b, x.get<double>())) {
      problems.push_back(fmt::format("{}: must be {}, got {}", where, RangeText(b), Short(x)));
    }
  };
  auto fixed_array = [&](std::size_t n, const std::string& what, const Field* b) {
    if (!v.is_array() || v.size() != n) {
      problem(fmt::format("must be {}, got {}", what, Short(v)));
      return;
    }
    for (std::size_t i = 0; i < n; ++i) {
      std::string where = fmt::format("{}[{}]", path, i);
      if (b) {
        number_problem(v[i], where, *b);
      } else if (!IsFiniteNumber(v[i])) {
        problems.push_back(fmt::format("{}: must be a finite number, got {}", where, Short(v[i])));
      }
    }
  };
  auto count_ok = [&](std::size_t n, const char* noun) {
    if (n < f.min_items || (f.max_items && n > f.max_items)) {
      if (f.max_items) {
        problem(fmt::format("must have {} to {} {}, got {}", f.min_items, f.max_items, noun, n));
      } else {
        problem(fmt::format("must have at least {} {}, got {}", f.min_items, noun, n));
      }
      return false;
    }
    return true;
  };

  switch (f.kind) {
    case FieldKind::kNumber:
      number_problem(v, path, f);
      break;
    case FieldKind::kInteger: {
      bool whole =
          v.is_number_integer() || (v.is_number_float() && std::isfinite(v.get<double>()) &&
                                    v.get<double>() == std::floor(v.get<double>()) && std::abs(v.get<double>()) < 9e15);
      if (!whole) {
        problem(
            fmt::format("must be a whole number{}, got {}", RangeText(f).empty() ? "" : " " + RangeText(f), Short(v)));
      } else if (!InRange(f, v.get<double>())) {
        problem(fmt::format("must be an integer {}, got {}", RangeText(f), Short(v)));
      }
      break;
    }
    case FieldKind::kString:
      if (!v.is_string()) {
        problem(fmt::format("must be a string, got {}", Short(v)));
      } else if (f.max_length && v.get_ref<const std::string&>().size() > f.max_length) {
        problem(
            fmt::format("must be at most {} characters, got {}", f.max_length, v.get_ref<const std::string&>().size()));
      }
      break;
    case FieldKind::kBool:
      if (!v.is_boolean()) problem(fmt::format("must be true or false, got {}", Short(v)));
      break;
    case FieldKind::kEnum: {
      bool ok = false;
      if (v.is_string()) {
        for (auto c : f.choices) ok = ok || v.get_ref<const std::string&>() == c;
      }
      if (!ok) {
        problem(
            fmt::format("must be one of {}, got {}", fmt::format("\"{}\"", fmt::join(f.choices, "\", \"")), Short(v)));
      }
      break;
    }
    case FieldKind::kPoint2:
      fixed_array(2, "[x, y] (two numbers, metres)", HasBounds(f) ? &f : nullptr);
      break;
    case FieldKind::kPoint3:
      fixed_array(3, "three numbers", HasBounds(f) ? &f : nullptr);
      break;
    case FieldKind::kColor: {
      Field unit{.minimum = 0.0, .maximum = 1.0};
      fixed_array(3, "[r, g, b] with each value in 0..1", &unit);
      break;
    }
    case FieldKind::kPolygon: {
      if (!v.is_array()) {
        problem(fmt::format("must be an array of [x, y] points, got {}", Short(v)));
        break;
      }
      if (!count_ok(v.size(), "points")) break;
      for (std::size_t i = 0; i < v.size(); ++i) {
        const auto& p = v[i];
        std::string where = fmt::format("{}[{}]", path, i);
        if (!p.is_array() || p.size() != 2 || !IsFiniteNumber(p[0]) || !IsFiniteNumber(p[1])) {
          problems.push_back(fmt::format("{}: must be [x, y] (two numbers, metres), got {}", where, Short(p)));
        }
      }
      break;
    }
    case FieldKind::kNumberList: {
      if (!v.is_array()) {
        problem(fmt::format("must be an array of numbers, got {}", Short(v)));
        break;
      }
      if (!count_ok(v.size(), "numbers")) break;
      for (std::size_t i = 0; i < v.size(); ++i) {
        number_problem(v[i], fmt::format("{}[{}]", path, i), f);
      }
      break;
    }
  }
}

}  // namespace

FieldArgsError::FieldArgsError(std::vector<std::string> problems)
    : InvalidArgument(fmt::format("{}", fmt::join(problems, "\n"))), problems_(std::move(problems)) {}

nlohmann::json FieldsSchema(std::span<const Field> fields) {
  nlohmann::json properties = nlohmann::json::object();
  nlohmann::json required = nlohmann::json::array();
  for (const Field& f : fields) {
    properties[std::string(f.name)] = FieldSchema(f);
    if (f.required) required.push_back(f.name);
  }
  nlohmann::json schema = {{"type", "object"}, {"properties", properties}, {"additionalProperties", false}};
  if (!required.empty()) schema["required"] = required;
  return schema;
}

FieldArgs ParseFieldArgs(std::span<const Field> fields, const nlohmann::json& arguments) {
  std::vector<std::string> problems;
  FieldArgs args;
  if (!arguments.is_null() && !arguments.is_object()) {
    throw FieldArgsError({fmt::format("arguments: must be an object, got {}", Short(arguments))});
  }
  const nlohmann::json empty = nlohmann::json::object();
  const nlohmann::json& given = arguments.is_object() ? arguments : empty;
  for (auto it = given.begin(); it != given.end(); ++it) {
    bool known = false;
    for (const Field& f : fields) known = known || f.name == it.key();
    if (!known) {
      std::vector<std::string_view> names;
      for (const Field& f : fields) names.push_back(f.name);
      problems.push_back(
          names.empty() ? fmt::format("{}: unknown argument; this tool takes no arguments", Path(it.key()))
                        : fmt::format("{}: unknown argument; allowed: {}", Path(it.key()), fmt::join(names, ", ")));
    }
  }
  for (const Field& f : fields) {
    auto it = given.find(f.name);
    if (it == given.end() || it->is_null()) {
      if (f.required) {
        problems.push_back(fmt::format("{}: required ({}: {})", Path(f.name), TypeWord(f.kind), f.description));
      } else if (!f.default_value.is_null()) {
        args.values_[std::string(f.name)] = f.default_value;
      }
      continue;
    }
    std::size_t before = problems.size();
    CheckField(f, *it, problems);
    if (problems.size() == before) args.values_[std::string(f.name)] = *it;
  }
  if (!problems.empty()) throw FieldArgsError(std::move(problems));
  return args;
}

bool FieldArgs::Has(std::string_view name) const { return values_.contains(name); }

const nlohmann::json& FieldArgs::Get(std::string_view name) const {
  auto it = values_.find(name);
  if (it == values_.end()) {
    throw InvalidArgument(fmt::format("{}: missing and has no default", Path(name)));
  }
  return *it;
}

double FieldArgs::Number(std::string_view name) const { return Get(name).get<double>(); }
std::optional<double> FieldArgs::OptNumber(std::string_view name) const {
  if (!Has(name)) return std::nullopt;
  return Number(name);
}
std::int64_t FieldArgs::Integer(std::string_view name) const {
  const auto& v = Get(name);
  return v.is_number_integer() ? v.get<std::int64_t>() : static_cast<std::int64_t>(v.get<double>());
}
std::optional<std::int64_t> FieldArgs::OptInteger(std::string_view name) const {
  if (!Has(name)) return std::nullopt;
  return Integer(name);
}
std::string FieldArgs::String(std::string_view name) const { return Get(name).get<std::string>(); }
std::optional<std::string> FieldArgs::OptString(std::string_view name) const {
  if (!Has(name)) return std::nullopt;
  return String(name);
}
bool FieldArgs::Bool(std::string_view name) const { return Get(name).get<bool>(); }
std::vector<double> FieldArgs::Numbers(std::string_view name) const { return Get(name).get<std::vector<double>>(); }
std::vector<std::vector<double>> FieldArgs::Points(std::string_view name) const {
  return Get(name).get<std::vector<std::vector<double>>>();
}

std::optional<std::string> FieldValuesProblem(std::span<const Field> fields, const nlohmann::json& values,
                                              std::string_view prefix) {
  for (const Field& f : fields) {
    auto it = values.find(f.name);
    if (it == values.end() || it->is_null()) continue;
    if (f.kind == FieldKind::kEnum) {
      if (!it->is_string() ||
          std::find(f.choices.begin(), f.choices.end(), it->get<std::string>()) == f.choices.end()) {
        return fmt::format("{}.{} = {}, must be one of {}", prefix, f.name, it->dump(), fmt::join(f.choices, ", "));
      }
      continue;
    }
    std::vector<nlohmann::json> numbers;
    switch (f.kind) {
      case FieldKind::kNumber:
      case FieldKind::kInteger:
        numbers = {*it};
        break;
      case FieldKind::kPoint2:
      case FieldKind::kPoint3:
      case FieldKind::kNumberList:
        numbers.assign(it->begin(), it->end());
        break;
      default:
        continue;
    }
    for (const nlohmann::json& n : numbers) {
      if (!IsFiniteNumber(n) || !InRange(f, n.get<double>())) {
        return fmt::format("{}.{} = {}, must be {}", prefix, f.name, ValueText(*it), BoundsText(f));
      }
    }
  }
  return std::nullopt;
}

std::string FieldsMarkdown(std::span<const Field> fields, std::string_view first_column) {
  if (fields.empty()) return "No arguments.\n";
  std::string out = fmt::format("| {} | type | default | description |\n|---|---|---|---|\n", first_column);
  for (const Field& f : fields) {
    std::string type = TypeWord(f.kind);
    if (f.kind == FieldKind::kEnum) {
      type = fmt::format("`{}`", fmt::join(f.choices, "` \\| `"));
    }
    std::string range = RangeText(f);
    if (!range.empty() && f.kind != FieldKind::kEnum) type += " " + range;
    const std::string def = f.required                  ? std::string("required")
                            : f.default_value.is_null() ? std::string("—")
                                                        : fmt::format("`{}`", f.default_value.dump());
    out += fmt::format("| `{}` | {} | {} | {} |\n", f.name, type, def, f.description);
  }
  return out;
}

}  // namespace asbuilt
