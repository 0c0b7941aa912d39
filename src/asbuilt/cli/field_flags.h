#ifndef ASBUILT_CLI_FIELD_FLAGS_H_
#define ASBUILT_CLI_FIELD_FLAGS_H_

// CLI flags built from a field list (STYLE.md 13; util/fields.h), so a
// command takes every option of its Options struct with the bounds, defaults
// and descriptions of the list, and a command and the MCP tool sharing an
// Options struct take the same options:
//
//   field `samples_per_pixel`          → --samples-per-pixel N
//   nested `plan.epsilon_m`            → --plan.epsilon-m X
//   kBool field `normals`              → --normals / --no-normals
//   kBool `points.use_corners`         → --points.use-corners / --points.no-use-corners
//   kPoint2/3, kColor, kNumberList     → comma-separated numbers ("1.2,0.3")
//
//   FieldFlags flags(app, CaptureRenderOptionFields().Fields(), {{"samples_per_pixel", "--spp"}});
//   Parse(app, argc, argv);
//   CaptureRenderOptions options;
//   flags.Read(CaptureRenderOptionFields(), options);

#include <deque>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "asbuilt/util/fields.h"

namespace asbuilt::cli {

// The flag name of a field: "--" + name with '_' → '-' ("--plan.epsilon-m").
std::string FieldFlagName(std::string_view field_name);

// An extra CLI name of a field's flag, kept for shorter or older spellings
// that scripts use: {"samples_per_pixel", "--spp"}; for a kBool field,
// "!--no-indirect" sets it false. Several names: "--a,--b".
struct FlagAlias {
  std::string_view field;
  std::string_view names;
};

class FieldFlags {
 public:
  // Adds one flag per field to `app` (to an option group of that title when
  // `group` is not empty, so --help lists them together); `app` must outlive
  // this object's use. Throws std::logic_error for an alias of no field.
  FieldFlags(CLI::App& app, std::vector<Field> fields, std::vector<FlagAlias> aliases = {},
             std::string_view group = {});
  FieldFlags(const FieldFlags&) = delete;
  FieldFlags& operator=(const FieldFlags&) = delete;

  // A WIDTHxHEIGHT flag for two integer fields at once (`--size 640x480` for
  // width_px and height_px), before parsing. Given together with either
  // field's own flag, it is refused.
  void AddSize(std::string_view width_field, std::string_view height_field, std::string_view names,
               std::string_view description);

  // After parsing: the given flags plus defaults, validated against the
  // fields. Throws CLI::ValidationError naming every bad flag
  // ("--plan.epsilon-m: must be > 0, got -1"), which main() reports as a
  // usage error.
  FieldArgs Args() const;

  // After parsing: writes the given flags (and the defaults of the others)
  // of `list`'s fields into `into`. Throws like Args().
  template <class T>
  void Read(const FieldList<T>& list, T& into) const {
    list.Read(Args(), into);
  }

  // After parsing: writes only the flags given (validated as Args()) into
  // `into`, leaving the rest as `into` has them: flags over a recipe the
  // command chose (`train --finetune`).
  template <class T>
  void ReadGiven(const FieldList<T>& list, T& into) const {
    const FieldArgs args = Args();
    const nlohmann::json given = GivenValues();
    for (const BoundField<T>& f : list.bound()) {
      if (given.contains(f.field.name)) f.set(into, args.raw().at(f.field.name));
    }
  }

  const std::vector<Field>& fields() const { return fields_; }

 private:
  struct SizeFlag {
    std::string width_field, height_field;
    CLI::Option* option = nullptr;
    std::string text;
  };
  nlohmann::json GivenValues() const;  // By field name, as typed (sizes split).

  CLI::App* target_ = nullptr;
  std::deque<SizeFlag> sizes_;
  std::vector<Field> fields_;
  std::vector<CLI::Option*> options_;
  std::deque<std::string> text_;  // Non-bool values as typed.
  std::deque<bool> flag_;         // Bool values.
};

// The command-line words that give `values` (by field name, as
// FieldList::ToJson writes them) to a command binding `fields` with
// FieldFlags: {"--count", "100", "--no-resume", …}, every value given, in
// the fields' order. How a Slurm task gets its options.
std::vector<std::string> FieldFlagArgs(std::span<const Field> fields, const nlohmann::json& values);

}  // namespace asbuilt::cli

#endif  // ASBUILT_CLI_FIELD_FLAGS_H_
