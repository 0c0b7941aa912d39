// Parts of train.h that need no LibTorch: options, records, the summary.
// They live in the host's seg library; TrainSegmenter itself is in the
// LibTorch plugin (torch_plugin.h).

#include <cmath>

#include <fmt/format.h>

#include "asbuilt/seg/segformer_config.h"
#include "asbuilt/seg/train.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

nlohmann::json Num(double x) { return std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x); }

}  // namespace

const FieldList<TrainOptions>& TrainOptionFields() {
  using O = TrainOptions;
  static const FieldList<O> kList = [] {
    FieldList<O> list = {
        BindChoice(&O::arch, {.name = "arch",
                              .description = "Architecture: b0, b1, b2 (published SegFormer), tiny (b0, decoder 128), "
                                             "or tflite (fine-tunes the TFLite network of `init`).",
                              .choices = {"b0", "b1", "b2", "tiny", "tflite"}}),
        Bind(&O::num_classes, {.name = "num_classes",
                               .description = "Classes the head predicts (asbuilt's labels: 4).",
                               .minimum = 2.0,
                               .maximum = 255.0}),
        Bind(&O::epochs, {.name = "epochs", .description = "Epochs (paper: 50).", .minimum = 1.0}),
        Bind(&O::steps_per_epoch, {.name = "steps_per_epoch",
                                   .description = "Steps per epoch; 0 = one pass over the training pairs.",
                                   .minimum = 0.0}),
        Bind(&O::batch_size, {.name = "batch_size",
                              .description = "Batch size (paper: 2); with K ranks the global batch.",
                              .minimum = 1.0}),
        Bind(&O::lr, {.name = "lr", .description = "AdamW learning rate (paper: 1e-4).", .exclusive_minimum = 0.0}),
        Bind(&O::weight_decay,
             {.name = "weight_decay", .description = "AdamW weight decay (paper: 1e-3).", .minimum = 0.0}),
        Bind(&O::head_lr_mult, {.name = "head_lr_mult",
                                .description = "Decoder learning-rate multiplier (mmseg SegFormer: 10).",
                                .exclusive_minimum = 0.0}),
        Bind(&O::warmup_steps, {.name = "warmup_steps",
                                .description = "Linear warm-up steps from warmup_ratio x lr; 0 = none.",
                                .minimum = 0.0}),
        Bind(&O::warmup_ratio, {.name = "warmup_ratio",
                                .description = "Share of lr the warm-up starts from.",
                                .minimum = 0.0,
                                .maximum = 1.0}),
        Bind(&O::poly_power, {.name = "poly_power",
                              .description = "Poly schedule: lr = base x (1 - step/total)^power.",
                              .minimum = 0.0}),
        Bind(&O::drop_path_rate, {.name = "drop_path_rate",
                                  .description = "Stochastic depth rate.",
                                  .minimum = 0.0,
                                  .exclusive_maximum = 1.0}),
        Bind(&O::val_fraction, {.name = "val_fraction",
                                .description = "Image folders only: share held out for validation.",
                                .minimum = 0.0,
                                .exclusive_maximum = 1.0}),
        Bind(&O::val_max_images, {.name = "val_max_images",
                                  .description = "Validate on at most this many images (0 = all).",
                                  .minimum = 0.0}),
        Bind(
            &O::seed,
            {.name = "seed", .description = "Split, sampling order, augmentation and initialisation.", .minimum = 0.0}),
        Bind(&O::stop_after_epoch, {.name = "stop_after_epoch",
                                    .description = "End this run after that epoch (0 = run to `epochs`); the "
                                                   "schedule still spans `epochs`.",
                                    .minimum = 0.0}),
        Bind(&O::threads,
             {.name = "threads", .description = "LibTorch intra-op threads (0 = every core).", .minimum = 0.0}),
        Bind(&O::distributed, &DistributedOptions::timeout_s,
             {.name = "dist_timeout_s",
              .description = "Seconds a rank waits for the others (rendezvous, each exchange) before it fails.",
              .exclusive_minimum = 0.0}),
    };
    list.Nest("augment", &O::augment, AugmentOptionFields());
    return list;
  }();
  return kList;
}

