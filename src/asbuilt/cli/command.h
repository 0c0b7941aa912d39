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
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "asbuilt/cli/field_flags.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/seg/segmenter.h"

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

// The views of a panorama (TurnInPlaceOptionFields) as flags, shared by
// `pano views` and `eval zind`: --width-px … --pitch-deg, with --size WxH and
// the older spellings (--yaw-step, --first-yaw, --pitch; survey's --pano-size,
// --pano-fx, --pano-views, --pano-yaw-step). Read the options after parsing
// with ReadGiven(TurnInPlaceOptionFields(), turn).
std::unique_ptr<FieldFlags> AddTurnInPlaceFlags(CLI::App& app, const TurnInPlaceOptions& defaults,
                                                std::string_view group = {});

// The segmenter's options (SegmentOptionFields) as flags: --mode,
// --scale-width-px and --scale-height-px (WxH as `scale_names`), and
// --batch-size (--batch) when `with_batch`. Read them after parsing with
// ReadGiven(SegmentOptionFields(), options).
std::unique_ptr<FieldFlags> AddSegmentFlags(CLI::App& app, const SegmentOptions& defaults,
                                            std::string_view scale_names = "--scale", bool with_batch = true);

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
