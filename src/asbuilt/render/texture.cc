#include "asbuilt/render/texture.h"

#include <algorithm>
#include <cmath>

namespace asbuilt {
namespace {

inline std::uint32_t Hash(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

inline float Lattice(int x, int y, int z, std::uint32_t seed) {
  std::uint32_t h = Hash(
      static_cast<std::uint32_t>(x) * 0x8da6b343U ^
      Hash(static_cast<std::uint32_t>(y) * 0xd8163841U ^ Hash(static_cast<std::uint32_t>(z) * 0xcb1ab31fU ^ seed)));
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

inline float Smooth(float t) { return t * t * (3.0f - 2.0f * t); }
inline float Lerp(float a, float b, float t) { return a + (b - a) * t; }
inline Vec3f Mix(const Vec3f& a, const Vec3f& b, float t) { return a + (b - a) * t; }
inline float Fract(float x) { return x - std::floor(x); }

}  // namespace

float ValueNoise(const Vec3f& p, std::uint32_t seed) {
  float fx = std::floor(p.x()), fy = std::floor(p.y()), fz = std::floor(p.z());
  int x = static_cast<int>(fx), y = static_cast<int>(fy), z = static_cast<int>(fz);
  float tx = Smooth(p.x() - fx), ty = Smooth(p.y() - fy), tz = Smooth(p.z() - fz);
  float c00 = Lerp(Lattice(x, y, z, seed), Lattice(x + 1, y, z, seed), tx);
  float c10 = Lerp(Lattice(x, y + 1, z, seed), Lattice(x + 1, y + 1, z, seed), tx);
  float c01 = Lerp(Lattice(x, y, z + 1, seed), Lattice(x + 1, y, z + 1, seed), tx);
  float c11 = Lerp(Lattice(x, y + 1, z + 1, seed), Lattice(x + 1, y + 1, z + 1, seed), tx);
  return Lerp(Lerp(c00, c10, ty), Lerp(c01, c11, ty), tz);
}

float FractalNoise(const Vec3f& p, int octaves, std::uint32_t seed) {
  float sum = 0.0f, amp = 0.5f, norm = 0.0f;
  Vec3f q = p;
  for (int i = 0; i < octaves; ++i) {
    sum += amp * ValueNoise(q, seed + 1013u * i);
    norm += amp;
    amp *= 0.5f;
    q *= 2.03f;
  }
  return sum / norm;
}

void PlaneCoordinates(const Vec3f& point, const Vec3f& normal, float* u, float* v) {
  const float ax = std::abs(normal.x()), ay = std::abs(normal.y()), az = std::abs(normal.z());
  if (az >= ax && az >= ay) {
    *u = point.x(), *v = point.y();
  } else if (ax >= ay) {
    *u = point.y(), *v = point.z();
  } else {
    *u = point.x(), *v = point.z();
  }
}

Vec3f TextureAlbedo(const Material& material, const Vec3f& point, const Vec3f& normal, std::uint32_t seed) {
  const Vec3f base = material.base_color.cast<float>();
  const Vec3f second = material.secondary_color.cast<float>();
  const float scale = static_cast<float>(std::max(material.texture_scale_m, 1e-3));
  float u, v;
  PlaneCoordinates(point, normal, &u, &v);
  switch (material.texture) {
    case TextureKind::kNone:
      return base;
    case TextureKind::kPlaster: {
      float n = FractalNoise(point / (0.25f * scale), 4, seed);
      float fine = ValueNoise(point * (40.0f / scale), seed + 7);
      return base * (0.9f + 0.16f * n + 0.04f * fine);
    }
    case TextureKind::kPaint: {
      float n = FractalNoise(point / (0.5f * scale), 3, seed + 11);
      return base * (0.96f + 0.07f * n);
    }
    case TextureKind::kWallpaper: {
      float s = Fract(u / scale);
      float motif = ValueNoise(Vec3f(u / (0.25f * scale), v / (0.25f * scale), 0), seed + 3);
      Vec3f c = s < 0.35f ? second : base;
      if (motif > 0.72f) c = Mix(c, second, 0.5f);
      return c * (0.95f + 0.08f * ValueNoise(point * 30.0f, seed));
    }
    case TextureKind::kWood: {
      // Planks of width `scale` along u, staggered joints along v.
      float plank = std::floor(v / scale);
      float along = u + 1.7f * Lattice(static_cast<int>(plank), 0, 0, seed) * 3.0f;
      float joint = Fract(along / (6.0f * scale));
      float edge = std::min(Fract(v / scale), 1.0f - Fract(v / scale));
      float tint = 0.85f + 0.3f * Lattice(static_cast<int>(plank), 1, 0, seed);
      float grain = 0.5f + 0.5f * std::sin(v * 180.0f / (scale * 6.0f) +
                                           6.0f * FractalNoise(Vec3f(along * 2.0f, v * 20.0f, plank), 3, seed));
      Vec3f c = Mix(base, second, 0.55f * grain) * tint;
      if (edge < 0.015f || joint < 0.004f) c *= 0.55f;
      return c;
    }
    case TextureKind::kTiles: {
      float fu = Fract(u / scale), fv = Fract(v / scale);
      float grout = 0.035f;
      if (fu < grout || fv < grout) return second;
      float jitter = Lattice(static_cast<int>(std::floor(u / scale)), static_cast<int>(std::floor(v / scale)), 5, seed);
      return base * (0.92f + 0.14f * jitter) * (0.97f + 0.05f * ValueNoise(point * 20.0f, seed));
    }
    case TextureKind::kCarpet: {
      float n = ValueNoise(point * (200.0f / scale), seed);
      float m = FractalNoise(point / scale, 3, seed + 5);
      return Mix(base, second, 0.35f * m) * (0.82f + 0.3f * n);
    }
    case TextureKind::kConcrete: {
      float n = FractalNoise(point / (0.3f * scale), 5, seed + 9);
      return Mix(base, second, n) * (0.9f + 0.15f * ValueNoise(point * 25.0f, seed));
    }
  }
  return base;
}

}  // namespace asbuilt
