#ifndef ASBUILT_CLI_FIELD_FLAGS_H_
#define ASBUILT_CLI_FIELD_FLAGS_H_

// CLI flags built from a field list (STYLE.md 13; mcp/option_fields.h), so a
// command and the MCP tool sharing an Options struct take the same options
// with the same bounds, defaults and descriptions:
//
//   field `samples_per_pixel` → --samples-per-pixel N (+ field.cli_names, e.g. --spp)
//   kBool field `normals`     → --normals / --no-normals
//   kPoint2/3, kColor, kNumberList → comma-separated numbers ("1.2,0.3")
//
//   FieldFlags flags(*app, mcp::CaptureRenderOptionFields());
//   Parse(app, argc, argv);
//   CaptureRenderOptions options = mcp::CaptureRenderOptionsFromArgs(flags.Args());

#include <deque>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "asbuilt/mcp/tool_args.h"

namespace asbuilt::cli {

// The flag name of a field: "--" + name with '_' → '-'.
std::string FieldFlagName(std::string_view field_name);

class FieldFlags {
 public:
  // Adds one flag per field to `app`, which must outlive this object's use.
  FieldFlags(CLI::App& app, std::vector<mcp::ToolField> fields);
  FieldFlags(const FieldFlags&) = delete;
  FieldFlags& operator=(const FieldFlags&) = delete;

  // After parsing: the given flags plus defaults, validated against the
  // fields. Throws CLI::ValidationError naming every bad flag
  // ("--samples-per-pixel: must be >= 1, got 0"), which main() reports as a
  // usage error.
  mcp::ToolArgs Args() const;

  const std::vector<mcp::ToolField>& fields() const { return fields_; }

 private:
  std::vector<mcp::ToolField> fields_;
  std::vector<CLI::Option*> options_;
  std::deque<std::string> text_;  // Non-bool values as typed.
  std::deque<bool> flag_;         // Bool values.
};

}  // namespace asbuilt::cli

#endif  // ASBUILT_CLI_FIELD_FLAGS_H_
