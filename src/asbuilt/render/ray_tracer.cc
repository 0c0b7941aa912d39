#include "asbuilt/render/ray_tracer.h"

#include <embree3/rtcore.h>

#include <limits>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {

struct RayTracer::Impl {
  RTCDevice device = nullptr;
  RTCScene opaque = nullptr;
  RTCScene glass = nullptr;
  std::vector<int> opaque_objects;  // Embree geometry id → object index.
  std::vector<int> glass_objects;

  ~Impl() {
    if (opaque) rtcReleaseScene(opaque);
    if (glass) rtcReleaseScene(glass);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

void AttachMesh(RTCDevice device, RTCScene scene, const MeshObject& o) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), o.vertices.size()));
  for (std::size_t i = 0; i < o.vertices.size(); ++i) {
    v[3 * i] = o.vertices[i].x();
    v[3 * i + 1] = o.vertices[i].y();
    v[3 * i + 2] = o.vertices[i].z();
  }
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), o.triangles.size()));
  for (std::size_t i = 0; i < o.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) idx[3 * i + k] = static_cast<unsigned>(o.triangles[i][k]);
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
}

void InitRay(RTCRay& ray, const Vec3f& origin, const Vec3f& dir, float t_near, float t_far) {
  ray.org_x = origin.x();
  ray.org_y = origin.y();
  ray.org_z = origin.z();
  ray.dir_x = dir.x();
  ray.dir_y = dir.y();
  ray.dir_z = dir.z();
  ray.tnear = t_near;
  ray.tfar = t_far;
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
}

bool Query(RTCScene scene, const Vec3f& origin, const Vec3f& dir, float t_near, float t_far, RTCRayHit* rh) {
  InitRay(rh->ray, origin, dir, t_near, t_far);
  rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene, &context, rh);
  return rh->hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

}  // namespace

RayTracer::RayTracer(const SceneMesh& mesh) : mesh_(mesh), impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (impl_->device == nullptr) {
    throw Error(fmt::format("Embree: cannot create a device (error {})", static_cast<int>(rtcGetDeviceError(nullptr))));
  }
  impl_->opaque = rtcNewScene(impl_->device);
  impl_->glass = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->opaque, RTC_BUILD_QUALITY_HIGH);
  for (std::size_t i = 0; i < mesh.objects.size(); ++i) {
    const MeshObject& o = mesh.objects[i];
    if (o.triangles.empty()) continue;
    bool glass = o.role == SurfaceRole::kGlass;
    AttachMesh(impl_->device, glass ? impl_->glass : impl_->opaque, o);
    (glass ? impl_->glass_objects : impl_->opaque_objects).push_back(static_cast<int>(i));
  }
  rtcCommitScene(impl_->opaque);
  rtcCommitScene(impl_->glass);
}

RayTracer::~RayTracer() = default;

bool RayTracer::Intersect(const Vec3f& origin, const Vec3f& dir, float t_near, float t_far, bool with_glass,
                          RayHit* hit) const {
  RTCRayHit rh;
  bool found = false;
  if (Query(impl_->opaque, origin, dir, t_near, t_far, &rh)) {
    found = true;
    hit->t = rh.ray.tfar;
    hit->object = impl_->opaque_objects[rh.hit.geomID];
    hit->triangle = static_cast<int>(rh.hit.primID);
    hit->geometric_normal = Vec3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z).normalized();
    t_far = rh.ray.tfar;
  }
  if (with_glass && !impl_->glass_objects.empty() && Query(impl_->glass, origin, dir, t_near, t_far, &rh)) {
    found = true;
    hit->t = rh.ray.tfar;
    hit->object = impl_->glass_objects[rh.hit.geomID];
    hit->triangle = static_cast<int>(rh.hit.primID);
    hit->geometric_normal = Vec3f(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z).normalized();
  }
  return found;
}

bool RayTracer::Occluded(const Vec3f& origin, const Vec3f& dir, float t_near, float t_far) const {
  RTCRay ray;
  InitRay(ray, origin, dir, t_near, t_far);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(impl_->opaque, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar = −inf on a hit.
}

}  // namespace asbuilt
