#include "asbuilt/seg/toy_rooms.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {

struct V3 {
  double x = 0, y = 0, z = 0;
};
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
double Dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 Normalize(V3 a) { return (1.0 / std::sqrt(Dot(a, a))) * a; }

using Rgb = std::array<double, 3>;

// Hash-based value noise in [0, 1].
double Hash(int x, int y, std::uint32_t seed) {
  std::uint32_t h =
      static_cast<std::uint32_t>(x) * 374761393u + static_cast<std::uint32_t>(y) * 668265263u + seed * 2246822519u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return ((h ^ (h >> 16)) & 0xffffff) / double(0xffffff);
}
double Noise(double x, double y, std::uint32_t seed) {
  int xi = static_cast<int>(std::floor(x)), yi = static_cast<int>(std::floor(y));
  double fx = x - xi, fy = y - yi;
  fx = fx * fx * (3 - 2 * fx);
  fy = fy * fy * (3 - 2 * fy);
  double a = Hash(xi, yi, seed), b = Hash(xi + 1, yi, seed), c = Hash(xi, yi + 1, seed), d = Hash(xi + 1, yi + 1, seed);
  return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
}

enum Kind { kBg = 0, kWall = 1, kDoor = 2, kWindow = 3 };

struct Opening {
  int kind = kDoor;
  double u0 = 0, u1 = 0, z0 = 0, z1 = 0;  // Extent incl. casing, wall coords.
  double casing = 0.06;
  bool open = false;
  Rgb leaf{}, frame{};
  int panes = 2;
};

struct Picture {
  double u0, u1, z0, z1;
  Rgb colour;
};

struct Box {
  V3 lo, hi;
  Rgb colour;
};

struct Wall {
  V3 origin, along, normal;  // Inner face: origin + u·along + z·up; normal into the room.
  double length = 0;
  Rgb colour{};
  std::vector<Opening> openings;
  std::vector<Picture> pictures;
};

struct Room {
  double w = 4, d = 4, h = 2.7;
  std::array<Wall, 4> walls;
  Rgb floor{}, ceiling{};
  int floor_style = 0;
  double floor_scale = 0.2;
  std::vector<Box> boxes;
  V3 light;
  double ambient = 0.4, light_power = 0.8;
  Rgb tint{1, 1, 1};
  Rgb sky_top{}, sky_horizon{}, ground{};
  std::uint32_t tex_seed = 0;
};

Rgb RandomColour(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  return {u(rng), u(rng), u(rng)};
}
Rgb Mix(const Rgb& a, const Rgb& b, double t) {
  return {a[0] * (1 - t) + b[0] * t, a[1] * (1 - t) + b[1] * t, a[2] * (1 - t) + b[2] * t};
}

