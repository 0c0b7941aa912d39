#ifndef ASBUILT_MCP_TOOL_ARGS_H_
#define ASBUILT_MCP_TOOL_ARGS_H_

// One field list per tool (STYLE.md 13): the same list builds the tool's JSON
// Schema (tools/list) and validates and reads its arguments (tools/call), so
// the two can never diverge. Validation collects every problem with its
// argument path ("arguments.width_m: must be > 0, got -2") so the LLM on the
// other side can fix all of them at once.
//
//   const ToolField kFields[] = {
//       {.name = "width_m", .type = ArgType::kNumber, .description = "…",
//        .exclusive_minimum = 0, .maximum = 100},
//   };
//   nlohmann::json schema = ToolInputSchema(kFields);
//   ToolArgs args = ParseToolArgs(kFields, arguments);   // throws ToolArgsError
//   double w = args.Number("width_m");

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/util/error.h"

namespace asbuilt::mcp {

enum class ArgType {
  kNumber,       // Finite number.
  kInteger,      // Whole number.
  kString,
  kBool,
  kEnum,         // One of `choices` (a string).
  kPoint2,       // [x, y], finite numbers.
  kPoint3,       // [x, y, z].
  kColor,        // [r, g, b], each in [0, 1].
  kPolygon,      // [[x, y], ...], between min_items and max_items points.
  kNumberList,   // [n, ...], between min_items and max_items finite numbers.
};

struct ToolField {
  std::string_view name;
  ArgType type = ArgType::kNumber;
  std::string_view description;
  bool required = false;
  // Numbers (and each element of kNumberList): bounds, inclusive unless
  // exclusive_minimum is used.
  std::optional<double> minimum;
  std::optional<double> exclusive_minimum;
  std::optional<double> maximum;
  // kPolygon / kNumberList: element count bounds.
  std::size_t min_items = 0;
  std::size_t max_items = 0;  // 0: no limit.
  // kEnum: the allowed values.
  std::vector<std::string_view> choices;
  // kString: maximum length in bytes (0: no limit).
  std::size_t max_length = 0;
  // Shown in the schema as "default" (and used by ToolArgs when absent).
  nlohmann::json default_value = nullptr;
  // Where a CLI command shares the list (cli/field_flags.h): the flag is
  // always --name-with-dashes (and --no-name for a kBool); these are extra
  // CLI11 names kept for short or older spellings ("--spp", "!--no-indirect").
  std::string_view cli_names;
};

// The JSON Schema (draft 2020-12 subset) of a tool's `arguments` object:
// properties with types, bounds, enums, defaults and descriptions;
// `required`; additionalProperties false.
nlohmann::json ToolInputSchema(std::span<const ToolField> fields);

// Bad tool arguments; what() lists every problem, one per line, each naming
// the argument ("arguments.wall: must be an integer >= 0, got -1").
class ToolArgsError : public InvalidArgument {
 public:
  explicit ToolArgsError(std::vector<std::string> problems);
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

// Validated arguments of one call. Accessors take a field name from the list;
// an absent optional field reads as its default (or nullopt for the Opt*
// accessors when there is none).
class ToolArgs {
 public:
  bool Has(std::string_view name) const;
  double Number(std::string_view name) const;
  std::optional<double> OptNumber(std::string_view name) const;
  std::int64_t Integer(std::string_view name) const;
  std::optional<std::int64_t> OptInteger(std::string_view name) const;
  std::string String(std::string_view name) const;  // Also kEnum.
  std::optional<std::string> OptString(std::string_view name) const;
  bool Bool(std::string_view name) const;
  std::vector<double> Numbers(std::string_view name) const;  // Point, colour, list.
  std::vector<std::vector<double>> Points(std::string_view name) const;  // Polygon.

  const nlohmann::json& raw() const { return values_; }

 private:
  friend ToolArgs ParseToolArgs(std::span<const ToolField>, const nlohmann::json&);
  const nlohmann::json& Get(std::string_view name) const;
  nlohmann::json values_ = nlohmann::json::object();  // Given values + defaults.
};

// Validates `arguments` (an object, or null for none) against the field list.
// Unknown arguments are errors (they are usually typos an LLM should fix).
// Throws ToolArgsError listing every problem.
ToolArgs ParseToolArgs(std::span<const ToolField> fields, const nlohmann::json& arguments);

// Markdown table of the fields (name, type, default, description) for
// docs/mcp.md, generated from the same list.
std::string ToolFieldsMarkdown(std::span<const ToolField> fields);

}  // namespace asbuilt::mcp

#endif  // ASBUILT_MCP_TOOL_ARGS_H_
