#ifndef ASBUILT_CLI_DATASET_SYNTH_FLAGS_H_
#define ASBUILT_CLI_DATASET_SYNTH_FLAGS_H_

// The flags of `asbuilt dataset synth` that make a dataset's items (not -o,
// --shard, resume), stated once for `dataset synth` and `cluster synth`:
// DatasetSynthOptionFields as flags, with the older spellings (--size WxH,
// --spp, --effects, --rig-share, --no-indirect), and --photo-dir.

#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "asbuilt/cli/field_flags.h"
#include "asbuilt/render/dataset_synth.h"

namespace asbuilt::cli {

struct DatasetSynthFlags {
  std::unique_ptr<FieldFlags> fields;
  std::vector<std::string> photo_dirs;
};

void AddDatasetSynthFlags(CLI::App& app, DatasetSynthFlags& flags);
// The options the flags give (checked). Throws CLI::ValidationError or InvalidArgument.
DatasetSynthOptions ResolveDatasetSynthFlags(const DatasetSynthFlags& flags);
// Flags that give `options` back through AddDatasetSynthFlags (what a
// cluster's array task runs with).
std::vector<std::string> DatasetSynthArgs(const DatasetSynthOptions& options);

}  // namespace asbuilt::cli

#endif  // ASBUILT_CLI_DATASET_SYNTH_FLAGS_H_