Room MakeRoom(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u01(0, 1);
  auto U = [&](double a, double b) { return a + (b - a) * u01(rng); };
  Room r;
  r.w = U(2.8, 7.0);
  r.d = U(2.8, 7.0);
  r.h = U(2.4, 3.3);
  r.tex_seed = static_cast<std::uint32_t>(rng());
  // Plaster colours: mostly light, sometimes saturated or dark.
  Rgb base = u01(rng) < 0.75 ? RandomColour(rng, 0.6, 0.95) : RandomColour(rng, 0.2, 0.8);
  const V3 up{0, 0, 1};
  (void)up;
  std::array<V3, 4> corners = {V3{0, 0, 0}, V3{r.w, 0, 0}, V3{r.w, r.d, 0}, V3{0, r.d, 0}};
  for (int i = 0; i < 4; ++i) {
    Wall& wall = r.walls[i];
    wall.origin = corners[i];
    V3 e = corners[(i + 1) % 4] - corners[i];
    wall.length = std::sqrt(Dot(e, e));
    wall.along = (1.0 / wall.length) * e;
    wall.normal = {-wall.along.y, wall.along.x, 0};  // CCW room: interior on the left.
    wall.colour = u01(rng) < 0.8 ? Mix(base, RandomColour(rng, 0, 1), 0.08) : RandomColour(rng, 0.3, 0.95);
    // Openings: place left to right with gaps.
    int n = static_cast<int>(U(0, 3.2));
    double cursor = U(0.1, 0.8);
    for (int k = 0; k < n; ++k) {
      Opening o;
      o.kind = u01(rng) < 0.4 ? kDoor : kWindow;
      o.casing = U(0.03, 0.09);
      double width = o.kind == kDoor ? (u01(rng) < 0.15 ? U(1.4, 1.8) : U(0.75, 1.1)) : U(0.5, 2.6);
      if (cursor + width + 2 * o.casing > wall.length - 0.1) break;
      o.u0 = cursor;
      o.u1 = cursor + width + 2 * o.casing;
      if (o.kind == kDoor) {
        o.z0 = 0;
        o.z1 = std::min(r.h - 0.05, U(1.95, 2.4));
        o.open = u01(rng) < 0.3;
      } else {
        o.z0 = U(0.3, 1.3);
        o.z1 = std::min(r.h - U(0.05, 0.5), o.z0 + U(0.5, 2.0));
      }
      o.leaf =
          u01(rng) < 0.5 ? RandomColour(rng, 0.75, 0.98) : Mix(RandomColour(rng, 0.2, 0.7), Rgb{0.2, 0.35, 0.55}, 0.5);
      o.frame = u01(rng) < 0.6 ? RandomColour(rng, 0.8, 1.0) : RandomColour(rng, 0.1, 0.6);
      o.panes = 1 + static_cast<int>(U(0, 3));
      wall.openings.push_back(o);
      cursor = o.u1 + U(0.3, 2.0);
    }
    // Pictures and posters (background class, on walls between openings).
    int np = static_cast<int>(U(0, 2.5));
    for (int k = 0; k < np; ++k) {
      Picture p;
      double pw = U(0.3, 1.4);
      p.u0 = U(0.1, std::max(0.2, wall.length - pw - 0.1));
      p.u1 = p.u0 + pw;
      p.z0 = U(0.9, 1.6);
      p.z1 = std::min(r.h - 0.1, p.z0 + U(0.3, 1.0));
      p.colour = RandomColour(rng, 0.05, 0.95);
      bool overlaps = false;
      for (const auto& o : wall.openings) overlaps |= p.u1 > o.u0 - 0.05 && p.u0 < o.u1 + 0.05;
      if (!overlaps) wall.pictures.push_back(p);
    }
  }
  r.floor_style = static_cast<int>(U(0, 3));
  r.floor = r.floor_style == 0 ? Mix(Rgb{0.15, 0.3, 0.5}, RandomColour(rng, 0, 1), 0.3) : RandomColour(rng, 0.15, 0.8);
  r.floor_scale = U(0.1, 0.6);
  r.ceiling = RandomColour(rng, 0.85, 1.0);
  // Furniture boxes, mostly against walls.
  int nb = static_cast<int>(U(0, 5));
  for (int k = 0; k < nb; ++k) {
    Box b;
    double sx = U(0.3, 2.0), sy = U(0.3, 1.0), sz = U(0.3, 2.1);
    if (u01(rng) < 0.5) std::swap(sx, sy);
    double x = U(0, std::max(0.01, r.w - sx)), y = U(0, std::max(0.01, r.d - sy));
    if (u01(rng) < 0.6) {  // Snap to a wall.
      int side = static_cast<int>(U(0, 4));
      if (side == 0) y = 0;
      if (side == 1) x = r.w - sx;
      if (side == 2) y = r.d - sy;
      if (side == 3) x = 0;
    }
    b.lo = {x, y, 0};
    b.hi = {x + sx, y + sy, sz};
    b.colour = RandomColour(rng, 0.05, 0.9);
    r.boxes.push_back(b);
  }
  r.light = {U(0.3, r.w - 0.3), U(0.3, r.d - 0.3), r.h - 0.05};
  r.ambient = U(0.25, 0.6);
  r.light_power = U(0.4, 1.2);
  r.tint = {U(0.85, 1.1), U(0.9, 1.05), U(0.8, 1.15)};
  r.sky_top = Mix(Rgb{0.55, 0.35, 0.2}, RandomColour(rng, 0.5, 1.0), 0.4);  // BGR-ish order handled at output.
  r.sky_horizon = RandomColour(rng, 0.75, 1.0);
  r.ground = Mix(Rgb{0.3, 0.5, 0.3}, RandomColour(rng, 0.2, 0.7), 0.5);
  return r;
}

bool InsideBox(const V3& p, const Box& b, double margin) {
  return p.x > b.lo.x - margin && p.x < b.hi.x + margin && p.y > b.lo.y - margin && p.y < b.hi.y + margin &&
         p.z > b.lo.z - margin && p.z < b.hi.z + margin;
}

