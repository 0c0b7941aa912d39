#include "asbuilt/render/renderer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/render/ray_tracer.h"
#include "asbuilt/render/texture.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/hash.h"

namespace asbuilt {
namespace {

constexpr float kPiF = 3.14159265f;
constexpr float kEpsilon = 2e-4f;  // Ray offset from surfaces (metres).
constexpr float kFar = 1e5f;
constexpr float kGlassTransmission = 0.85f;
constexpr float kGlassReflection = 0.06f;
constexpr float kMirrorReflection = 0.9f;
constexpr int kAmbientScale = 1;

// Small fast generator, seeded per pixel so results do not depend on threads.
struct Rng {
  std::uint64_t state;
  std::int64_t rays = 0;  // Rays traced for this pixel (statistics).
  float Next() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    std::uint64_t x = SplitMix64(state);
    return static_cast<float>(x >> 40) * (1.0f / 16777216.0f);
  }
};

inline float Luminance(const Vec3f& c) { return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z(); }

// Orthonormal basis around a unit normal (Duff et al. 2017).
inline void Basis(const Vec3f& n, Vec3f* t, Vec3f* b) {
  float sign = std::copysign(1.0f, n.z());
  float a = -1.0f / (sign + n.z());
  float bb = n.x() * n.y() * a;
  *t = Vec3f(1.0f + sign * n.x() * n.x() * a, sign * bb, -sign * n.x());
  *b = Vec3f(bb, sign + n.y() * n.y() * a, -n.y());
}

inline Vec3f CosineSample(const Vec3f& n, Rng& rng) {
  float r1 = rng.Next(), r2 = rng.Next();
  float r = std::sqrt(r1), phi = 2.0f * kPiF * r2;
  Vec3f t, b;
  Basis(n, &t, &b);
  return (t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0f, 1.0f - r1))).normalized();
}

// Per-pixel results of the RGB pass, demodulated: colour = albedo·E/π + extra.
struct PixelBuffers {
  int width = 0, height = 0;
  std::vector<Vec3f> albedo, irradiance, extra, normal;
  std::vector<float> distance;  // Along the ray to the shaded surface; 0 = sky.
  std::vector<int> object;      // Shaded object, −1 = sky.
  void Resize(int w, int h) {
    width = w;
    height = h;
    std::size_t n = static_cast<std::size_t>(w) * h;
    albedo.assign(n, Vec3f::Zero());
    irradiance.assign(n, Vec3f::Zero());
    extra.assign(n, Vec3f::Zero());
    normal.assign(n, Vec3f::Zero());
    distance.assign(n, 0.0f);
    object.assign(n, -1);
  }
};

struct AuxBuffers {
  cv::Mat labels, depth_mm, normals, instance_ids;
};

// The albedo of a photo-textured material at a surface point (PhotoAlbedo).
Vec3f PhotoAlbedoAt(const PhotoAlbedo& pa, const Material& m, const Vec3f& point, const Vec3f& normal) {
  const Photo& photo = *pa.photo;
  float u, v;
  PlaneCoordinates(point, normal, &u, &v);  // As TextureAlbedo's.
  if (pa.swap_uv) std::swap(u, v);
  const float width_m = static_cast<float>(pa.size_m);
  const float height_m =
      width_m * static_cast<float>(photo.linear_rgb.height()) / static_cast<float>(photo.linear_rgb.width());
  Vec3f c = photo.Sample((u + static_cast<float>(pa.offset_m.x())) / width_m,
                         -(v + static_cast<float>(pa.offset_m.y())) / height_m);
  const Vec3f base = m.base_color.cast<float>();
  const float base_lum = std::max(Luminance(base), 1e-3f);
  const float ratio = Luminance(c) / photo.mean_luminance;
  Vec3f detailed = base * std::max(0.0f, 1.0f + static_cast<float>(pa.detail) * (ratio - 1.0f));
  Vec3f coloured = c * (base_lum / photo.mean_luminance);
  const float k = static_cast<float>(pa.colour);
  return (detailed * (1.0f - k) + coloured * k).cwiseMin(0.95f);
}

}  // namespace

