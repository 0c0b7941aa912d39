#ifndef ASBUILT_RENDER_RAY_TRACER_H_
#define ASBUILT_RENDER_RAY_TRACER_H_

// Embree 3 behind one small class: nearest-hit and occlusion queries on a
// SceneMesh. Glass lives in its own Embree scene so shading rays can pass
// through panes while primary rays (labels, depth) stop on them.
// Thread-safe for queries after construction.

#include <memory>

#include "asbuilt/render/scene_mesh.h"

namespace asbuilt {

struct RayHit {
  float t = 0.0f;   // Distance along the (unit) ray direction.
  int object = -1;  // Index into SceneMesh::objects.
  int triangle = -1;
  Vec3f geometric_normal = Vec3f::UnitZ();  // Unit, not yet facing the ray.
};

class RayTracer {
 public:
  // Builds the acceleration structures (Embree, multi-threaded). The mesh
  // must outlive the tracer.
  explicit RayTracer(const SceneMesh& mesh);
  ~RayTracer();
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  // Nearest hit in (t_near, t_far); glass included when `with_glass`.
  bool Intersect(const Vec3f& origin, const Vec3f& dir, float t_near, float t_far, bool with_glass, RayHit* hit) const;
  // True if anything opaque (not glass) lies in (t_near, t_far).
  bool Occluded(const Vec3f& origin, const Vec3f& dir, float t_near, float t_far) const;

  const SceneMesh& mesh() const { return mesh_; }

 private:
  struct Impl;
  const SceneMesh& mesh_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace asbuilt

#endif  // ASBUILT_RENDER_RAY_TRACER_H_
