// `asbuilt experiment ratios …` — the paper's real/synthetic ratio experiment
// (seg/experiment.h); `asbuilt experiment toy-rooms …` — a quick labelled set
// from seg/'s toy-room ray caster (tests, smoke runs, bootstrapping).

#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cli/train_flags.h"
#include "asbuilt/seg/experiment.h"
#include "asbuilt/seg/toy_rooms.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

int RunExperimentCommand(int argc, char** argv) {
  CLI::App app("Segmentation experiments.", "asbuilt experiment");
  AddCommonFlags(app);
  app.require_subcommand(1);

  CLI::App* ratios = app.add_subcommand(
      "ratios",
      "train and evaluate one segmenter per real/synthetic mix (R100, S100, RS5050, RS8020, …) on the same\n"
      "held-out real test set; writes OUT/results.md (the paper's table), results.json and plot.png");
  RatioExperimentOptions r;
  std::string real, synthetic, real_test, out, configs = "R100,S100,RS5050,RS8020";
  std::vector<std::string> extra_tests;
  ratios->add_option("--real", real, "dataset folder of real annotated photos");
  ratios->add_option("--synthetic", synthetic, "dataset folder of synthetic views");
  ratios->add_option("--real-test", real_test, "explicit real test folder (default: hold out 10 % of --real)");
  ratios->add_option("--extra-test", extra_tests,
                     "further labelled dataset folder every config is also scored on (repeatable), e.g. real\n"
                     "photos when --real is a stand-in from another domain");
  ratios->add_option("--configs", configs, "comma-separated mixes")->capture_default_str();
  ratios->add_option("--total", r.total, "train + val pairs per config (0 = as many as allowed)")
      ->capture_default_str();
  ratios->add_option("-o,--out", out, "output folder")->required();
  // The seed is the mix's too; each config splits its own validation set.
  TrainFlags flags(*ratios, {"seed", "val_fraction", "stop_after_epoch", "dist_timeout_s"});
  ratios->add_option("--init", r.train.init, "initial weights for every config");
  ratios->add_option("--seed", r.seed, "mix and training seed")->capture_default_str();

  CLI::App* toy = app.add_subcommand("toy-rooms", "write N labelled toy-room views: OUT/images, OUT/labels");
  std::string toy_out;
  int count = 100;
  ToyRoomOptions t;
  toy->add_option("-o,--out", toy_out, "output folder")->required();
  toy->add_option("--count", count, "views")->capture_default_str()->check(CLI::PositiveNumber);
  toy->add_option("--seed", t.seed, "seed")->capture_default_str();
  toy->add_option("--width", t.width_px, "width, px")->capture_default_str();
  toy->add_option("--height", t.height_px, "height, px")->capture_default_str();
  Parse(app, argc, argv);

  ProgressPrinter printer;
  if (ratios->parsed()) {
#ifdef ASBUILT_SEG_NO_TORCH
    throw Error("asbuilt experiment ratios: this build has no LibTorch (configured with ASBUILT_WITH_TORCH=OFF)");
#else
    r.real_dir = real;
    r.synthetic_dir = synthetic;
    r.real_test_dir = real_test;
    for (const std::string& e : extra_tests) r.extra_test_dirs.emplace_back(e);
    flags.ReadGiven(r.train);
    r.out_dir = out;
    r.train.seed = r.seed;
    r.configs.clear();
    for (size_t start = 0; start <= configs.size();) {
      size_t comma = configs.find(',', start);
      if (comma == std::string::npos) comma = configs.size();
      if (comma > start) r.configs.push_back(configs.substr(start, comma - start));
      start = comma + 1;
    }
    RatioExperimentSummary s = RunRatioExperiment(r, printer.Callback());
    printer.Finish();
    fmt::print("{}{}\n", s.ToMarkdown(), s.BriefReport());
    return 0;
#endif
  }
  int n = WriteToyRoomSet(toy_out, count, t, printer.Callback());
  printer.Finish();
  fmt::print("wrote {} toy-room views to {}\n", n, toy_out);
  return 0;
}

}  // namespace asbuilt::cli
