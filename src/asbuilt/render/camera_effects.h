#ifndef ASBUILT_RENDER_CAMERA_EFFECTS_H_
#define ASBUILT_RENDER_CAMERA_EFFECTS_H_

// What a real camera does to light before it becomes an 8-bit image:
// exposure, white balance, vignetting, tone curve, slight blur, sensor noise
// and JPEG artefacts — drawn at random per view (domain randomisation).

#include <cstdint>
#include <string>

#include "asbuilt/geometry/rig.h"
#include "asbuilt/imageio/image.h"

namespace asbuilt {

struct ViewEffects {
  double exposure = 1.0;              // Multiplier on the automatic exposure.
  Vec3 white_balance = Vec3::Ones();  // Per-channel gains (linear RGB).
  double vignetting = 0.0;            // Light lost in the image corners, [0, 1).
  double blur_sigma_px = 0.0;         // Gaussian blur (defocus, lens softness).
  double noise_sigma = 0.0;           // Sensor noise at mid-grey, in [0, 1] units.
  int jpeg_quality = 0;               // 0: none; else JPEG round trip at this quality.
  // A phone's processing (RandomViewEffects with phone = true):
  double chromatic_aberration_px = 0.0;  // Lateral: red and blue scaled about the centre, shifted
                                         // this far at the image corner (sub-pixel colour fringes,
                                         // geometry of green, hence labels, unchanged).
  double sharpen = 0.0;                  // Unsharp-mask amount (σ 1 px).
  double saturation = 1.0;               // Colour saturation multiplier.

  std::string ToString() const;
};

// Effects drawn from `seed`; `strength` ∈ [0, 1] scales how far they stray
// from a clean image (0 gives ViewEffects{}). `phone` adds a phone's
// processing, drawn after the others (which it leaves as phone = false draws
// them): exposure ±0.8 stops instead of ±0.45, noise up to 2.5× stronger, JPEG
// quality 35–95 on 85 % of views, chromatic aberration up to 1.2 px,
// sharpening up to 0.8, saturation 0.75–1.3.
ViewEffects RandomViewEffects(double strength, std::uint64_t seed, bool phone = false);

// Linear-RGB float image (3 × 32-bit float, channels R, G, B; already
// exposed) → 8-bit BGR with the effects applied. `noise_seed` makes the noise
// deterministic (use different seeds for the two eyes).
Image DevelopImage(const Image& linear_rgb, const ViewEffects& effects, std::uint64_t noise_seed);

// The automatic exposure: the scale bringing the image's log-average
// luminance (linear RGB, 3 × 32-bit float) to `key` (0.18 is photographic
// mid-grey).
double AutoExposure(const Image& linear_rgb, double key = 0.2);

}  // namespace asbuilt

#endif  // ASBUILT_RENDER_CAMERA_EFFECTS_H_
