#ifndef ASBUILT_CLI_TRAIN_FLAGS_H_
#define ASBUILT_CLI_TRAIN_FLAGS_H_

// The training flags `asbuilt train` and `asbuilt experiment ratios` share,
// stated once: the architecture, the schedule, the image scale and crop, the
// augmentation switches, validation and threads.

#include <string>

#include <CLI/CLI.hpp>

#include "asbuilt/cli/command.h"
#include "asbuilt/seg/train.h"

namespace asbuilt::cli {

// What the flags hold that is not a TrainOptions field as it is.
struct TrainFlags {
  std::string scale, crop;  // WxH; empty: the options' own.
  bool no_photometric = false, no_blur_noise = false;

  // Binds the shared flags to `o` (defaults shown from `o` as it is).
  void Add(CLI::App& app, TrainOptions& o) {
    app.add_option("--arch", o.arch,
                   "architecture: b0, b1, b2, tiny, or tflite (fine-tunes the TFLite network of --init)")
        ->capture_default_str();
    app.add_option("--epochs", o.epochs, "epochs (paper: 50)")->capture_default_str();
    app.add_option("--steps-per-epoch", o.steps_per_epoch, "steps per epoch; 0 = one pass over the data")
        ->capture_default_str();
    app.add_option("--batch", o.batch_size, "batch size (paper: 2)")->capture_default_str();
    app.add_option("--lr", o.lr, "AdamW learning rate (paper: 1e-4)")->capture_default_str();
    app.add_option("--weight-decay", o.weight_decay, "AdamW weight decay (paper: 1e-3)")->capture_default_str();
    app.add_option("--warmup", o.warmup_steps, "linear warm-up steps")->capture_default_str();
    app.add_option("--scale", scale, "base scale WxH images are fitted to (default 256x192)");
    app.add_option("--crop", crop, "training crop WxH (default 192x192)");
    app.add_flag("--no-photometric", no_photometric, "no photometric distortion");
    app.add_flag("--no-blur-noise", no_blur_noise, "no blur / noise augmentation");
    app.add_option("--val-max", o.val_max_images, "validate on at most N images (0 = all)")->capture_default_str();
    app.add_option("--threads", o.threads, "LibTorch threads (0 = every core)")->capture_default_str();
  }

  // The scale, crop and switches into `o` (throws on a bad WxH).
  void Apply(TrainOptions& o) const {
    ParseSizeFlag(scale, "--scale", o.augment.scale_width_px, o.augment.scale_height_px);
    ParseSizeFlag(crop, "--crop", o.augment.crop_width_px, o.augment.crop_height_px);
    o.augment.photometric = !no_photometric;
    o.augment.blur_noise = !no_blur_noise;
  }
};

}  // namespace asbuilt::cli

#endif  // ASBUILT_CLI_TRAIN_FLAGS_H_