std::string SceneLook::ToString() const {
  std::string s = "SceneLook(albedo";
  for (const auto& [name, pa] : albedo) {
    s += fmt::format(" {}={}", name, pa.photo ? std::filesystem::path(pa.photo->path).filename().string() : "none");
  }
  s += fmt::format(", outside={}, next_room_depth_m={:.2f})",
                   outside ? std::filesystem::path(outside->path).filename().string() : "sky", mesh.next_room_depth_m);
  return s;
}

struct SceneRenderer::Impl {
  SceneMesh mesh;
  std::unique_ptr<RayTracer> tracer;
  std::uint32_t texture_seed = 0;
  SceneLook look;
  std::vector<const PhotoAlbedo*> photo_of_material;  // Per mesh material; null: procedural.
  float outside_scale = 1.0f;                         // Photo radiance → scene radiance.

  // What a ray that leaves the building sees: the sky gradient, or the photo.
  Vec3f Outside(const Vec3f& d) const {
    if (!look.outside) return Sky(d);
    return outside_scale * look.outside->Outside(d, static_cast<float>(DegToRad(look.outside_yaw_deg)));
  }

  Vec3f Sky(const Vec3f& d) const {
    const Environment& env = mesh.environment;
    if (!env.sky) return Vec3f::Constant(0.03f);
    Vec3f zenith = env.sky_color.cast<float>();
    if (d.z() < 0) return 0.5f * env.ground_color.cast<float>();
    Vec3f horizon = 0.55f * zenith + Vec3f::Constant(0.45f);
    return horizon + (zenith - horizon) * std::sqrt(d.z());
  }

  Vec3f Albedo(const MeshObject& o, const Vec3f& p, const Vec3f& n) const {
    if (const PhotoAlbedo* pa = photo_of_material[o.material]) {
      const Material& m = mesh.materials[o.material];
      Vec3f a = PhotoAlbedoAt(*pa, m, p, n);
      if (pa->keep_procedural) {
        a *= Luminance(TextureAlbedo(m, p, n, texture_seed)) / std::max(Luminance(m.base_color.cast<float>()), 1e-3f);
      }
      return a.cwiseMin(0.95f);
    }
    return TextureAlbedo(mesh.materials[o.material], p, n, texture_seed);
  }

  // Direct irradiance at p (normal n) from area lights and suns, one shadow
  // ray each; adds a Blinn–Phong highlight towards `to_eye` into *specular.
  // With `one_light`, a single light drawn at random stands for all of them
  // (weighted by their count): cheaper, noisier — for bounce points.
  Vec3f Direct(const Vec3f& p, const Vec3f& n, const Vec3f* to_eye, float roughness, Rng& rng, Vec3f* specular,
               bool one_light = false) const {
    Vec3f e = Vec3f::Zero();
    const int lights = static_cast<int>(mesh.area_lights.size() + mesh.suns.size());
    int only = -1;
    float weight = 1.0f;
    if (one_light && lights > 1) {
      only = std::min(lights - 1, static_cast<int>(rng.Next() * lights));
      weight = static_cast<float>(lights);
    }
    int light_index = -1;
    const Vec3f origin = p + n * kEpsilon;
    float shininess = 0, ks = 0;
    if (to_eye != nullptr) {
      float r2 = std::max(roughness * roughness, 0.02f);
      shininess = std::clamp(2.0f / (r2 * r2) - 2.0f, 2.0f, 2000.0f);
      ks = 0.04f + 0.25f * (1.0f - roughness) * (1.0f - roughness);
    }
    for (const AreaLight& light : mesh.area_lights) {
      if (only >= 0 && ++light_index != only) continue;
      Vec3f q = (light.centre + (2.0 * rng.Next() - 1.0) * light.half_u + (2.0 * rng.Next() - 1.0) * light.half_v)
                    .cast<float>();
      Vec3f l = q - origin;
      float d2 = l.squaredNorm();
      float d = std::sqrt(d2);
      l /= d;
      float cos_s = n.dot(l);
      float cos_l = -light.normal.cast<float>().dot(l);
      if (cos_s <= 0 || cos_l <= 0) continue;
      ++rng.rays;
      if (tracer->Occluded(origin, l, 0.0f, d - 1e-3f)) continue;
      Vec3f contrib =
          light.radiance.cast<float>() * (static_cast<float>(light.area_m2) * cos_s * cos_l / std::max(d2, 1e-4f));
      e += contrib;
      if (to_eye != nullptr) {
        Vec3f h = (l + *to_eye).normalized();
        *specular +=
            contrib * (ks * (shininess + 8.0f) / (8.0f * kPiF) * std::pow(std::max(n.dot(h), 0.0f), shininess));
      }
    }
    for (const SunLight& sun : mesh.suns) {
      if (only >= 0 && ++light_index != only) continue;
      Vec3f s = sun.direction_to_sun.cast<float>();
      Vec3f t, b;
      Basis(s, &t, &b);
      float a = static_cast<float>(sun.angular_radius_rad);
      s = (s + t * (a * (2 * rng.Next() - 1)) + b * (a * (2 * rng.Next() - 1))).normalized();
      float cos_s = n.dot(s);
      if (cos_s <= 0) continue;
      ++rng.rays;
      if (tracer->Occluded(origin, s, 0.0f, kFar)) continue;
      Vec3f contrib = sun.irradiance.cast<float>() * cos_s;
      e += contrib;
      if (to_eye != nullptr) {
        Vec3f h = (s + *to_eye).normalized();
        *specular +=
            contrib * (ks * (shininess + 8.0f) / (8.0f * kPiF) * std::pow(std::max(n.dot(h), 0.0f), shininess));
      }
    }
    return weight * e + Vec3f::Constant(static_cast<float>(0.5 * mesh.environment.ambient) * kAmbientScale);
  }

