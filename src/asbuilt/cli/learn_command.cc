// `asbuilt learn` — surveys corrected in `asbuilt review` become labelled real
// rooms, and the model learns from them (seg/learn.h): mix → fine-tune →
// old vs new on the held-out rooms → the new model only when it is better.

#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/seg/learn.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

int RunLearnCommand(int argc, char** argv) {
  CLI::App app(
      "Learn from corrections: every survey you corrected and saved in `asbuilt review` is a labelled real room.\n"
      "Mixes them with renders (whole rooms held out to judge on), fine-tunes the model on the mix, scores the\n"
      "old and the new model on the held-out rooms and writes OUT/model.pt only when the new one is better.\n"
      "Writes OUT/mix.json, OUT/train/, OUT/report.md and report.json; re-running resumes the fine-tuning.\n"
      "Use the new model with `asbuilt survey --model OUT/model.pt`.",
      "asbuilt learn");
  AddCommonFlags(app);
  LearnOptions o;
  std::vector<std::string> reviews;
  std::string model = "default", synthetic, out, hold_out;
  app.add_option("reviews", reviews,
                 "corrected surveys: survey folders whose review was saved, or folders holding them")
      ->required();
  app.add_option("-o,--out", out, "output folder (e.g. runs/NAME)")->required();
  app.add_option("--model", model, "the model to improve: \"default\", a shipped model's name, or a checkpoint")
      ->capture_default_str();
  app.add_option("--synthetic", synthetic, "renders to mix in (a folder made by `asbuilt dataset synth`)");
  app.add_option("--config", o.config, "the mix: RS5050, RS8020, … (needs --synthetic) or R100")->capture_default_str();
  app.add_option("--test-fraction", o.test_fraction, "share of the rooms held out to judge on")->capture_default_str();
  app.add_option("--hold-out", hold_out, "judge on this review instead (leave-one-room-out: name each room in turn)");
  app.add_option("--epochs", o.epochs, "fine-tuning epochs (0 = the fine-tuning default, 8)")->capture_default_str();
  app.add_option("--steps-per-epoch", o.steps_per_epoch, "steps per epoch (0 = the default, 50)")
      ->capture_default_str();
  app.add_option("--seed", o.seed, "which rooms are held out; training order")->capture_default_str();
  app.add_option("--threads", o.threads, "LibTorch threads (0 = every core)")->capture_default_str();
  Parse(app, argc, argv);

  o.reviews.assign(reviews.begin(), reviews.end());
  o.model = ModelPathFor(model);
  o.synthetic_dir = synthetic;
  o.hold_out = hold_out;
  o.out_dir = out;
  ProgressPrinter printer;
  LearnSummary summary = LearnFromReviews(o, printer.Callback());
  printer.Finish();
  fmt::print("{}\n{}\n→ {}\n", summary.ToMarkdown(), summary.BriefReport(), (o.out_dir / "report.md").string());
  return 0;
}

}  // namespace asbuilt::cli