// Ray–AABB slab test; returns entry t and the hit normal.
bool HitBox(const V3& o, const V3& d, const Box& b, double& t_hit, V3& n) {
  double t0 = 0, t1 = 1e30;
  int axis = -1;
  double sign = 0;
  const double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
  const double oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
  for (int a = 0; a < 3; ++a) {
    if (std::abs(dd[a]) < 1e-12) {
      if (oo[a] < lo[a] || oo[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - oo[a]) / dd[a], tb = (hi[a] - oo[a]) / dd[a];
    double s = -1;
    if (ta > tb) {
      std::swap(ta, tb);
      s = 1;
    }
    if (ta > t0) {
      t0 = ta;
      axis = a;
      sign = s;
    }
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  if (axis < 0) return false;
  t_hit = t0;
  n = {axis == 0 ? sign : 0, axis == 1 ? sign : 0, axis == 2 ? sign : 0};
  return true;
}

struct Shade {
  Rgb albedo;
  int label;
  V3 normal;
  bool emissive = false;  // Window views are not lit by the room light.
};

Shade ShadeWall(const Room& room, const Wall& wall, int wall_index, double u, double z, const V3& dir) {
  const std::uint32_t ts = room.tex_seed + wall_index * 17;
  for (const Opening& o : wall.openings) {
    if (u < o.u0 || u > o.u1 || z < o.z0 || z > o.z1) continue;
    const double c = o.casing;
    bool casing = u < o.u0 + c || u > o.u1 - c || z > o.z1 - c || (o.kind == kWindow && z < o.z0 + c);
    if (casing) return {o.frame, o.kind, wall.normal};
    if (o.kind == kDoor) {
      if (o.open) {
        double g = 0.15 + 0.2 * Noise(u * 3, z * 3, ts + 5);
        return {{g, g, g}, kDoor, wall.normal};
      }
      // Leaf with panel grooves and a handle.
      double lu = (u - o.u0 - c) / (o.u1 - o.u0 - 2 * c), lz = (z - o.z0) / (o.z1 - o.z0 - c);
      Rgb a = o.leaf;
      bool groove = (std::abs(lu - 0.15) < 0.01 || std::abs(lu - 0.85) < 0.01) && lz > 0.1 && lz < 0.9;
      if (groove) a = Mix(a, Rgb{0, 0, 0}, 0.3);
      if (std::abs(lu - 0.88) < 0.03 && std::abs(z - 1.0) < 0.04) a = {0.6, 0.6, 0.6};
      double grain = 0.9 + 0.1 * Noise(u * 40, z * 2, ts + 9);
      return {{a[0] * grain, a[1] * grain, a[2] * grain}, kDoor, wall.normal};
    }
    // Window: mullions (frame colour) and glass showing the outside.
    double inner_w = o.u1 - o.u0 - 2 * c;
    double lu = (u - o.u0 - c) / inner_w;
    double pane = lu * o.panes;
    if (std::abs(pane - std::round(pane)) * inner_w / o.panes < 0.025) return {o.frame, kWindow, wall.normal};
    if (std::abs(z - 0.5 * (o.z0 + o.z1)) < 0.02 && o.panes > 2) return {o.frame, kWindow, wall.normal};
    Rgb out;
    if (dir.z > -0.02) {
      double t = std::clamp(dir.z * 2.5, 0.0, 1.0);
      out = Mix(room.sky_horizon, room.sky_top, t);
      // Distant buildings and trees near the horizon.
      double hgt = 0.12 * Noise(std::atan2(dir.y, dir.x) * 6, 0.5, ts + 3);
      if (dir.z < hgt) out = Mix(room.ground, Rgb{0.4, 0.4, 0.45}, Noise(std::atan2(dir.y, dir.x) * 20, 1, ts));
    } else {
      out = Mix(room.ground, Rgb{0.25, 0.3, 0.25}, Noise(dir.x * 30, dir.y * 30, ts + 1));
    }
    return {Mix(out, Rgb{0.8, 0.85, 0.9}, 0.15), kWindow, wall.normal, true};
  }
  for (const Picture& p : wall.pictures) {
    if (u >= p.u0 && u <= p.u1 && z >= p.z0 && z <= p.z1) {
      double v = Noise(u * 8, z * 8, ts + 77);
      return {Mix(p.colour, Rgb{v, v * 0.8, v * 0.6}, 0.5), kBg, wall.normal};
    }
  }
  Rgb a = wall.colour;
  if (z < 0.08) a = Mix(a, Rgb{1, 1, 1}, 0.5);  // Skirting board (wall class).
  double n = 0.94 + 0.06 * Noise(u * 25, z * 25, ts) + 0.03 * Noise(u * 3, z * 3, ts + 1);
  return {{a[0] * n, a[1] * n, a[2] * n}, kWall, wall.normal};
}

Shade ShadeFloor(const Room& room, double x, double y) {
  Rgb a = room.floor;
  double s = room.floor_scale, n = 1;
  if (room.floor_style == 0) {  // Planks.
    double row = std::floor(y / s);
    n = 0.8 + 0.2 * Noise(x * 2 + row * 13.1, row, room.tex_seed + 2) + 0.05 * Noise(x * 40, y * 4, room.tex_seed);
    if (std::abs(y / s - std::round(y / s)) < 0.02) n *= 0.6;
  } else if (room.floor_style == 1) {  // Tiles.
    double fx = x / s - std::round(x / s), fy = y / s - std::round(y / s);
    n = (std::abs(fx) < 0.03 || std::abs(fy) < 0.03) ? 0.6 : 0.95 + 0.05 * Noise(x * 10, y * 10, room.tex_seed);
  } else {  // Carpet.
    n = 0.85 + 0.15 * Noise(x * 60, y * 60, room.tex_seed + 4);
  }
  return {{a[0] * n, a[1] * n, a[2] * n}, kBg, {0, 0, 1}};
}

cv::Vec3b ToPixel(const Rgb& c) {
  auto q = [](double v) { return static_cast<std::uint8_t>(std::clamp(v * 255.0, 0.0, 255.0)); };
  return {q(c[0]), q(c[1]), q(c[2])};
}

}  // namespace

void ToyRoomOptions::Check() const {
  CheckArgument(width_px >= 16 && height_px >= 16,
                fmt::format("ToyRoomOptions size {}x{}, must be at least 16x16", width_px, height_px));
}

ToyView RenderToyRoom(const ToyRoomOptions& options, std::uint64_t index) {
  options.Check();
  std::mt19937_64 rng(options.seed * 0x9E3779B97F4A7C15ull + index * 0xBF58476D1CE4E5B9ull + 1);
  std::uniform_real_distribution<double> u01(0, 1);
  auto U = [&](double a, double b) { return a + (b - a) * u01(rng); };
  Room room = MakeRoom(rng);

  // Camera: level-ish, inside the room and outside furniture.
  V3 cam;
  for (int tries = 0; tries < 50; ++tries) {
    cam = {U(0.2, 0.8) * room.w, U(0.2, 0.8) * room.d, U(1.0, 1.8)};
    bool inside = false;
    for (const Box& b : room.boxes) inside |= InsideBox(cam, b, 0.3);
    if (!inside) break;
  }
  room.boxes.erase(
      std::remove_if(room.boxes.begin(), room.boxes.end(), [&](const Box& b) { return InsideBox(cam, b, 0.3); }),
      room.boxes.end());
  const double yaw = U(0, 2 * M_PI), pitch = U(-12, 12) * M_PI / 180, roll = U(-2, 2) * M_PI / 180;
  const double hfov = U(55, 90) * M_PI / 180;
  V3 fwd{-std::sin(yaw) * std::cos(pitch), std::cos(yaw) * std::cos(pitch), std::sin(pitch)};
  V3 right{std::cos(yaw), std::sin(yaw), 0};
  V3 down = {fwd.y * right.z - fwd.z * right.y, fwd.z * right.x - fwd.x * right.z, fwd.x * right.y - fwd.y * right.x};
  // right × fwd gives up; fwd × right gives down in a right-handed frame.
  if (down.z > 0) down = -1.0 * down;
  V3 r2 = Normalize(std::cos(roll) * right + std::sin(roll) * down);
  V3 d2 = Normalize(std::cos(roll) * down - std::sin(roll) * right);

  const int ss = 2;
  const int W = options.width_px * ss, H = options.height_px * ss;
  const double f = (W / 2.0) / std::tan(hfov / 2);
  cv::Mat colour(H, W, CV_8UC3);
  ToyView view;
  view.label.create(options.height_px, options.width_px, CV_8UC1);
  for (int v = 0; v < H; ++v) {
    for (int u = 0; u < W; ++u) {
      V3 dir = Normalize(fwd + ((u - (W - 1) / 2.0) / f) * r2 + ((v - (H - 1) / 2.0) / f) * d2);
      // Nearest room surface: exit of the convex box.
      double t_best = 1e30;
      int surface = -1;
      for (int i = 0; i < 4; ++i) {
        const Wall& wall = room.walls[i];
        double den = Dot(dir, wall.normal);
        if (den >= -1e-12) continue;
        double t = Dot(wall.origin - cam, wall.normal) / den;
        if (t > 0 && t < t_best) {
          t_best = t;
          surface = i;
        }
      }
      if (dir.z < -1e-12) {
        double t = -cam.z / dir.z;
        if (t < t_best) t_best = t, surface = 4;
      } else if (dir.z > 1e-12) {
        double t = (room.h - cam.z) / dir.z;
        if (t < t_best) t_best = t, surface = 5;
      }
      Shade shade{};
      V3 hit = cam + t_best * dir;
      // Furniture in front?
      double tb = 0;
      V3 nb;
      int box = -1;
      for (size_t k = 0; k < room.boxes.size(); ++k) {
        if (HitBox(cam, dir, room.boxes[k], tb, nb) && tb < t_best) {
          t_best = tb;
          box = static_cast<int>(k);
          hit = cam + tb * dir;
          shade = {room.boxes[k].colour, kBg, nb};
        }
      }
      if (box < 0) {
        if (surface < 4) {
          const Wall& wall = room.walls[surface];
          shade = ShadeWall(room, wall, surface, Dot(hit - wall.origin, wall.along), hit.z, dir);
        } else if (surface == 4) {
          shade = ShadeFloor(room, hit.x, hit.y);
        } else {
          shade = {room.ceiling, kBg, {0, 0, -1}};
        }
      }
      // Lambert + ambient, inverse-square falloff from a ceiling light.
      Rgb c = shade.albedo;
      if (!shade.emissive) {
        V3 to_light = room.light - hit;
        double dist2 = Dot(to_light, to_light);
        double lambert = std::max(0.0, Dot(Normalize(to_light), shade.normal));
        double e = room.ambient + room.light_power * lambert * 4.0 / (2.0 + dist2);
        for (int k = 0; k < 3; ++k) c[k] *= e * room.tint[k];
      }
      colour.at<cv::Vec3b>(v, u) = ToPixel(c);
      // Labels at output pixel centres (sample (1,1) of each 2×2 block).
      if (u % ss == 1 && v % ss == 1)
        view.label.at<std::uint8_t>(v / ss, u / ss) = static_cast<std::uint8_t>(shade.label);
    }
  }
  cv::resize(colour, view.bgr, cv::Size(options.width_px, options.height_px), 0, 0, cv::INTER_AREA);
  // Sensor noise.
  cv::Mat noise(view.bgr.size(), CV_16SC3);
  cv::RNG cv_rng(rng());
  cv_rng.fill(noise, cv::RNG::NORMAL, 0, U(0, 6));
  cv::Mat img16;
  view.bgr.convertTo(img16, CV_16SC3);
  img16 += noise;
  img16.convertTo(view.bgr, CV_8UC3);
  return view;
}

int WriteToyRoomSet(const std::filesystem::path& dir, int count, const ToyRoomOptions& options,
                    const ProgressCallback& progress) {
  options.Check();
  CheckArgument(count >= 0, fmt::format("toy room count = {}, must be >= 0", count));
  std::filesystem::create_directories(dir / "images");
  std::filesystem::create_directories(dir / "labels");
  for (int i = 0; i < count; ++i) {
    ToyView v = RenderToyRoom(options, static_cast<std::uint64_t>(i));
    const std::string name = fmt::format("{:05d}.png", i);
    AtomicFile img(dir / "images" / name), lab(dir / "labels" / name);
    if (!cv::imwrite(img.temp_path().string(), v.bgr) || !cv::imwrite(lab.temp_path().string(), v.label)) {
      throw Error(fmt::format("{}: cannot write toy room view", (dir / name).string()));
    }
    img.Commit();
    lab.Commit();
    ReportProgress(progress, {.stage = "toy rooms", .done = i + 1, .total = count});
  }
  return count;
}

}  // namespace asbuilt
