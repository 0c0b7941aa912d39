#ifndef ASBUILT_GEOMETRY_RIG_H_
#define ASBUILT_GEOMETRY_RIG_H_

// The normative conventions of DESIGN.md in code: world frame (+Z up, floor
// z = 0), yaw (about +Z, 0 looks along +Y, counter-clockwise positive), the
// OpenCV camera frame (x right, y down, z forward), OpenCV pixel centres (the
// top-left pixel's centre is (0, 0)), and the parallel stereo rig (position =
// rig centre; left camera at −B/2 along the rig's right axis).
// Every module that maps between pixels and the world goes through here.

#include <optional>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace asbuilt {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// Plan (floor) geometry: the z component of a × b, and `d` turned +90°.
inline double Cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
inline Vec2 Perp(const Vec2& d) { return Vec2(-d.y(), d.x()); }

inline constexpr double kPi = 3.14159265358979323846;
inline double DegToRad(double deg) { return deg * kPi / 180.0; }
inline double RadToDeg(double rad) { return rad * 180.0 / kPi; }

// Pinhole intrinsics in pixels (OpenCV pixel-centre convention).
struct PinholeCamera {
  int width_px = 640;
  int height_px = 480;
  double fx = 400.0;
  double fy = 400.0;
  double cx = 319.5;  // (width − 1) / 2 is the image centre.
  double cy = 239.5;

  // Horizontal-FOV camera with the principal point at the image centre.
  static PinholeCamera FromHorizontalFov(int width_px, int height_px, double hfov_deg);
  double HorizontalFovDeg() const;
  // Throws InvalidArgument naming the field ("PinholeCamera.fx = 0, must be > 0").
  void Check() const;
  std::string ToString() const;
};

// Pose of a level stereo rig: its centre in the world and its yaw.
struct RigPose {
  Vec3 position_m = Vec3::Zero();
  double yaw_rad = 0.0;

  std::string ToString() const;
};

enum class StereoEye { kLeft, kRight };

// Rig axes in the world for a yaw: forward (−sin ψ, cos ψ, 0), right
// (cos ψ, sin ψ, 0), down (0, 0, −1).
Vec3 ForwardFromYaw(double yaw_rad);
Vec3 RightFromYaw(double yaw_rad);

// Rotation taking camera-frame vectors (x right, y down, z forward) into the
// world frame for a level camera at this yaw. Columns: right, down, forward.
Mat3 WorldFromCameraRotation(double yaw_rad);

// Optical centre of one eye: position ∓ (B/2)·right.
Vec3 EyeCentre(const RigPose& pose, double baseline_m, StereoEye eye);

// Rigid transform camera → world for one eye of the rig.
Eigen::Isometry3d WorldFromCamera(const RigPose& pose, double baseline_m, StereoEye eye);

// Pixel (u, v) with depth z (along the optical axis) → camera-frame point.
Vec3 UnprojectToCamera(const PinholeCamera& camera, const Vec2& pixel, double z_m);
// Camera-frame point → pixel; nullopt when the point is not in front (z ≤ 0).
std::optional<Vec2> ProjectFromCamera(const PinholeCamera& camera, const Vec3& point_in_camera);

// Rectified parallel stereo: depth from disparity d = u_left − u_right,
// Z = fx·B/d (nullopt for d ≤ 0), and its standard deviation for a disparity
// error σ_d: σ_Z = Z²·σ_d/(fx·B).
std::optional<double> DepthFromDisparity(double fx, double baseline_m, double disparity_px);
double DepthSigmaFromDisparitySigma(double fx, double baseline_m, double z_m, double disparity_sigma_px);

}  // namespace asbuilt

#endif  // ASBUILT_GEOMETRY_RIG_H_
