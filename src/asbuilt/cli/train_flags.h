#ifndef ASBUILT_CLI_TRAIN_FLAGS_H_
#define ASBUILT_CLI_TRAIN_FLAGS_H_

// The training flags `asbuilt train` and `asbuilt experiment ratios` share,
// stated once: TrainOptionFields (seg/train.h) as flags, with the older
// spellings kept (--batch, --warmup, --scale WxH, --no-flip, …).

#include <algorithm>
#include <memory>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "asbuilt/cli/field_flags.h"
#include "asbuilt/seg/train.h"

namespace asbuilt::cli {

class TrainFlags {
 public:
  // Binds the fields to `app`, but those named in `omit` (what a command
  // binds itself or does not use).
  explicit TrainFlags(CLI::App& app, std::vector<std::string_view> omit = {}) {
    std::vector<Field> fields;
    for (Field& f : TrainOptionFields().Fields()) {
      if (std::find(omit.begin(), omit.end(), f.name) == omit.end()) fields.push_back(std::move(f));
    }
    static const std::vector<FlagAlias> kAliases = {
        {"batch_size", "--batch"},
        {"warmup_steps", "--warmup"},
        {"drop_path_rate", "--drop-path"},
        {"val_max_images", "--val-max"},
        {"stop_after_epoch", "--stop-after"},
        {"dist_timeout_s", "--dist-timeout"},
        {"augment.ratio_min", "--ratio-min"},
        {"augment.ratio_max", "--ratio-max"},
        {"augment.flip", "!--no-flip"},
        {"augment.photometric", "!--no-photometric"},
        {"augment.blur_noise", "!--no-blur-noise"},
        {"augment.stray_light_probability", "--stray-light"},
    };
    std::vector<FlagAlias> aliases;
    for (const FlagAlias& a : kAliases) {
      if (std::find(omit.begin(), omit.end(), a.field) == omit.end()) aliases.push_back(a);
    }
    flags_ = std::make_unique<FieldFlags>(app, std::move(fields), std::move(aliases));
    flags_->AddSize("augment.scale_width_px", "augment.scale_height_px", "--scale", "base scale images are fitted to");
    flags_->AddSize("augment.crop_width_px", "augment.crop_height_px", "--crop", "training crop");
  }

  // After parsing: the flags given, over `o` (the defaults, or a recipe
  // such as FinetuneOptions).
  void ReadGiven(TrainOptions& o) const { flags_->ReadGiven(TrainOptionFields(), o); }

 private:
  std::unique_ptr<FieldFlags> flags_;
};

}  // namespace asbuilt::cli

#endif  // ASBUILT_CLI_TRAIN_FLAGS_H_
