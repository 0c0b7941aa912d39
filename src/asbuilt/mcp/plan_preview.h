#ifndef ASBUILT_MCP_PLAN_PREVIEW_H_
#define ASBUILT_MCP_PLAN_PREVIEW_H_

// A top-down picture of a scene for render_preview: floor, walls with their
// thickness, doors (gap, leaf and swing), windows (glazing lines), furniture
// footprints, lights, the stereo rig and the direction of each view, wall
// numbers with lengths, a north arrow and a scale bar. Lets an LLM (or a
// person) check a scene at a glance before rendering anything. Drawn as
// overlay primitives on a plan sheet of its own (plan/sheet.h; a scene is
// more than a plan: hinge sides, furniture, lights) and rasterised by the
// drawings' PNG serialiser (plan/sheet_cairo.h).

#include <string>

#include "asbuilt/scene/scene.h"

namespace asbuilt::mcp {

struct PlanPreviewOptions {
  int width_px = 768;        // Image width; the height follows the scene's aspect.
  int max_height_px = 1536;  // Cap on the height (tall scenes are scaled down).
  int margin_px = 48;        // Around the drawing (room for labels).
  bool wall_labels = true;   // "0: 6.00 m" beside each wall.
  bool view_rays = true;     // One short ray per viewpoint from the rig.

  // Throws InvalidArgument naming the field ("PlanPreviewOptions.width_px = 10, must be in 64..4096").
  void Check() const;
};

// PNG bytes of the picture. A scene without rooms gives a picture with a
// note saying so.
std::string RenderPlanPreviewPng(const Scene& scene, const PlanPreviewOptions& options = {});

}  // namespace asbuilt::mcp

#endif  // ASBUILT_MCP_PLAN_PREVIEW_H_
