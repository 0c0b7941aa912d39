#ifndef ASBUILT_UTIL_FIELDS_H_
#define ASBUILT_UTIL_FIELDS_H_

// One field list per Options struct (STYLE.md 13). A Field says what a value
// is (name, kind, one-line description, bounds); a FieldList<T> binds fields
// to the members of an Options struct T, so the same list gives
//
//   - the MCP tool's JSON Schema and argument checks (FieldsSchema,
//     ParseFieldArgs; mcp/tools.h),
//   - the CLI flags (cli/field_flags.h: `epsilon_m` → --epsilon-m, nested
//     `disparity.block_size_px` → --disparity.block-size-px),
//   - the reference tables (FieldsMarkdown: docs/mcp.md, --help),
//
// with defaults read from the struct itself and values written into it, so
// adding an option is one member plus one line in its list:
//
//   const FieldList<PlanOptions>& PlanOptionFields() {
//     static const FieldList<PlanOptions> kList = {
//         Bind(&PlanOptions::epsilon_m, {.name = "epsilon_m", .description = "…",
//                                        .exclusive_minimum = 0.0}),
//     };
//     return kList;
//   }
//   FieldArgs args = ParseFieldArgs(PlanOptionFields().Fields(), json);  // Throws FieldArgsError.
//   PlanOptions options = PlanOptionFields().FromArgs(args);
//
// Validation collects every problem with its path ("arguments.width_m: must be
// > 0, got -2") so a caller (an LLM, a person at a shell) can fix all at once.

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt {

enum class FieldKind {
  kNumber,   // Finite number.
  kInteger,  // Whole number.
  kString,
  kBool,
  kEnum,        // One of `choices` (a string).
  kPoint2,      // [x, y], finite numbers.
  kPoint3,      // [x, y, z].
  kColor,       // [r, g, b], each in [0, 1].
  kPolygon,     // [[x, y], ...], between min_items and max_items points.
  kNumberList,  // [n, ...], between min_items and max_items finite numbers.
};

struct Field {
  std::string name;  // Nested fields: "disparity.block_size_px".
  FieldKind kind = FieldKind::kNumber;
  std::string_view description;  // One line: meaning, unit, trade-off.
  bool required = false;
  // Numbers (and each element of kPoint*, kNumberList): bounds, inclusive
  // unless exclusive_minimum is used.
  std::optional<double> minimum;
  std::optional<double> exclusive_minimum;
  std::optional<double> maximum;
  std::optional<double> exclusive_maximum;
  // kPolygon / kNumberList: element count bounds.
  std::size_t min_items = 0;
  std::size_t max_items = 0;  // 0: no limit.
  // kEnum: the allowed values.
  std::vector<std::string_view> choices;
  // kString: maximum length in bytes (0: no limit).
  std::size_t max_length = 0;
  // Shown as "default" (and used by FieldArgs when absent); null: none (an
  // optional member that is unset, or a required field).
  nlohmann::json default_value = nullptr;
};

// The JSON Schema (draft 2020-12 subset) of an object of these fields:
// properties with types, bounds, enums, defaults and descriptions;
// `required`; additionalProperties false.
nlohmann::json FieldsSchema(std::span<const Field> fields);

// Bad values; what() lists every problem, one per line, each naming the
// value ("arguments.wall: must be an integer >= 0, got -1").
class FieldArgsError : public InvalidArgument {
 public:
  explicit FieldArgsError(std::vector<std::string> problems);
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

// Validated values of one object. Accessors take a field name from the list;
// an absent optional field reads as its default (or nullopt for the Opt*
// accessors when there is none).
class FieldArgs {
 public:
  bool Has(std::string_view name) const;
  double Number(std::string_view name) const;
  std::optional<double> OptNumber(std::string_view name) const;
  std::int64_t Integer(std::string_view name) const;
  std::optional<std::int64_t> OptInteger(std::string_view name) const;
  std::string String(std::string_view name) const;  // Also kEnum.
  std::optional<std::string> OptString(std::string_view name) const;
  bool Bool(std::string_view name) const;
  std::vector<double> Numbers(std::string_view name) const;              // Point, colour, list.
  std::vector<std::vector<double>> Points(std::string_view name) const;  // Polygon.

  // Given values + defaults, by field name.
  const nlohmann::json& raw() const { return values_; }

 private:
  friend FieldArgs ParseFieldArgs(std::span<const Field>, const nlohmann::json&);
  const nlohmann::json& Get(std::string_view name) const;
  nlohmann::json values_ = nlohmann::json::object();
};

// Validates `arguments` (an object, or null for none) against the fields;
// problems are reported as "arguments.NAME: …". Unknown names are errors
// (usually typos the caller should fix). Throws FieldArgsError listing every
// problem.
FieldArgs ParseFieldArgs(std::span<const Field> fields, const nlohmann::json& arguments);

// The first problem with the values `values` holds (by field name, as
// FieldList::ToJson gives them) against the fields' bounds, worded for a
// library caller: "PlanOptions.epsilon_m = -1, must be > 0" (`prefix`
// "PlanOptions"); nullopt when every value is within its bounds and finite.
std::optional<std::string> FieldValuesProblem(std::span<const Field> fields, const nlohmann::json& values,
                                              std::string_view prefix);

// Markdown table of the fields (name, type, default, description), e.g. for
// docs/mcp.md; `first_column` heads the names.
std::string FieldsMarkdown(std::span<const Field> fields, std::string_view first_column = "argument");

// ------------------------------------------------------------- binding

// How a member type reads and writes as a field value. Specialised for
// double, integers, bool, std::string and std::optional of those; enums and
// other types bind with BindEnum or BindWith.
template <class M, class = void>
struct FieldCodec;

template <>
struct FieldCodec<double> {
  static constexpr FieldKind kKind = FieldKind::kNumber;
  static nlohmann::json ToJson(double v) { return v; }
  static double FromJson(const nlohmann::json& v) { return v.get<double>(); }
};

template <class M>
struct FieldCodec<M, std::enable_if_t<std::is_integral_v<M> && !std::is_same_v<M, bool>>> {
  static constexpr FieldKind kKind = FieldKind::kInteger;
  static nlohmann::json ToJson(M v) { return v; }
  static M FromJson(const nlohmann::json& v) {
    return static_cast<M>(v.is_number_integer() ? v.get<std::int64_t>() : static_cast<std::int64_t>(v.get<double>()));
  }
};

template <>
struct FieldCodec<bool> {
  static constexpr FieldKind kKind = FieldKind::kBool;
  static nlohmann::json ToJson(bool v) { return v; }
  static bool FromJson(const nlohmann::json& v) { return v.get<bool>(); }
};

template <>
struct FieldCodec<std::string> {
  static constexpr FieldKind kKind = FieldKind::kString;
  static nlohmann::json ToJson(const std::string& v) { return v; }
  static std::string FromJson(const nlohmann::json& v) { return v.get<std::string>(); }
};

// Unset reads as null (no default); a value sets it.
template <class M>
struct FieldCodec<std::optional<M>> {
  static constexpr FieldKind kKind = FieldCodec<M>::kKind;
  static nlohmann::json ToJson(const std::optional<M>& v) {
    return v ? FieldCodec<M>::ToJson(*v) : nlohmann::json(nullptr);
  }
  static std::optional<M> FromJson(const nlohmann::json& v) {
    if (v.is_null()) return std::nullopt;
    return FieldCodec<M>::FromJson(v);
  }
};

// A field bound to a place in T: `get` reads the value (null: unset), `set`
// writes a value that passed the field's checks.
template <class T>
struct BoundField {
  Field field;
  std::function<nlohmann::json(const T&)> get;
  std::function<void(T&, const nlohmann::json&)> set;
};

// A field bound to a member; its kind comes from the member's type.
template <class T, class M>
BoundField<T> Bind(M T::*member, Field field) {
  field.kind = FieldCodec<M>::kKind;
  return {std::move(field), [member](const T& t) { return FieldCodec<M>::ToJson(t.*member); },
          [member](T& t, const nlohmann::json& v) { t.*member = FieldCodec<M>::FromJson(v); }};
}

// A field bound to a member of a member (`render.seed` read as `seed`).
template <class T, class S, class M>
BoundField<T> Bind(S T::*outer, M S::*member, Field field) {
  field.kind = FieldCodec<M>::kKind;
  return {std::move(field), [outer, member](const T& t) { return FieldCodec<M>::ToJson(t.*outer.*member); },
          [outer, member](T& t, const nlohmann::json& v) { t.*outer.*member = FieldCodec<M>::FromJson(v); }};
}

// An enum member as a kEnum field; `names` lists every value with its name
// (the field's choices, in this order).
template <class T, class E>
BoundField<T> BindEnum(E T::*member, Field field, std::vector<std::pair<std::string_view, E>> names) {
  field.kind = FieldKind::kEnum;
  field.choices.clear();
  for (const auto& [name, value] : names) field.choices.push_back(name);
  return {std::move(field),
          [member, names](const T& t) -> nlohmann::json {
            for (const auto& [name, value] : names) {
              if (t.*member == value) return std::string(name);
            }
            return nullptr;
          },
          [member, names](T& t, const nlohmann::json& v) {
            for (const auto& [name, value] : names) {
              if (v.get_ref<const std::string&>() == name) t.*member = value;
            }
          }};
}

// A string member that takes one of `field.choices` as a kEnum field (an
// option whose values are words, such as SegmentOptions::mode).
template <class T>
BoundField<T> BindChoice(std::string T::*member, Field field) {
  field.kind = FieldKind::kEnum;
  return {std::move(field), [member](const T& t) { return nlohmann::json(t.*member); },
          [member](T& t, const nlohmann::json& v) { t.*member = v.get<std::string>(); }};
}

// A field with its own reading and writing (types util does not know, such
// as Eigen vectors); `field.kind` must be set.
template <class T>
BoundField<T> BindWith(Field field, std::function<nlohmann::json(const T&)> get,
                       std::function<void(T&, const nlohmann::json&)> set) {
  return {std::move(field), std::move(get), std::move(set)};
}

// The field list of an Options struct T (default-constructible).
template <class T>
class FieldList {
 public:
  FieldList() = default;
  FieldList(std::initializer_list<BoundField<T>> fields) : fields_(fields) {}

  FieldList& Add(BoundField<T> f) {
    fields_.push_back(std::move(f));
    return *this;
  }

  // Adds `inner`'s fields, named "prefix.name" (as they are for an empty
  // prefix), reading and writing (t.*member).
  template <class S>
  FieldList& Nest(std::string_view prefix, S T::*member, const FieldList<S>& inner) {
    for (const BoundField<S>& f : inner.bound()) {
      Field field = f.field;
      if (!prefix.empty()) field.name = std::string(prefix) + "." + field.name;
      fields_.push_back({std::move(field), [member, get = f.get](const T& t) { return get(t.*member); },
                         [member, set = f.set](T& t, const nlohmann::json& v) { set(t.*member, v); }});
    }
    return *this;
  }

  // Adds the fields of `inner` named in `names` (in `inner`'s order), named
  // "prefix.name", or as they are for an empty prefix. Throws
  // std::logic_error for a name `inner` lacks.
  template <class S>
  FieldList& Nest(std::string_view prefix, S T::*member, const FieldList<S>& inner,
                  std::initializer_list<std::string_view> names) {
    FieldList<S> some;
    for (std::string_view name : names) {
      bool found = false;
      for (const BoundField<S>& f : inner.bound()) found = found || f.field.name == name;
      if (!found) throw std::logic_error("FieldList::Nest: no field " + std::string(name));
    }
    for (const BoundField<S>& f : inner.bound()) {
      for (std::string_view name : names) {
        if (f.field.name == name) some.Add(f);
      }
    }
    return Nest(prefix, member, some);
  }

  // The fields, each with its default_value read from `defaults`.
  std::vector<Field> Fields(const T& defaults = T{}) const {
    std::vector<Field> out;
    out.reserve(fields_.size());
    for (const BoundField<T>& f : fields_) {
      out.push_back(f.field);
      out.back().default_value = f.get(defaults);
    }
    return out;
  }

  // Writes every value `args` holds for a field of this list into `into`
  // (names it does not hold, and names of other lists, are left alone).
  void Read(const FieldArgs& args, T& into) const {
    for (const BoundField<T>& f : fields_) {
      auto it = args.raw().find(f.field.name);
      if (it != args.raw().end()) f.set(into, *it);
    }
  }
  T FromArgs(const FieldArgs& args) const {
    T t{};
    Read(args, t);
    return t;
  }

  // The values of `t` by field name (unset optional members left out).
  nlohmann::json ToJson(const T& t) const {
    nlohmann::json out = nlohmann::json::object();
    for (const BoundField<T>& f : fields_) {
      nlohmann::json v = f.get(t);
      if (!v.is_null()) out[f.field.name] = std::move(v);
    }
    return out;
  }

  // Throws InvalidArgument naming the first value of `t` outside its
  // field's bounds (FieldValuesProblem): the one statement of every
  // single-field bound, so an Options struct's Check() keeps only the rules
  // that involve several fields.
  void CheckValues(const T& t, std::string_view prefix) const {
    if (auto problem = FieldValuesProblem(Fields(), ToJson(t), prefix)) throw InvalidArgument(*problem);
  }

  const std::vector<BoundField<T>>& bound() const { return fields_; }
  std::size_t size() const { return fields_.size(); }

 private:
  std::vector<BoundField<T>> fields_;
};

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_FIELDS_H_
