#include "asbuilt/cli/option_tables.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "asbuilt/pano/pano_layout.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/plan/plan_options.h"
#include "asbuilt/render/capture_render.h"
#include "asbuilt/render/dataset_synth.h"
#include "asbuilt/scene/procedural.h"
#include "asbuilt/scene/scene_text.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/seg/train.h"
#include "asbuilt/stereo/frame_points_options.h"
#include "asbuilt/util/error.h"

namespace asbuilt::cli {

const std::vector<OptionTable>& OptionTables() {
  static const std::vector<OptionTable> kTables = {
      {"SceneTextOptions", "scene/scene_text.h", "`asbuilt scene text --NAME`; MCP `scene_from_text`",
       SceneTextOptionFields().Fields()},
      {"RandomSceneOptions", "scene/procedural.h", "`asbuilt scene random --NAME`; MCP `random_scene`",
       RandomSceneOptionFields().Fields()},
      {"RenderOptions", "render/renderer.h",
       "through `CaptureRenderOptions` and `DatasetSynthOptions` (the seed is each one's own)",
       RenderOptionFields().Fields()},
      {"CaptureRenderOptions", "render/capture_render.h", "`asbuilt render --NAME`; MCP `render_capture`",
       CaptureRenderOptionFields().Fields()},
      {"DatasetSynthOptions", "render/dataset_synth.h",
       "`asbuilt dataset synth --NAME` and `asbuilt cluster synth --NAME` (`--size WxH`, `--spp`, `--effects`, "
       "`--rig-share`, `--no-indirect` too)",
       DatasetSynthOptionFields().Fields()},
      {"TrainOptions", "seg/train.h",
       "`asbuilt train --NAME` and `asbuilt experiment ratios --NAME` (`--batch`, `--warmup`, `--drop-path`, "
       "`--val-max`, `--stop-after`, `--dist-timeout`, `--scale WxH`, `--crop WxH`, `--ratio-min`, `--ratio-max`, "
       "`--no-flip`, `--no-photometric`, `--no-blur-noise`, `--stray-light` too)",
       TrainOptionFields().Fields()},
      {"AugmentOptions", "seg/seg_data.h", "through `TrainOptions` as `augment.NAME`", AugmentOptionFields().Fields()},
      {"SegmentOptions", "seg/segmenter.h",
       "`asbuilt segment --NAME` and `asbuilt eval seg --NAME` (`--scale WxH`, `--batch` too); `asbuilt eval zind` "
       "(`--seg-scale WxH`)",
       SegmentOptionFields().Fields()},
      {"TurnInPlaceOptions", "pano/perspective.h",
       "`asbuilt pano views --NAME` and `asbuilt eval zind --NAME` (`--size WxH`, `--yaw-step`, `--first-yaw`, "
       "`--pitch` too); `asbuilt survey --pano.NAME` (`--pano-size WxH`, `--pano-fx`, `--pano-views`, "
       "`--pano-yaw-step`)",
       TurnInPlaceOptionFields().Fields()},
      {"FramePointsOptions", "stereo/frame_points_options.h", "`asbuilt points --NAME`; `asbuilt survey --points.NAME`",
       FramePointsOptionFields().Fields()},
      {"PanoLayoutOptions", "pano/pano_layout.h", "`asbuilt survey --layout.NAME`", PanoLayoutOptionFields().Fields()},
      {"PlanOptions", "plan/plan_options.h", "`asbuilt plan --NAME`; `asbuilt survey --plan.NAME`",
       PlanOptionFields().Fields()},
  };
  return kTables;
}

std::string OptionTableMarkdown(std::string_view name) {
  std::vector<std::string_view> names;
  for (const OptionTable& t : OptionTables()) {
    if (t.name == name) {
      return fmt::format("`{}` ({}): {}.\n\n{}", t.name, t.header, t.flags, FieldsMarkdown(t.fields, "field"));
    }
    names.push_back(t.name);
  }
  throw InvalidArgument(fmt::format("no options named '{}'; known: {}", name, fmt::join(names, ", ")));
}

}  // namespace asbuilt::cli
