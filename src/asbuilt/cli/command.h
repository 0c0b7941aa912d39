#ifndef ASBUILT_CLI_COMMAND_H_
#define ASBUILT_CLI_COMMAND_H_

// The CLI is one table of commands (STYLE.md 12). Each command lives in its
// own file `cli/<name>_command.cc`, parses its flags with CLI11, builds an
// Options struct, calls one library function and prints the summary.
//
// To add a command: write `int Run<Name>Command(int argc, char** argv)` in
// its own file, declare it below and add one row to Commands() in
// command.cc. Errors are thrown (STYLE.md 7); main() maps them to exit codes.

#include <filesystem>
#include <span>
#include <string>
#include <vector>
#include <string_view>

#include <CLI/CLI.hpp>

#include "asbuilt/pano/perspective.h"

namespace asbuilt::cli {

// argv[0] is the command name ("validate"), the rest its arguments.
using CommandFn = int (*)(int argc, char** argv);

struct Command {
  std::string_view name;
  std::string_view summary;  // One line, shown by `asbuilt help`.
  CommandFn run;
};

// The command table, in the order `asbuilt help` lists it.
std::span<const Command> Commands();
const Command* FindCommand(std::string_view name);

// A CLI11 app for a command, with the common flags (--quiet, --verbose)
// already added and wired to the logger.
void AddCommonFlags(CLI::App& app);

// WIDTHxHEIGHT of `flag` into w and h (left alone when `text` is empty);
// throws CLI::ValidationError naming the flag otherwise.
void ParseSizeFlag(const std::string& text, const std::string& flag, int& w, int& h);

// The views of a panorama (TurnInPlaceOptions), shared by `pano views` and
// `eval zind`: --size WxH (into *size, parsed by ApplyTurnInPlaceSize),
// --fx, --fy, --views, --yaw-step, --first-yaw, --pitch; --pano-size,
// --pano-fx, --pano-views and --pano-yaw-step (survey's spellings) too.
void AddTurnInPlaceFlags(CLI::App& app, TurnInPlaceOptions* turn, std::string* size);
void ApplyTurnInPlaceSize(const std::string& size, TurnInPlaceOptions& turn);

// Thrown by Parse() after it printed the help text (main() exits 0).
struct HelpPrinted {};

// Parses argv into `app`. On --help prints the help and throws HelpPrinted;
// on bad flags throws CLI::ParseError, which main() turns into a usage
// error (exit 2).
void Parse(CLI::App& app, int argc, char** argv);

// Expands file arguments: each is a path or a glob pattern (quoted so the
// shell leaves it). Sorted by name, so left/right lists pair up by position.
// Throws CLI::ValidationError naming `flag` when a pattern matches nothing.
std::vector<std::filesystem::path> ExpandFileArgs(const std::vector<std::string>& args, const std::string& flag);

// One declaration per command.
int RunHelpCommand(int argc, char** argv);
int RunSurveyCommand(int argc, char** argv);
int RunDemoCommand(int argc, char** argv);
int RunValidateCommand(int argc, char** argv);
int RunEvalCommand(int argc, char** argv);
int RunPlanCommand(int argc, char** argv);
int RunSceneCommand(int argc, char** argv);
int RunRenderCommand(int argc, char** argv);
// `dataset synth` (dataset_synth_command.cc): adds the subcommand, whose callback runs it.
CLI::App* AddDatasetSynthSubcommand(CLI::App& dataset_app);
int RunTrainCommand(int argc, char** argv);
int RunSegmentCommand(int argc, char** argv);
int RunModelCommand(int argc, char** argv);
int RunExperimentCommand(int argc, char** argv);
int RunLearnCommand(int argc, char** argv);
int RunCalibrateCommand(int argc, char** argv);
int RunRectifyCommand(int argc, char** argv);
int RunDisparityCommand(int argc, char** argv);
int RunPointsCommand(int argc, char** argv);
int RunMcpCommand(int argc, char** argv);
int RunReviewCommand(int argc, char** argv);
int RunLabelsCommand(int argc, char** argv);
int RunDatasetCommand(int argc, char** argv);
int RunClusterCommand(int argc, char** argv);
int RunVersionCommand(int argc, char** argv);
int RunPanoCommand(int argc, char** argv);

}  // namespace asbuilt::cli

#endif  // ASBUILT_CLI_COMMAND_H_
