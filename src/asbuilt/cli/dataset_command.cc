// `asbuilt dataset <synth|merge|verify|mix|check|level-views>` — training sets: rendered
// synthetic items (synth: dataset_synth_command.cc) and their one manifest
// once every shard is in (merge, verify), real/synthetic mixes with a
// held-out real test list, validation of (image, label) pairs, and a
// panorama's tall views cut into level ones (dataset/, docs/dataset.md,
// docs/cluster.md).

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/dataset/check.h"
#include "asbuilt/dataset/level_views.h"
#include "asbuilt/dataset/mix.h"
#include "asbuilt/dataset/synth_merge.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

int RunDatasetCommand(int argc, char** argv) {
  CLI::App app(
      "Training sets (docs/dataset.md).\n"
      "  mix    real + synthetic pairs at a ratio (R100, S100, RS5050, RS8020, RS2080, RSxxyy) → manifest.json\n"
      "  check  validate every (image, label) pair of a dataset folder or manifest; class histograms\n"
      "  synth  random rooms rendered as labelled training items (images/ labels/ idmaps/ depth/ meta/)\n"
      "  merge  a synth folder's shards → synth_manifest.json (every item's files and SHA-256)\n"
      "  verify re-hash every file of a merged synth folder against its manifest\n"
      "  level-views  a panorama's tall views (a saved review's training/) cut into 4:3 level views",
      "asbuilt dataset");
  AddCommonFlags(app);
  app.require_subcommand(1);

  // mix
  CLI::App* mix = app.add_subcommand("mix", "real + synthetic → manifest.json (train / val / held-out real test)");
  std::vector<std::string> mix_real;
  std::string mix_synth, mix_test, mix_out;
  MixOptions mix_options;
  bool no_checksums = false;
  mix->add_option("--real", mix_real,
                  "real dataset folder (images/ + labels/, at any depth); repeat it for several, e.g. survey "
                  "folders whose reviews were saved (OUT/review/training/). Test rooms are held out whole");
  mix->add_option("--synthetic", mix_synth,
                  "synthetic dataset folder (left/ + labels/ captures, or images/ + labels/)");
  mix->add_option("--test", mix_test, "explicit real test folder (default: hold out --test-fraction of --real)");
  mix->add_option("--config", mix_options.config, "R100, S100, RS5050, RS8020, RS2080 or any RSxxyy")
      ->capture_default_str();
  mix->add_option("--total", mix_options.total, "train + val pairs (0 = as many as the ratio allows)")
      ->capture_default_str();
  mix->add_option("--split", mix_options.split, "train fraction (the rest is val; 0.9 = the paper's 9:1)")
      ->capture_default_str();
  mix->add_option("--test-fraction", mix_options.test_fraction, "fraction of real pairs held out for test")
      ->capture_default_str();
  mix->add_option("--seed", mix_options.seed, "selection and order seed")->capture_default_str();
  mix->add_flag("--no-checksums", no_checksums, "do not record SHA-256 of the files (faster)");
  mix->add_option("--threads", mix_options.num_threads, "worker threads (0 = all cores)")->capture_default_str();
  mix->add_option("-o,--output", mix_out, "manifest file to write")->required();

  // check
  CLI::App* check = app.add_subcommand("check", "validate pairs, print class histograms");
  std::string check_path;
  DatasetCheckOptions check_options;
  check->add_option("path", check_path, "dataset folder or manifest.json")->required();
  check->add_option("--threads", check_options.num_threads, "worker threads (0 = all cores)")->capture_default_str();

  // merge, verify
  CLI::App* merge = app.add_subcommand(
      "merge", "every item of a synth folder there and whole → DIR/synth_manifest.json (files and SHA-256)");
  std::string merge_dir;
  SynthMergeOptions merge_options;
  merge->add_option("dir", merge_dir, "folder written by dataset synth (all its shards)")->required();
  merge->add_option("--shards", merge_options.shard_count, "the run's shard count, to name a shard's missing items");
  merge->add_option("--threads", merge_options.num_threads, "hashing threads (0 = all cores)")->capture_default_str();
  CLI::App* verify = app.add_subcommand("verify", "re-hash every file of a merged synth folder against its manifest");
  std::string verify_dir;
  int verify_threads = 0;
  verify->add_option("dir", verify_dir, "folder with synth_manifest.json")->required();
  verify->add_option("--threads", verify_threads, "hashing threads (0 = all cores)")->capture_default_str();

  // level-views
  CLI::App* level = app.add_subcommand(
      "level-views",
      "cut each tall image of IN (a panorama's level views, as OUT/review/training/ holds them) and its label into\n"
      "three 4:3 windows across its width around its horizon: level views at the renders' scale (docs/dataset.md)");
  std::string level_in, level_out;
  level->add_option("in", level_in, "folder with images/ + labels/")->required();
  level->add_option("-o,--output", level_out, "output folder (images/ + labels/)")->required();

  // synth (render/): runs from its callback during Parse.
  CLI::App* synth = AddDatasetSynthSubcommand(app);

  Parse(app, argc, argv);
  if (synth->parsed()) return 0;

  if (mix->parsed()) {
    mix_options.checksums = !no_checksums;
    mix_options.Check();
    if (mix_real.empty() && mix_synth.empty()) {
      throw CLI::ValidationError("--real/--synthetic", "give at least one of --real and --synthetic");
    }
    ProgressPrinter printer;
    const std::vector<std::filesystem::path> real_dirs(mix_real.begin(), mix_real.end());
    MixSummary summary = MixDataset(mix_options, real_dirs, mix_synth, mix_test, mix_out, printer.Callback());
    printer.Finish();
    fmt::print("{}\nwrote {}\n", summary.BriefReport(), mix_out);
    return 0;
  }
  if (level->parsed()) {
    const LevelViewsSummary summary = CutLevelViews(level_in, level_out);
    fmt::print("{} tall views cut into {} level views, {} kept as they were → {}\n", summary.tall, 3 * summary.tall,
               summary.skipped, level_out);
    return 0;
  }
  if (merge->parsed()) {
    ProgressPrinter printer;
    SynthMergeSummary summary = MergeSynthDataset(merge_dir, merge_options, printer.Callback());
    printer.Finish();
    fmt::print("{}\n", summary.BriefReport());
    return 0;
  }
  if (verify->parsed()) {
    ProgressPrinter printer;
    SynthVerifySummary summary = VerifySynthDataset(verify_dir, verify_threads, printer.Callback());
    printer.Finish();
    for (const Problem& p : summary.problems) fmt::print(stderr, "{}\n", p.ToString());
    fmt::print("{}\n", summary.BriefReport());
    return summary.ok() ? 0 : 1;
  }
  if (check->parsed()) {
    check_options.Check();
    ProgressPrinter printer;
    DatasetCheckSummary summary = CheckDataset(check_options, check_path, printer.Callback());
    printer.Finish();
    for (const Problem& p : summary.problems) fmt::print(stderr, "{}\n", p.ToString());
    fmt::print("{}\n", summary.BriefReport());
    fmt::print("{}", summary.HistogramTable());
    return summary.ok() ? 0 : 1;
  }
  return 2;
}

}  // namespace asbuilt::cli
