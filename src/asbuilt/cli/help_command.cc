#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cli/option_tables.h"

namespace asbuilt::cli {

int RunHelpCommand(int argc, char** argv) {
  CLI::App app("List the commands, or show one command's help.", "asbuilt help");
  std::string topic, options_name;
  app.add_option("command", topic, "command to describe, or `options` for every option's table (Markdown)");
  app.add_option("name", options_name, "with `options`: only this struct's table (e.g. PlanOptions)");
  Parse(app, argc, argv);
  if (topic == "options") {
    if (!options_name.empty()) {
      fmt::print("{}", OptionTableMarkdown(options_name));
      return 0;
    }
    for (const OptionTable& t : OptionTables()) fmt::print("## {}\n\n{}\n", t.name, OptionTableMarkdown(t.name));
    return 0;
  }
  if (!options_name.empty()) throw CLI::ValidationError("name", "only `asbuilt help options` takes a second word");
  if (!topic.empty()) {
    const Command* c = FindCommand(topic);
    if (c == nullptr) {
      throw CLI::ValidationError("command", fmt::format("unknown command '{}'", topic));
    }
    std::string flag = "--help";
    char* args[] = {const_cast<char*>(c->name.data()), flag.data()};
    return c->run(2, args);
  }
  fmt::print(
      "asbuilt — dimensioned as-built floor plans from stereo photos of rooms,\n"
      "and the labelled synthetic data to train its segmenter.\n\n"
      "usage: asbuilt <command> [options]\n\ncommands:\n");
  for (const Command& c : Commands()) fmt::print("  {:<12} {}\n", c.name, c.summary);
  fmt::print(
      "\nRun `asbuilt <command> --help` for a command's options, `asbuilt help options` for every\n"
      "option with its bounds and default.\n"
      "Exit codes: 0 success, 1 bad input or failure, 2 usage error.\n");
  return 0;
}

int RunVersionCommand(int argc, char** argv) {
  CLI::App app("Print the version.", "asbuilt version");
  Parse(app, argc, argv);
  fmt::print("asbuilt {}\n", ASBUILT_VERSION);
  return 0;
}

}  // namespace asbuilt::cli