void TrainOptions::Check() const {
  CheckArgument(!out_dir.empty(), "TrainOptions.out_dir is empty: give an output folder (-o)");
  CheckArgument(!manifest.empty() || !images_dir.empty(),
                "TrainOptions: give a manifest (--manifest) or an image folder (--images [--labels])");
  CheckArgument(manifest.empty() || images_dir.empty(), "TrainOptions: give --manifest or --images, not both");
  TrainOptionFields().CheckValues(*this, "TrainOptions");
  if (arch == "tflite") {
    CheckArgument(!init.empty(),
                  "TrainOptions.arch = tflite fine-tunes a TFLite graph: give it with --init "
                  "(a .tflite file or an asbuilt-tflite checkpoint)");
    CheckArgument(num_classes == 4, fmt::format("TrainOptions.num_classes = {}: a TFLite graph is trained on "
                                                "asbuilt's 4 classes",
                                                num_classes));
  } else {
    SegformerConfigFor(arch, num_classes);  // Throws for an unknown arch.
  }
  augment.Check();
  distributed.Check();
  CheckArgument(batch_size % distributed.world_size == 0,
                fmt::format("TrainOptions.batch_size = {} is the global batch: it must be divisible by the {} "
                            "ranks of --distributed (each reads an equal share)",
                            batch_size, distributed.world_size));
}

TrainOptions FinetuneOptions(const std::filesystem::path& model, const SegmenterInfo& info) {
  TrainOptions o;
  o.init = model;
  o.arch = info.config.arch;
  o.num_classes = info.config.num_classes;
  if (info.scale_width_px > 0 && info.metadata.value("format", "") != "tflite") {
    o.augment.scale_width_px = info.scale_width_px;
    o.augment.scale_height_px = info.scale_height_px;
    o.augment.crop_width_px = info.crop_width_px;
    o.augment.crop_height_px = info.crop_height_px;
  } else {  // A .tflite file read as it is: fine-tune at the scale of asbuilt's views.
    o.augment.scale_width_px = 320, o.augment.scale_height_px = 240;
    o.augment.crop_width_px = 256, o.augment.crop_height_px = 256;
  }
  o.epochs = 8;
  o.steps_per_epoch = 50;
  o.batch_size = 8;
  o.warmup_steps = 30;
  if (o.arch == "tflite") {
    o.lr = 5e-5;  // The head at 10×; 1e-4 left each held-out CC0 room worse in learn (docs/seg.md).
    o.head_lr_mult = 10;
  } else {
    o.lr = 3e-5;  // 1e-4 cost the renders-only B0 3–15 points on rendered rooms in 300 steps.
    o.head_lr_mult = 1;
  }
  return o;
}

nlohmann::json TrainOptions::ToJson() const {
  return {{"manifest", manifest.string()},
          {"images_dir", images_dir.string()},
          {"labels_dir", labels_dir.string()},
          {"val_fraction", val_fraction},
          {"out_dir", out_dir.string()},
          {"arch", arch},
          {"num_classes", num_classes},
          {"epochs", epochs},
          {"steps_per_epoch", steps_per_epoch},
          {"batch_size", batch_size},
          {"lr", lr},
          {"weight_decay", weight_decay},
          {"head_lr_mult", head_lr_mult},
          {"warmup_steps", warmup_steps},
          {"warmup_ratio", warmup_ratio},
          {"poly_power", poly_power},
          {"drop_path_rate", drop_path_rate},
          {"augment",
           {{"scale", {augment.scale_width_px, augment.scale_height_px}},
            {"ratio_range", {augment.ratio_min, augment.ratio_max}},
            {"crop", {augment.crop_width_px, augment.crop_height_px}},
            {"cat_max_ratio", augment.cat_max_ratio},
            {"flip", augment.flip},
            {"photometric", augment.photometric},
            {"blur_noise", augment.blur_noise},
            {"stray_light_probability", augment.stray_light_probability}}},
          {"val_max_images", val_max_images},
          {"seed", seed},
          {"init", init.string()},
          {"resume", resume},
          {"stop_after_epoch", stop_after_epoch},
          {"threads", threads},
          {"distributed", distributed.ToJson()}};
}

nlohmann::json EpochRecord::ToJson() const {
  return {{"epoch", epoch},
          {"step", step},
          {"lr", lr},
          {"train_loss", Num(train_loss)},
          {"val_mIoU", Num(val_miou)},
          {"val_mFscore", Num(val_mfscore)},
          {"val_mPrecision", Num(val_mprecision)},
          {"val_mRecall", Num(val_mrecall)},
          {"val_aAcc", Num(val_aacc)},
          {"wall_s", wall_s}};
}

std::string TrainSummary::BriefReport() const {
  return fmt::format(
      "{} epoch{} ({} steps, {} train / {} val pairs{}), loss {:.4f} → {:.4f}, best val mIoU {} "
      "(epoch {}), {:.0f} s{} → {}",
      epochs_done, epochs_done == 1 ? "" : "s", steps, train_pairs, val_pairs,
      resumed_from_epoch > 0 ? fmt::format(", resumed after epoch {}", resumed_from_epoch) : "", first_loss, last_loss,
      std::isnan(best_miou) ? "n/a" : fmt::format("{:.4f}", best_miou), best_epoch, wall_s, stopped ? " (stopped)" : "",
      out_dir.string());
}

}  // namespace asbuilt
