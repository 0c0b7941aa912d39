// `asbuilt dataset synth -o DIR --count N --seed S [--shard i/N]` — the
// synthetic training set (render/dataset_synth.h). Registered by
// dataset_command.cc as one subcommand of `asbuilt dataset`.

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/render/dataset_synth.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

CLI::App* AddDatasetSynthSubcommand(CLI::App& dataset_app) {
  CLI::App* synth = dataset_app.add_subcommand(
      "synth",
      "random rooms rendered as labelled training items: images/ labels/ idmaps/ depth/ meta/ (NNNNNN);\n"
      "deterministic per item, so shards never overlap; re-running skips finished items");
  struct Flags {
    std::string out, shard, size, levers;
    std::vector<std::string> photo_dirs;
    DatasetSynthOptions options;
    bool no_resume = false, no_indirect = false;
  };
  auto flags = std::make_shared<Flags>();
  synth->add_option("-o,--out", flags->out, "output folder")->required();
  synth->add_option("--count", flags->options.count, "items in the whole dataset")->capture_default_str();
  synth->add_option("--seed", flags->options.seed, "scenes, views and rendering seed")->capture_default_str();
  synth->add_option("--shard", flags->shard, "render only shard i of N (i/N, 0-based)");
  synth->add_option("--size", flags->size, "image size WxH")->default_str("320x240");
  synth->add_option("--spp", flags->options.render.samples_per_pixel, "RGB samples per pixel")->capture_default_str();
  synth->add_option("--effects", flags->options.render.camera_effects, "camera effects strength [0, 1]")
      ->capture_default_str();
  synth->add_option("--id-drift", flags->options.render.id_drift, "ID-map colour drift [0, 1]")->capture_default_str();
  synth->add_option("--rig-share", flags->options.rig_view_share, "share of level rig views")->capture_default_str();
  synth->add_option("--items-per-scene", flags->options.items_per_scene, "consecutive items per room")
      ->capture_default_str();
  synth
      ->add_option("--levers", flags->levers,
                   fmt::format("realism levers: all, none or a comma list of {}\n(\"all,-sunlight\" turns "
                               "one off); docs/render.md \"Realism levers\"",
                               fmt::join(SynthLeverNames(), ", ")))
      ->default_str("none");
  synth->add_option("--photo-dir", flags->photo_dirs,
                    "folder of photos for photo_textures/outside_photos (repeatable; replaces the Debian\n"
                    "defaults: /usr/share/gimp/2.0/patterns, /usr/share/blender/datafiles/studiolights/world)");
  synth->add_flag("--no-indirect", flags->no_indirect, "direct light only (faster)");
  synth->add_flag("--no-resume", flags->no_resume, "re-render items that already exist");
  synth->callback([synth, flags] {
    DatasetSynthOptions& o = flags->options;
    if (!flags->shard.empty() && std::sscanf(flags->shard.c_str(), "%d/%d", &o.shard_index, &o.shard_count) != 2) {
      throw CLI::ValidationError("--shard", fmt::format("'{}' is not i/N (e.g. 0/4)", flags->shard));
    }
    if (!flags->size.empty() && (std::sscanf(flags->size.c_str(), "%dx%d", &o.width_px, &o.height_px) != 2 ||
                                 o.width_px <= 0 || o.height_px <= 0)) {
      throw CLI::ValidationError("--size", fmt::format("'{}' is not WxH (e.g. 320x240)", flags->size));
    }
    if (!flags->levers.empty()) o.levers = ParseSynthLevers(flags->levers);
    if (!flags->photo_dirs.empty()) o.photo_dirs.assign(flags->photo_dirs.begin(), flags->photo_dirs.end());
    o.resume = !flags->no_resume;
    o.render.indirect_light = !flags->no_indirect;
    o.Check();
    ProgressPrinter printer;
    DatasetSynthSummary summary = SynthesizeDataset(flags->out, o, printer.Callback());
    printer.Finish();
    fmt::print("{}\n", summary.BriefReport());
    (void)synth;
  });
  return synth;
}

}  // namespace asbuilt::cli
