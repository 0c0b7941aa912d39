#include "asbuilt/cli/field_flags.h"

#include <algorithm>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace asbuilt::cli {
namespace {

using mcp::ArgType;
using mcp::ToolField;

std::string TypeName(ArgType type) {
  switch (type) {
    case ArgType::kInteger: return "INT";
    case ArgType::kNumber: return "FLOAT";
    case ArgType::kString: return "TEXT";
    case ArgType::kEnum: return "CHOICE";
    case ArgType::kPoint2: return "X,Y";
    case ArgType::kPoint3: return "X,Y,Z";
    case ArgType::kColor: return "R,G,B";
    case ArgType::kNumberList: return "N,...";
    case ArgType::kPolygon: return "JSON";
    case ArgType::kBool: return "";
  }
  return "";
}

// The help line: description, then range and default.
std::string HelpText(const ToolField& f) {
  std::string text(f.description);
  std::vector<std::string> notes;
  if (f.type == ArgType::kEnum) notes.push_back(fmt::format("one of {}", fmt::join(f.choices, ", ")));
  if (f.exclusive_minimum) notes.push_back(fmt::format("> {}", *f.exclusive_minimum));
  if (f.minimum) notes.push_back(fmt::format(">= {}", *f.minimum));
  if (f.maximum) notes.push_back(fmt::format("<= {}", *f.maximum));
  if (!f.default_value.is_null()) notes.push_back(fmt::format("default {}", f.default_value.dump()));
  if (!notes.empty()) text += fmt::format(" [{}]", fmt::join(notes, "; "));
  return text;
}

// A flag's text as the JSON value ParseToolArgs checks; a text that is not
// even of the right shape becomes a string, so the check names the flag.
nlohmann::json ToJson(const ToolField& f, const std::string& text) {
  auto number = [](std::string_view s) -> nlohmann::json {
    nlohmann::json v = nlohmann::json::parse(s.begin(), s.end(), nullptr, false);
    return v.is_number() ? v : nlohmann::json(std::string(s));
  };
  switch (f.type) {
    case ArgType::kNumber:
    case ArgType::kInteger: return number(text);
    case ArgType::kPoint2:
    case ArgType::kPoint3:
    case ArgType::kColor:
    case ArgType::kNumberList: {
      nlohmann::json list = nlohmann::json::array();
      std::string_view rest = text;
      while (true) {
        std::size_t comma = rest.find(',');
        list.push_back(number(rest.substr(0, comma)));
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
      }
      return list;
    }
    case ArgType::kPolygon: {
      nlohmann::json v = nlohmann::json::parse(text, nullptr, false);
      return v.is_discarded() ? nlohmann::json(text) : v;
    }
    default: return text;
  }
}

}  // namespace

std::string FieldFlagName(std::string_view field_name) {
  std::string flag = "--" + std::string(field_name);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

FieldFlags::FieldFlags(CLI::App& app, std::vector<ToolField> fields) : fields_(std::move(fields)) {
  for (const ToolField& f : fields_) {
    std::string names = FieldFlagName(f.name);
    if (f.type == ArgType::kBool) {
      names += ",!--no-" + names.substr(2);
      if (!f.cli_names.empty()) names += "," + std::string(f.cli_names);
      bool& value = flag_.emplace_back(f.default_value.is_boolean() && f.default_value.get<bool>());
      options_.push_back(app.add_flag(names, value, HelpText(f)));
    } else {
      if (!f.cli_names.empty()) names += "," + std::string(f.cli_names);
      std::string& value = text_.emplace_back();
      CLI::Option* option = app.add_option(names, value, HelpText(f))->type_name(TypeName(f.type));
      if (f.required) option->required();
      options_.push_back(option);
    }
  }
}

mcp::ToolArgs FieldFlags::Args() const {
  nlohmann::json given = nlohmann::json::object();
  std::size_t text_index = 0, flag_index = 0;
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    const ToolField& f = fields_[i];
    bool is_bool = f.type == ArgType::kBool;
    const std::size_t at = is_bool ? flag_index++ : text_index++;
    if (options_[i]->count() == 0) continue;
    given[std::string(f.name)] = is_bool ? nlohmann::json(flag_[at]) : ToJson(f, text_[at]);
  }
  try {
    return mcp::ParseToolArgs(fields_, given);
  } catch (const mcp::ToolArgsError& e) {
    // "arguments.samples_per_pixel: …" → "--samples-per-pixel: …".
    std::vector<std::string> lines;
    for (std::string problem : e.problems()) {
      if (problem.starts_with("arguments.")) {
        std::size_t colon = problem.find(':');
        problem = FieldFlagName(problem.substr(10, colon - 10)) + problem.substr(colon);
      }
      lines.push_back(problem);
    }
    throw CLI::ValidationError(fmt::format("{}", fmt::join(lines, "\n")));
  }
}

}  // namespace asbuilt::cli
