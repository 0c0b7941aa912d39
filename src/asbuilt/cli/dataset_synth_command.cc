// `asbuilt dataset synth -o DIR --count N --seed S [--shard i/N]` — the
// synthetic training set (render/dataset_synth.h). Registered by
// dataset_command.cc as one subcommand of `asbuilt dataset`; its flags are
// also `asbuilt cluster synth`'s, which hands them on to every array task.

#include "asbuilt/cli/dataset_synth_flags.h"

#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

void AddDatasetSynthFlags(CLI::App& app, DatasetSynthFlags& flags) {
  DatasetSynthOptions& o = flags.options;
  app.add_option("--count", o.count, "items in the whole dataset")->capture_default_str();
  app.add_option("--seed", o.seed, "scenes, views and rendering seed")->capture_default_str();
  app.add_option("--size", flags.size, "image size WxH")->default_str("320x240");
  app.add_option("--spp", o.render.samples_per_pixel, "RGB samples per pixel")->capture_default_str();
  app.add_option("--effects", o.render.camera_effects, "camera effects strength [0, 1]")->capture_default_str();
  app.add_option("--id-drift", o.render.id_drift, "ID-map colour drift [0, 1]")->capture_default_str();
  app.add_option("--rig-share", o.rig_view_share, "share of level rig views")->capture_default_str();
  app.add_option("--items-per-scene", o.items_per_scene, "consecutive items per room")->capture_default_str();
  app.add_option("--levers", flags.levers,
                 fmt::format("realism levers: all, none or a comma list of {}\n(\"all,-sunlight\" turns "
                             "one off); docs/render.md \"Realism levers\"",
                             fmt::join(SynthLeverNames(), ", ")))
      ->default_str("none");
  app.add_option("--photo-dir", flags.photo_dirs,
                 "folder of photos for photo_textures/outside_photos (repeatable; replaces the Debian\n"
                 "defaults: /usr/share/gimp/2.0/patterns, /usr/share/blender/datafiles/studiolights/world)");
  app.add_flag("--no-indirect", flags.no_indirect, "direct light only (faster)");
  app.add_flag("--layout-labels", o.render.layout_labels,
               "label by the layout rule, as reviews and ZInD do: furniture and door leaves before a wall are\n"
               "wall (docs/seg.md); default: what the ray meets first");
}

DatasetSynthOptions ResolveDatasetSynthFlags(const DatasetSynthFlags& flags) {
  DatasetSynthOptions o = flags.options;
  if (!flags.size.empty() && (std::sscanf(flags.size.c_str(), "%dx%d", &o.width_px, &o.height_px) != 2 ||
                              o.width_px <= 0 || o.height_px <= 0)) {
    throw CLI::ValidationError("--size", fmt::format("'{}' is not WxH (e.g. 320x240)", flags.size));
  }
  if (!flags.levers.empty()) o.levers = ParseSynthLevers(flags.levers);
  if (!flags.photo_dirs.empty()) o.photo_dirs.assign(flags.photo_dirs.begin(), flags.photo_dirs.end());
  o.render.indirect_light = !flags.no_indirect;
  o.Check();
  return o;
}

std::vector<std::string> DatasetSynthArgs(const DatasetSynthOptions& o) {
  std::vector<std::string> args = {"--count",
                                   std::to_string(o.count),
                                   "--seed",
                                   std::to_string(o.seed),
                                   "--size",
                                   fmt::format("{}x{}", o.width_px, o.height_px),
                                   "--spp",
                                   std::to_string(o.render.samples_per_pixel),
                                   "--effects",
                                   fmt::format("{}", o.render.camera_effects),
                                   "--id-drift",
                                   fmt::format("{}", o.render.id_drift),
                                   "--rig-share",
                                   fmt::format("{}", o.rig_view_share),
                                   "--items-per-scene",
                                   std::to_string(o.items_per_scene),
                                   "--levers",
                                   o.levers.ToString()};
  if (o.levers.photo_textures || o.levers.outside_photos) {
    for (const auto& dir : o.photo_dirs) args.insert(args.end(), {"--photo-dir", dir.string()});
  }
  if (!o.render.indirect_light) args.push_back("--no-indirect");
  if (o.render.layout_labels) args.push_back("--layout-labels");
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