  // Irradiance at p from one diffuse bounce (cosine-sampled: E ≈ π·L).
  Vec3f Indirect(const Vec3f& p, const Vec3f& n, Rng& rng) const {
    Vec3f d = CosineSample(n, rng);
    RayHit hit;
    ++rng.rays;
    if (!tracer->Intersect(p + n * kEpsilon, d, 0.0f, kFar, false, &hit)) return kPiF * Sky(d);
    const MeshObject& o = mesh.objects[hit.object];
    if (o.emission.squaredNorm() > 0) return Vec3f::Zero();  // Counted as direct light.
    Vec3f q = p + n * kEpsilon + d * hit.t;
    Vec3f nq = hit.geometric_normal.dot(d) > 0 ? Vec3f(-hit.geometric_normal) : hit.geometric_normal;
    Vec3f e = Albedo(o, q, nq).cwiseProduct(Direct(q, nq, nullptr, 1.0f, rng, nullptr, true));
    float lum = Luminance(e);
    if (lum > 4.0f) e *= 4.0f / lum;  // Clamp fireflies (as Cycles' indirect clamp).
    return e;
  }
};

std::string StereoCamera::ToString() const {
  return fmt::format(
      "StereoCamera({} position_m=[{:.3f}, {:.3f}, {:.3f}] yaw_deg={:.2f} pitch_deg={:.2f} "
      "baseline_m={:.3f})",
      camera.ToString(), viewpoint.position_m.x(), viewpoint.position_m.y(), viewpoint.position_m.z(),
      viewpoint.yaw_deg, viewpoint.pitch_deg, baseline_m);
}

const FieldList<RenderOptions>& RenderOptionFields() {
  using R = RenderOptions;
  static const FieldList<R> kList = {
      Bind(&R::samples_per_pixel, {.name = "samples_per_pixel",
                                   .description = "RGB path-tracing samples per pixel (less noise vs linear time).",
                                   .minimum = 1.0,
                                   .maximum = 4096.0}),
      Bind(&R::camera_effects, {.name = "camera_effects",
                                .description = "Strength of the randomised camera effects (exposure, white balance, "
                                               "noise, blur, JPEG); 0 = clean.",
                                .minimum = 0.0,
                                .maximum = 1.0}),
      Bind(&R::id_drift, {.name = "id_drift",
                          .description = "How much ID-map colours follow the light; 0 = flat colours.",
                          .minimum = 0.0,
                          .maximum = 1.0}),
      Bind(&R::denoise_passes, {.name = "denoise_passes",
                                .description = "Edge-aware denoising passes over the lighting; 0 = raw.",
                                .minimum = 0.0,
                                .maximum = 8.0}),
      Bind(&R::indirect_light,
           {.name = "indirect_light",
            .description = "One diffuse bounce; off = direct light + ambient only (about 2× faster)."}),
      Bind(&R::normals, {.name = "normals", .description = "Also write normals/ (camera frame)."}),
      Bind(&R::instance_ids,
           {.name = "instance_ids", .description = "Also write instances/ (uint16 object index + 1, 0 = sky)."}),
      Bind(&R::phone_camera, {.name = "phone_camera",
                              .description = "Also a phone's processing: wider exposure, noise and JPEG ranges, "
                                             "chromatic aberration, sharpening, saturation."}),
      Bind(&R::layout_labels, {.name = "layout_labels",
                               .description = "Label by the layout rule, as reviews and ZInD do: furniture and door "
                                              "leaves before a wall are wall (docs/seg.md); off: what the ray meets "
                                              "first."}),
  };
  return kList;
}

