#ifndef ASBUILT_RENDER_TEXTURE_H_
#define ASBUILT_RENDER_TEXTURE_H_

// Procedural textures (plaster noise, paint, wallpaper, wood, tiles, carpet,
// concrete) evaluated at a world point: no images, no UVs, deterministic.

#include <cstdint>

#include "asbuilt/render/scene_mesh.h"

namespace asbuilt {

// Smooth value noise in [0, 1] at a 3-D point (lattice spacing 1), seeded.
float ValueNoise(const Vec3f& p, std::uint32_t seed);
// Fractal sum of `octaves` value-noise layers, in [0, 1].
float FractalNoise(const Vec3f& p, int octaves, std::uint32_t seed);

// Linear-RGB albedo of `material` at `point` (world metres) on a surface with
// unit `normal`. The texture is laid out in the plane most aligned with the
// surface (floor: x–y; walls: along the wall and z). `seed` varies the
// pattern between scenes.
// Surface coordinates (u, v) of `point` in the world plane most aligned with
// a surface of unit `normal` (x–y for floors, y–z or x–z for walls), metres.
void PlaneCoordinates(const Vec3f& point, const Vec3f& normal, float* u, float* v);

Vec3f TextureAlbedo(const Material& material, const Vec3f& point, const Vec3f& normal, std::uint32_t seed);

}  // namespace asbuilt

#endif  // ASBUILT_RENDER_TEXTURE_H_
