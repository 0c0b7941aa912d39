// asbuilt — the command-line entry point: finds the command in the table and
// maps errors to exit codes (the one place besides the MCP server that
// catches, STYLE.md 7): 0 success, 2 usage/invalid arguments, 1 input or
// runtime failure.

#include <cstdio>
#include <exception>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/log.h"

namespace {

std::string CommandList() {
  std::string out;
  for (const auto& c : asbuilt::cli::Commands()) {
    out += fmt::format("  {:<12} {}\n", c.name, c.summary);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  asbuilt::ConfigureLogging(asbuilt::Verbosity::kNormal);
  if (argc < 2) {
    fmt::print(stderr,
               "usage: asbuilt <command> [options]\n\ncommands:\n{}\n"
               "Run `asbuilt <command> --help` for a command's options.\n",
               CommandList());
    return 2;
  }
  std::string name = argv[1];
  if (name == "--help" || name == "-h") name = "help";
  if (name == "--version") name = "version";
  const asbuilt::cli::Command* command = asbuilt::cli::FindCommand(name);
  if (command == nullptr) {
    fmt::print(stderr, "asbuilt: unknown command '{}'\n\ncommands:\n{}", name, CommandList());
    return 2;
  }
  try {
    return command->run(argc - 1, argv + 1);
  } catch (const asbuilt::cli::HelpPrinted&) {
    return 0;
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "asbuilt {}: {}\nRun `asbuilt {} --help` for usage.\n", name, e.what(), name);
    return 2;
  } catch (const asbuilt::InvalidArgument& e) {
    fmt::print(stderr, "asbuilt {}: {}\n", name, e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "asbuilt {}: {}\n", name, e.what());
    return 1;
  }
}