void RenderOptions::Check() const { RenderOptionFields().CheckValues(*this, "RenderOptions"); }

Eigen::Isometry3d WorldFromStereoEye(const Viewpoint& viewpoint, double baseline_m, StereoEye eye) {
  RigPose pose{viewpoint.position_m, DegToRad(viewpoint.yaw_deg)};
  Eigen::Isometry3d world_from_cam = WorldFromCamera(pose, baseline_m, eye);
  // Pitch: rotate the camera about its own x axis (x right, y down, z
  // forward); positive pitch turns z towards −y, i.e. looks up.
  double p = DegToRad(viewpoint.pitch_deg);
  Mat3 pitch;
  pitch << 1, 0, 0, 0, std::cos(p), -std::sin(p), 0, std::sin(p), std::cos(p);
  world_from_cam.linear() = world_from_cam.linear() * pitch;
  return world_from_cam;
}

SceneRenderer::SceneRenderer(const Scene& scene, SceneLook look) : impl_(std::make_unique<Impl>()) {
  impl_->mesh = BuildSceneMesh(scene, look.mesh);
  impl_->tracer = std::make_unique<RayTracer>(impl_->mesh);
  impl_->texture_seed = static_cast<std::uint32_t>(SplitMix64(scene.seed));
  impl_->look = std::move(look);
  const SceneLook& lk = impl_->look;
  impl_->photo_of_material.assign(impl_->mesh.materials.size(), nullptr);
  for (std::size_t i = 0; i < impl_->mesh.materials.size(); ++i) {
    auto it = lk.albedo.find(impl_->mesh.materials[i].name);
    if (it != lk.albedo.end() && it->second.photo) {
      CheckArgument(it->second.size_m > 0, fmt::format("PhotoAlbedo.size_m = {} for material '{}', must be > 0",
                                                       it->second.size_m, it->first));
      impl_->photo_of_material[i] = &it->second;
    }
  }
  if (lk.outside) {
    // Match the photo's mean to the sky gradient a little above the horizon.
    const float sky = Luminance(impl_->Sky(Vec3f(1.0f, 0.0f, 0.4f).normalized()));
    impl_->outside_scale = static_cast<float>(lk.outside_gain) * sky / lk.outside->mean_luminance;
  }
}

SceneRenderer::~SceneRenderer() = default;

const SceneMesh& SceneRenderer::mesh() const { return impl_->mesh; }

