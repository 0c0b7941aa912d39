#ifndef ASBUILT_CLI_DATASET_SYNTH_FLAGS_H_
#define ASBUILT_CLI_DATASET_SYNTH_FLAGS_H_

// The flags of `asbuilt dataset synth` that make a dataset's items (not -o,
// --shard, resume), stated once for `dataset synth` and `cluster synth`.

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "asbuilt/render/dataset_synth.h"

namespace asbuilt::cli {

struct DatasetSynthFlags {
  DatasetSynthOptions options;
  std::string size, levers;
  std::vector<std::string> photo_dirs;
  bool no_indirect = false;
};

void AddDatasetSynthFlags(CLI::App& app, DatasetSynthFlags& flags);
// The options the flags give (checked). Throws CLI::ValidationError or InvalidArgument.
DatasetSynthOptions ResolveDatasetSynthFlags(const DatasetSynthFlags& flags);
// Flags that give `options` back through AddDatasetSynthFlags (what a
// cluster's array task runs with).
std::vector<std::string> DatasetSynthArgs(const DatasetSynthOptions& options);

}  // namespace asbuilt::cli

#endif  // ASBUILT_CLI_DATASET_SYNTH_FLAGS_H_
