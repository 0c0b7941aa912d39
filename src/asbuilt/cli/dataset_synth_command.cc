// `asbuilt dataset synth -o DIR --count N --seed S [--shard i/N]` — the
// synthetic training set (render/dataset_synth.h). Registered by
// dataset_command.cc as one subcommand of `asbuilt dataset`; its flags are
// also `asbuilt cluster synth`'s, which hands them on to every array task.

#include "asbuilt/cli/dataset_synth_flags.h"

#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

void AddDatasetSynthFlags(CLI::App& app, DatasetSynthFlags& flags) {
  flags.fields = std::make_unique<FieldFlags>(app, DatasetSynthOptionFields().Fields(),
                                              std::vector<FlagAlias>{{"samples_per_pixel", "--spp"},
                                                                     {"camera_effects", "--effects"},
                                                                     {"rig_view_share", "--rig-share"},
                                                                     {"indirect_light", "!--no-indirect"}});
  flags.fields->AddSize("width_px", "height_px", "--size", "image size");
  app.add_option("--photo-dir", flags.photo_dirs,
                 "folder of photos for photo_textures/outside_photos (repeatable; replaces the Debian\n"
                 "defaults: /usr/share/gimp/2.0/patterns, /usr/share/blender/datafiles/studiolights/world)");
}

DatasetSynthOptions ResolveDatasetSynthFlags(const DatasetSynthFlags& flags) {
  DatasetSynthOptions o;
  flags.fields->Read(DatasetSynthOptionFields(), o);
  if (!flags.photo_dirs.empty()) o.photo_dirs.assign(flags.photo_dirs.begin(), flags.photo_dirs.end());
  o.Check();
  return o;
}

std::vector<std::string> DatasetSynthArgs(const DatasetSynthOptions& o) {
  std::vector<std::string> args =
      FieldFlagArgs(DatasetSynthOptionFields().Fields(), DatasetSynthOptionFields().ToJson(o));
  if (o.levers.photo_textures || o.levers.outside_photos) {
    for (const auto& dir : o.photo_dirs) args.insert(args.end(), {"--photo-dir", dir.string()});
  }
  return args;
}

CLI::App* AddDatasetSynthSubcommand(CLI::App& dataset_app) {
  CLI::App* synth = dataset_app.add_subcommand(
      "synth",
      "random rooms rendered as labelled training items: images/ labels/ idmaps/ depth/ meta/ (NNNNNN);\n"
      "deterministic per item, so shards never overlap; re-running skips finished items. DIR/synth.json\n"
      "records the options: a folder made with other options is refused");
  struct Flags {
    std::string out, shard;
    bool no_resume = false, resume = false;
    DatasetSynthFlags synth;
  };
  auto flags = std::make_shared<Flags>();
  synth->add_option("-o,--out", flags->out, "output folder")->required();
  synth->add_option("--shard", flags->shard, "render only shard i of N (i/N, 0-based)");
  AddDatasetSynthFlags(*synth, flags->synth);
  synth->add_flag("--no-resume", flags->no_resume, "re-render items that already exist");
  synth->add_flag("--resume", flags->resume, "skip items already complete (the default; for scripts that say so)")
      ->excludes("--no-resume");
  synth->callback([flags] {
    DatasetSynthOptions o = ResolveDatasetSynthFlags(flags->synth);
    if (!flags->shard.empty()) {
      const Shard shard = ParseShard(flags->shard);
      o.shard_index = shard.index;
      o.shard_count = shard.count;
    }
    o.resume = !flags->no_resume;
    o.Check();
    ProgressPrinter printer;
    DatasetSynthSummary summary = SynthesizeDataset(flags->out, o, printer.Callback());
    printer.Finish();
    fmt::print("{}\n", summary.BriefReport());
  });
  return synth;
}

}  // namespace asbuilt::cli