namespace {

// À-trous wavelet filter (Dammertz et al. 2010) over the irradiance, guided
// by normals, distance and object: smooths sampling noise, keeps edges.
void DenoiseIrradiance(PixelBuffers& b, int passes) {
  static const float kKernel[5] = {1.f / 16, 1.f / 4, 3.f / 8, 1.f / 4, 1.f / 16};
  std::vector<Vec3f> next(b.irradiance.size());
  for (int pass = 0; pass < passes; ++pass) {
    const int step = 1 << pass;
    tbb::parallel_for(0, b.height, [&](int y) {
      for (int x = 0; x < b.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * b.width + x;
        if (b.object[i] < 0) {
          next[i] = b.irradiance[i];
          continue;
        }
        Vec3f sum = Vec3f::Zero();
        float wsum = 0.0f;
        const float dist = b.distance[i];
        for (int dy = -2; dy <= 2; ++dy) {
          int yy = y + dy * step;
          if (yy < 0 || yy >= b.height) continue;
          for (int dx = -2; dx <= 2; ++dx) {
            int xx = x + dx * step;
            if (xx < 0 || xx >= b.width) continue;
            const std::size_t j = static_cast<std::size_t>(yy) * b.width + xx;
            if (b.object[j] != b.object[i]) continue;
            float nd = std::max(0.0f, b.normal[i].dot(b.normal[j]));
            float wn = nd * nd;
            wn *= wn;
            wn *= wn;  // n·n'^8
            float wd = std::exp(-std::abs(b.distance[j] - dist) / (0.03f * dist * step + 1e-3f));
            float w = kKernel[dy + 2] * kKernel[dx + 2] * wn * wd;
            sum += w * b.irradiance[j];
            wsum += w;
          }
        }
        next[i] = wsum > 0 ? Vec3f(sum / wsum) : b.irradiance[i];
      }
    });
    b.irradiance.swap(next);
  }
}

// What the layout rule looks through: the room's contents, not its shell.
bool IsRoomContent(SurfaceRole role) {
  return role == SurfaceRole::kFurniture || role == SurfaceRole::kMirror || role == SurfaceRole::kLight ||
         role == SurfaceRole::kDoorLeaf;
}

// The label and distance of a primary ray's first hit that counts: the hit
// itself, or with the layout rule the first part of the shell behind the
// room's contents. Label portals crossed first win in both.
std::uint8_t PrimaryLabel(const RayTracer& tracer, const Vec3f& origin, const Vec3f& dir, bool found, RayHit hit,
                          bool layout) {
  const SceneMesh& mesh = tracer.mesh();
  double t_first = found ? hit.t : 1e30;
  if (layout && found) {
    float travelled = 0.0f;
    for (int k = 0; found && k < 16 && IsRoomContent(mesh.objects[hit.object].role); ++k) {
      travelled += hit.t;
      found = tracer.Intersect(origin + travelled * dir, dir, kEpsilon, kFar, true, &hit);
    }
    t_first = found ? travelled + hit.t : 1e30;
  }
  std::uint8_t label = found ? mesh.objects[hit.object].label : kLabelBackground;
  const Vec3 o_d = origin.cast<double>(), dir_d = dir.cast<double>();
  double best = 1e30;
  for (const LabelPortal& portal : mesh.portals) {
    double tp = IntersectPortal(portal, o_d, dir_d);
    if (tp > 0 && tp <= t_first + 1e-4 && tp < best) {
      best = tp;
      label = portal.label;
    }
  }
  return label;
}

// A camera-frame normal as an 8-bit BGR pixel (each component −1..1 → 0..255).
cv::Vec3b NormalPixel(const Vec3f& nc) {
  auto byte = [](float v) { return static_cast<std::uint8_t>(std::lround(127.5f * (v + 1))); };
  return {byte(nc.z()), byte(nc.y()), byte(nc.x())};
}

}  // namespace

