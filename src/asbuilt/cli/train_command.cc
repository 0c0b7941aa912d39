// `asbuilt train` — trains SegFormer on a manifest or image/label folders
// (seg/train.h): checkpoints, logs and a plot in -o, resumable after a kill;
// with --distributed, one rank of a data-parallel run (`srun -n K`).

#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "asbuilt/cli/command.h"
#include "asbuilt/cli/train_flags.h"
#include "asbuilt/pipeline/survey.h"
#include "asbuilt/seg/segformer_config.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/seg/train.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/log.h"
#include "asbuilt/util/progress.h"

namespace asbuilt::cli {

int RunTrainCommand(int argc, char** argv) {
  CLI::App app(
      "Train the SegFormer segmenter (walls, doors, windows) with AdamW, poly schedule, augmentation,\n"
      "validation each epoch and atomic checkpoints; re-running the same command resumes after a kill.\n"
      "Writes OUT/options.json, last.pt, best.pt, log.csv, log.jsonl, plot.png.",
      "asbuilt train");
  AddCommonFlags(app);
  std::string manifest, images, labels, out, init, finetune;
  bool no_resume = false, distributed = false;
  app.add_option("--manifest", manifest, "dataset manifest.json (train/val pairs)");
  app.add_option("--images", images, "image folder (or a dataset folder when --labels is absent)");
  app.add_option("--labels", labels, "label folder (PNG, same stems as the images)");
  app.add_option("-o,--out", out, "output folder for checkpoints and logs")->required();
  TrainFlags flags(app);
  app.add_option("--init", init,
                 "initial weights: an asbuilt checkpoint (mismatched tensors skipped); with --arch tflite a .tflite "
                 "file or an asbuilt-tflite checkpoint");
  app.add_option("--finetune", finetune,
                 "continue from MODEL (a shipped model's name, \"default\", or a checkpoint): its architecture, "
                 "scale and crop, lr 3e-5 (TFLite: 5e-5, head x10), 8 epochs of 50 steps, batch 8; flags given "
                 "here win")
      ->excludes("--init")
      ->excludes("--arch");
  app.add_flag("--no-resume", no_resume, "start afresh even if OUT/last.pt exists");
  app.add_flag("--distributed", distributed,
               "data-parallel training: this process is one rank of `srun -n K` (SLURM_PROCID, SLURM_NTASKS, "
               "SLURM_STEP_NODELIST) or of RANK, WORLD_SIZE, MASTER_ADDR, MASTER_PORT; --batch is the global "
               "batch (divisible by K); rank 0 writes every file");
  int check_ranks = 0;
  app.add_option("--check-flags", check_ranks,
                 "check the flags and options for a run of K ranks (1: one process), then stop without reading\n"
                 "data or training (asbuilt cluster train does so before it submits)");
  Parse(app, argc, argv);

  // The recipe: the defaults, or the model's to fine-tune; the flags given win.
  TrainOptions o;
  if (!finetune.empty()) {
    const std::filesystem::path model = ModelPathFor(finetune);
    o = FinetuneOptions(model, ReadSegmenterInfo(model));
    init = o.init.string();
  }
  flags.ReadGiven(o);
  o.manifest = manifest;
  o.images_dir = images;
  o.labels_dir = labels;
  o.out_dir = out;
  o.init = init;
  o.resume = !no_resume;
  if (check_ranks > 0) {
    o.distributed.world_size = check_ranks;  // A stand-in rendezvous: only the options are checked.
    o.distributed.master_addr = "localhost";
    o.distributed.master_port = 1;
    o.Check();
    fmt::print("asbuilt train: the flags hold for {} rank(s)\n", check_ranks);
    return 0;
  }
  if (distributed) {
    const double timeout_s = o.distributed.timeout_s;
    o.distributed = DistributedOptionsFromEnvironment();
    o.distributed.timeout_s = timeout_s;
  }
  const bool rank0 = o.distributed.rank == 0;
  if (!rank0) ConfigureLogging(Verbosity::kQuiet);  // Only rank 0 reports; every rank's errors name it.

#ifdef ASBUILT_SEG_NO_TORCH
  throw Error("asbuilt train: this build has no LibTorch (configured with ASBUILT_WITH_TORCH=OFF)");
#else
  if (!rank0) {
    TrainSegmenter(o);
    return 0;
  }
  ProgressPrinter printer;
  TrainSummary summary = TrainSegmenter(o, printer.Callback());
  printer.Finish();
  fmt::print("{}\n", summary.BriefReport());
  return 0;
#endif
}

}  // namespace asbuilt::cli
