#include <fmt/format.h>

#include "asbuilt/cli/command.h"

namespace asbuilt::cli {

int RunHelpCommand(int argc, char** argv) {
  CLI::App app("List the commands, or show one command's help.", "asbuilt help");
  std::string topic;
  app.add_option("command", topic, "command to describe");
  Parse(app, argc, argv);
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
      "\nRun `asbuilt <command> --help` for a command's options.\n"
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