RenderedView SceneRenderer::Render(const StereoCamera& cam, const RenderOptions& options, std::uint64_t view_key,
                                   bool right_eye) const {
  options.Check();
  cam.camera.Check();
  const Impl& im = *impl_;
  const PinholeCamera& K = cam.camera;
  const int W = K.width_px, H = K.height_px;
  const int spp = options.samples_per_pixel;
  const std::uint64_t view_seed = SplitMix64(options.seed ^ SplitMix64(view_key + 0x5EED));

  RenderedView out;
  out.effects = RandomViewEffects(options.camera_effects, view_seed, options.phone_camera);

  AuxBuffers aux;
  aux.labels = cv::Mat(H, W, CV_8U, cv::Scalar(0));
  aux.depth_mm = cv::Mat(H, W, CV_16U, cv::Scalar(0));
  if (options.normals) aux.normals = cv::Mat(H, W, CV_8UC3, cv::Scalar(0, 0, 0));
  if (options.instance_ids) aux.instance_ids = cv::Mat(H, W, CV_16U, cv::Scalar(0));

  double exposure = 1.0;
  PixelBuffers left_buffers;
  std::atomic<std::int64_t> total_rays{0};
  for (int eye_index = 0; eye_index < (right_eye ? 2 : 1); ++eye_index) {
    const StereoEye eye = eye_index == 0 ? StereoEye::kLeft : StereoEye::kRight;
    const bool with_aux = eye == StereoEye::kLeft;
    const Eigen::Isometry3d world_from_cam = WorldFromStereoEye(cam.viewpoint, cam.baseline_m, eye);
    const Mat3 rot_d = world_from_cam.linear();
    const Eigen::Matrix3f rot = rot_d.cast<float>();
    const Vec3f centre = world_from_cam.translation().cast<float>();
    PixelBuffers b;
    b.Resize(W, H);

    tbb::parallel_for(tbb::blocked_range2d<int>(0, H, 16, 0, W, 16), [&](const tbb::blocked_range2d<int>& r) {
      std::int64_t tile_rays = 0;
      for (int y = r.rows().begin(); y < r.rows().end(); ++y) {
        for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
          const std::size_t i = static_cast<std::size_t>(y) * W + x;
          Rng rng{SplitMix64(view_seed ^ (static_cast<std::uint64_t>(eye_index) << 62) ^ (i * 0x9E3779B97F4A7C15ULL))};
          Vec3f albedo_sum = Vec3f::Zero(), e_sum = Vec3f::Zero(), extra_sum = Vec3f::Zero();
          for (int s = 0; s < spp; ++s) {
            // Sample 0 goes through the pixel centre (labels, depth); the
            // others are jittered over the pixel (box filter).
            float jx = s == 0 ? 0.0f : rng.Next() - 0.5f;
            float jy = s == 0 ? 0.0f : rng.Next() - 0.5f;
            Vec3f d_cam((x + jx - static_cast<float>(K.cx)) / static_cast<float>(K.fx),
                        (y + jy - static_cast<float>(K.cy)) / static_cast<float>(K.fy), 1.0f);
            const float d_cam_norm = d_cam.norm();
            Vec3f dir = rot * (d_cam / d_cam_norm);
            Vec3f origin = centre;
            Vec3f throughput = Vec3f::Ones();
            float travelled = 0.0f;
            bool first = true;
            for (int layer = 0; layer < 4; ++layer) {
              RayHit hit;
              ++rng.rays;
              bool found = im.tracer->Intersect(origin, dir, layer == 0 ? 0.0f : kEpsilon, kFar, true, &hit);
              if (s == 0 && first && with_aux) {
                // Exact aux outputs from the first hit through the centre.
                aux.labels.at<std::uint8_t>(y, x) =
                    PrimaryLabel(*im.tracer, origin, dir, found, hit, options.layout_labels);
                if (found) {
                  double z_mm = hit.t / d_cam_norm * 1000.0;
                  aux.depth_mm.at<std::uint16_t>(y, x) =
                      z_mm < 65535.0 ? static_cast<std::uint16_t>(std::lround(z_mm)) : 0;
                  if (!aux.instance_ids.empty()) {
                    aux.instance_ids.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(hit.object + 1);
                  }
                  if (!aux.normals.empty()) {
                    Vec3f n = hit.geometric_normal.dot(dir) > 0 ? Vec3f(-hit.geometric_normal) : hit.geometric_normal;
                    aux.normals.at<cv::Vec3b>(y, x) = NormalPixel(rot.transpose() * n);
                  }
                }
              }
              first = false;
              if (!found) {
                extra_sum += throughput.cwiseProduct(im.Outside(dir));
                break;
              }
              const MeshObject& o = im.mesh.objects[hit.object];
              if (im.look.outside && (o.role == SurfaceRole::kGround || o.role == SurfaceRole::kExterior)) {
                extra_sum += throughput.cwiseProduct(im.Outside(dir));  // The photo stands for the outside.
                break;
              }
              Vec3f p = origin + dir * hit.t;
              travelled += hit.t;
              Vec3f n = hit.geometric_normal.dot(dir) > 0 ? Vec3f(-hit.geometric_normal) : hit.geometric_normal;
              if (o.role == SurfaceRole::kGlass || o.role == SurfaceRole::kMirror) {
                // Pane: a faint sky reflection, then on through it. Mirror: on along the reflection.
                const bool mirror = o.role == SurfaceRole::kMirror;
                const Vec3f refl = dir - 2.0f * dir.dot(n) * n,
                            tint = im.mesh.materials[o.material].base_color.cast<float>();
                if (!mirror) extra_sum += throughput.cwiseProduct(kGlassReflection * im.Sky(refl));
                throughput = throughput.cwiseProduct((mirror ? kMirrorReflection : kGlassTransmission) * tint);
                dir = mirror ? refl : dir;
                origin = p;
                continue;
              }
              if (o.emission.squaredNorm() > 0 && n.z() < -0.5f) {
                extra_sum += throughput.cwiseProduct(o.emission);
              } else {
                const Material& m = im.mesh.materials[o.material];
                Vec3f albedo = im.Albedo(o, p, n);
                Vec3f to_eye = -dir;
                Vec3f spec = Vec3f::Zero();
                Vec3f e = im.Direct(p, n, &to_eye, static_cast<float>(m.roughness), rng, &spec);
                if (options.indirect_light) e += im.Indirect(p, n, rng);
                albedo_sum += throughput.cwiseProduct(albedo);
                e_sum += e;
                extra_sum += throughput.cwiseProduct(spec);
              }
              if (s == 0) {
                b.normal[i] = n;
                b.distance[i] = travelled;
                b.object[i] = hit.object;
              }
              break;
            }
          }
          tile_rays += rng.rays;
          const float inv = 1.0f / spp;
          b.albedo[i] = albedo_sum * inv;
          b.irradiance[i] = e_sum * inv;
          b.extra[i] = extra_sum * inv;
        }
      }
      total_rays.fetch_add(tile_rays, std::memory_order_relaxed);
    });

    // Irradiance averaged over samples that hit a surface: E_sum / spp is
    // fine where all samples hit one surface; edges blend via albedo.
    if (options.denoise_passes > 0) DenoiseIrradiance(b, options.denoise_passes);

    cv::Mat linear(H, W, CV_32FC3);
    for (int y = 0; y < H; ++y) {
      auto* row = linear.ptr<cv::Vec3f>(y);
      for (int x = 0; x < W; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * W + x;
        Vec3f c = b.albedo[i].cwiseProduct(b.irradiance[i]) / kPiF + b.extra[i];
        row[x] = cv::Vec3f(c.x(), c.y(), c.z());
      }
    }
    if (eye == StereoEye::kLeft) exposure = AutoExposure(AsImage(linear));
    linear *= exposure;
    Image developed = DevelopImage(AsImage(linear), out.effects, view_seed * 2 + eye_index);
    if (eye == StereoEye::kLeft) {
      out.left = developed;
      left_buffers = std::move(b);
    } else {
      out.right = developed;
    }
  }

  // ID map: nominal class colours, brightened or darkened with the light and
  // tinted by the surface (the drift of a real ID pass).
  const PixelBuffers& b = left_buffers;
  double mean_lum = 0.0;
  int lit = 0;
  for (std::size_t i = 0; i < b.irradiance.size(); ++i) {
    if (b.object[i] >= 0) {
      mean_lum += Luminance(b.irradiance[i]);
      ++lit;
    }
  }
  mean_lum = lit > 0 ? mean_lum / lit : 1.0;
  const float drift = static_cast<float>(options.id_drift);
  cv::Mat idmap(H, W, CV_8UC3);
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * W + x;
      const auto& nominal = kIdMapColors[std::min<int>(aux.labels.at<std::uint8_t>(y, x), 3)];
      float shade = b.object[i] >= 0 ? static_cast<float>(Luminance(b.irradiance[i]) / std::max(mean_lum, 1e-6)) : 1.0f;
      float f = 1.0f + drift * (std::sqrt(std::clamp(shade, 0.1f, 4.0f)) - 1.0f);
      cv::Vec3b px;
      for (int c = 0; c < 3; ++c) {
        float v = nominal[c] * f + drift * 60.0f * (b.albedo[i][c] - 0.5f);
        px[2 - c] = static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
      }
      idmap.at<cv::Vec3b>(y, x) = px;
    }
  }
  out.idmap = AsImage(idmap);
  out.labels = AsImage(aux.labels);
  out.depth_mm = AsImage(aux.depth_mm);
  out.normals = AsImage(aux.normals);
  out.instance_ids = AsImage(aux.instance_ids);
  out.rays_traced = total_rays.load();
  return out;
}

}  // namespace asbuilt
