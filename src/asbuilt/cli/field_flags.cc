#include "asbuilt/cli/field_flags.h"

#include <algorithm>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace asbuilt::cli {
namespace {

std::string TypeName(FieldKind type) {
  switch (type) {
    case FieldKind::kInteger:
      return "INT";
    case FieldKind::kNumber:
      return "FLOAT";
    case FieldKind::kString:
      return "TEXT";
    case FieldKind::kEnum:
      return "CHOICE";
    case FieldKind::kPoint2:
      return "X,Y";
    case FieldKind::kPoint3:
      return "X,Y,Z";
    case FieldKind::kColor:
      return "R,G,B";
    case FieldKind::kNumberList:
      return "N,...";
    case FieldKind::kPolygon:
      return "JSON";
    case FieldKind::kBool:
      return "";
  }
  return "";
}

// The help line: description, then range and default.
std::string HelpText(const Field& f) {
  std::string text(f.description);
  std::vector<std::string> notes;
  if (f.kind == FieldKind::kEnum) notes.push_back(fmt::format("one of {}", fmt::join(f.choices, ", ")));
  if (f.exclusive_minimum) notes.push_back(fmt::format("> {}", *f.exclusive_minimum));
  if (f.minimum) notes.push_back(fmt::format(">= {}", *f.minimum));
  if (f.maximum) notes.push_back(fmt::format("<= {}", *f.maximum));
  if (!f.default_value.is_null()) notes.push_back(fmt::format("default {}", f.default_value.dump()));
  if (!notes.empty()) text += fmt::format(" [{}]", fmt::join(notes, "; "));
  return text;
}

// A flag's text as the JSON value ParseToolArgs checks; a text that is not
// even of the right shape becomes a string, so the check names the flag.
nlohmann::json ToJson(const Field& f, const std::string& text) {
  auto number = [](std::string_view s) -> nlohmann::json {
    nlohmann::json v = nlohmann::json::parse(s.begin(), s.end(), nullptr, false);
    return v.is_number() ? v : nlohmann::json(std::string(s));
  };
  switch (f.kind) {
    case FieldKind::kNumber:
    case FieldKind::kInteger:
      return number(text);
    case FieldKind::kPoint2:
    case FieldKind::kPoint3:
    case FieldKind::kColor:
    case FieldKind::kNumberList: {
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
    case FieldKind::kPolygon: {
      nlohmann::json v = nlohmann::json::parse(text, nullptr, false);
      return v.is_discarded() ? nlohmann::json(text) : v;
    }
    default:
      return text;
  }
}

}  // namespace

std::string FieldFlagName(std::string_view field_name) {
  std::string flag = "--" + std::string(field_name);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

FieldFlags::FieldFlags(CLI::App& app, std::vector<Field> fields, std::vector<FlagAlias> aliases, std::string_view group)
    : fields_(std::move(fields)) {
  for (const FlagAlias& a : aliases) {
    if (std::none_of(fields_.begin(), fields_.end(), [&](const Field& f) { return f.name == a.field; })) {
      throw std::logic_error(fmt::format("FlagAlias {}: no field {}", a.names, a.field));
    }
  }
  CLI::App* target = group.empty() ? &app : app.add_option_group(std::string(group));
  for (const Field& f : fields_) {
    std::string names = FieldFlagName(f.name);
    std::string extra;
    for (const FlagAlias& a : aliases) {
      if (a.field == f.name) extra += "," + std::string(a.names);
    }
    if (f.kind == FieldKind::kBool) {
      // "--points.use-corners" → "--points.no-use-corners".
      const std::size_t leaf = names.rfind('.') == std::string::npos ? 2 : names.rfind('.') + 1;
      names += ",!" + names.substr(0, leaf) + "no-" + names.substr(leaf) + extra;
      bool& value = flag_.emplace_back(f.default_value.is_boolean() && f.default_value.get<bool>());
      options_.push_back(target->add_flag(names, value, HelpText(f)));
    } else {
      names += extra;
      std::string& value = text_.emplace_back();
      CLI::Option* option = target->add_option(names, value, HelpText(f))->type_name(TypeName(f.kind));
      if (f.required) option->required();
      options_.push_back(option);
    }
  }
}

FieldArgs FieldFlags::Args() const {
  nlohmann::json given = nlohmann::json::object();
  std::size_t text_index = 0, flag_index = 0;
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    const Field& f = fields_[i];
    bool is_bool = f.kind == FieldKind::kBool;
    const std::size_t at = is_bool ? flag_index++ : text_index++;
    if (options_[i]->count() == 0) continue;
    given[f.name] = is_bool ? nlohmann::json(flag_[at]) : ToJson(f, text_[at]);
  }
  try {
    return ParseFieldArgs(fields_, given);
  } catch (const FieldArgsError& e) {
    // "arguments.plan.epsilon_m: …" → "--plan.epsilon-m: …".
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
