#include "asbuilt/cli/field_flags.h"

#include <algorithm>
#include <cstdio>
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
  if (f.exclusive_maximum) notes.push_back(fmt::format("< {}", *f.exclusive_maximum));
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
  target_ = target;
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

void FieldFlags::AddSize(std::string_view width_field, std::string_view height_field, std::string_view names,
                         std::string_view description) {
  auto default_of = [&](std::string_view name) -> const nlohmann::json& {
    for (const Field& f : fields_) {
      if (f.name == name && f.kind == FieldKind::kInteger) return f.default_value;
    }
    throw std::logic_error(fmt::format("FieldFlags::AddSize {}: no integer field {}", names, name));
  };
  const nlohmann::json& w = default_of(width_field);
  const nlohmann::json& h = default_of(height_field);
  SizeFlag& size = sizes_.emplace_back(SizeFlag{std::string(width_field), std::string(height_field)});
  std::string help =
      fmt::format("{}, short for {} W {} H", description, FieldFlagName(width_field), FieldFlagName(height_field));
  if (!w.is_null() && !h.is_null()) help += fmt::format(" [default {}x{}]", w.dump(), h.dump());
  size.option = target_->add_option(std::string(names), size.text, help)->type_name("WxH");
}

nlohmann::json FieldFlags::GivenValues() const {
  nlohmann::json given = nlohmann::json::object();
  std::size_t text_index = 0, flag_index = 0;
  for (std::size_t i = 0; i < fields_.size(); ++i) {
    const Field& f = fields_[i];
    bool is_bool = f.kind == FieldKind::kBool;
    const std::size_t at = is_bool ? flag_index++ : text_index++;
    if (options_[i]->count() == 0) continue;
    given[f.name] = is_bool ? nlohmann::json(flag_[at]) : ToJson(f, text_[at]);
  }
  for (const SizeFlag& size : sizes_) {
    if (size.option->count() == 0) continue;
    const std::string flag = size.option->get_name();
    if (given.contains(size.width_field) || given.contains(size.height_field)) {
      throw CLI::ValidationError(flag, fmt::format("give {} or {} and {}, not both", flag,
                                                   FieldFlagName(size.width_field), FieldFlagName(size.height_field)));
    }
    int w = 0, h = 0;
    char x = 0, rest = 0;
    if (std::sscanf(size.text.c_str(), "%d%c%d%c", &w, &x, &h, &rest) != 3 || (x != 'x' && x != 'X') || w <= 0 ||
        h <= 0) {
      throw CLI::ValidationError(flag,
                                 fmt::format("expected WIDTHxHEIGHT, both > 0 (e.g. 640x480), got '{}'", size.text));
    }
    given[size.width_field] = w;
    given[size.height_field] = h;
  }
  return given;
}

FieldArgs FieldFlags::Args() const {
  const nlohmann::json given = GivenValues();
  try {
    return ParseFieldArgs(fields_, given);
  } catch (const FieldArgsError& e) {
    // "arguments.plan.epsilon_m: …" → "--plan.epsilon-m: …"; a value a WxH
    // flag gave → "--size (its --width-px): …".
    std::vector<std::string> lines;
    for (std::string problem : e.problems()) {
      if (problem.starts_with("arguments.")) {
        const std::size_t colon = problem.find(':');
        const std::string field = problem.substr(10, colon - 10);
        std::string flag = FieldFlagName(field);
        for (const SizeFlag& size : sizes_) {
          if (size.option->count() > 0 && (size.width_field == field || size.height_field == field)) {
            flag = fmt::format("{} (its {})", size.option->get_name(), flag);
          }
        }
        problem = flag + problem.substr(colon);
      }
      lines.push_back(problem);
    }
    throw CLI::ValidationError(fmt::format("{}", fmt::join(lines, "\n")));
  }
}

}  // namespace asbuilt::cli

namespace asbuilt::cli {

std::vector<std::string> FieldFlagArgs(std::span<const Field> fields, const nlohmann::json& values) {
  std::vector<std::string> args;
  for (const Field& f : fields) {
    auto it = values.find(f.name);
    if (it == values.end() || it->is_null()) continue;
    std::string flag = FieldFlagName(f.name);
    if (f.kind == FieldKind::kBool) {
      const std::size_t leaf = flag.rfind('.') == std::string::npos ? 2 : flag.rfind('.') + 1;
      args.push_back(it->get<bool>() ? flag : flag.substr(0, leaf) + "no-" + flag.substr(leaf));
      continue;
    }
    args.push_back(flag);
    if (it->is_string()) {
      args.push_back(it->get<std::string>());
    } else if (it->is_array()) {
      std::vector<std::string> parts;
      for (const nlohmann::json& v : *it) parts.push_back(v.dump());
      args.push_back(fmt::format("{}", fmt::join(parts, ",")));
    } else {
      args.push_back(it->dump());
    }
  }
  return args;
}

}  // namespace asbuilt::cli
