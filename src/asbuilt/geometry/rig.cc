#include "asbuilt/geometry/rig.h"

#include <cmath>

#include <fmt/format.h>

#include "asbuilt/util/error.h"

namespace asbuilt {

PinholeCamera PinholeCamera::FromHorizontalFov(int width_px, int height_px, double hfov_deg) {
  CheckArgument(hfov_deg > 0 && hfov_deg < 180, fmt::format("hfov_deg = {}, must be in (0, 180)", hfov_deg));
  double f = 0.5 * width_px / std::tan(0.5 * DegToRad(hfov_deg));
  return {.width_px = width_px,
          .height_px = height_px,
          .fx = f,
          .fy = f,
          .cx = 0.5 * width_px - 0.5,
          .cy = 0.5 * height_px - 0.5};
}

double PinholeCamera::HorizontalFovDeg() const { return RadToDeg(2.0 * std::atan(0.5 * width_px / fx)); }

void PinholeCamera::Check() const {
  CheckArgument(width_px > 0, fmt::format("PinholeCamera.width_px = {}, must be > 0", width_px));
  CheckArgument(height_px > 0, fmt::format("PinholeCamera.height_px = {}, must be > 0", height_px));
  CheckArgument(std::isfinite(fx) && fx > 0, fmt::format("PinholeCamera.fx = {}, must be > 0", fx));
  CheckArgument(std::isfinite(fy) && fy > 0, fmt::format("PinholeCamera.fy = {}, must be > 0", fy));
  CheckArgument(std::isfinite(cx), fmt::format("PinholeCamera.cx = {}, must be finite", cx));
  CheckArgument(std::isfinite(cy), fmt::format("PinholeCamera.cy = {}, must be finite", cy));
}

std::string PinholeCamera::ToString() const {
  return fmt::format("PinholeCamera({}x{} fx={:.3f} fy={:.3f} cx={:.3f} cy={:.3f})", width_px, height_px, fx, fy, cx,
                     cy);
}

std::string RigPose::ToString() const {
  return fmt::format("RigPose(position_m=[{:.3f}, {:.3f}, {:.3f}] yaw_deg={:.2f})", position_m.x(), position_m.y(),
                     position_m.z(), RadToDeg(yaw_rad));
}

Vec3 ForwardFromYaw(double yaw_rad) { return {-std::sin(yaw_rad), std::cos(yaw_rad), 0.0}; }

Vec3 RightFromYaw(double yaw_rad) { return {std::cos(yaw_rad), std::sin(yaw_rad), 0.0}; }

Mat3 WorldFromCameraRotation(double yaw_rad) {
  Mat3 r;
  r.col(0) = RightFromYaw(yaw_rad);
  r.col(1) = Vec3(0, 0, -1);
  r.col(2) = ForwardFromYaw(yaw_rad);
  return r;
}

Vec3 EyeCentre(const RigPose& pose, double baseline_m, StereoEye eye) {
  double sign = eye == StereoEye::kLeft ? -0.5 : 0.5;
  return pose.position_m + sign * baseline_m * RightFromYaw(pose.yaw_rad);
}

Eigen::Isometry3d WorldFromCamera(const RigPose& pose, double baseline_m, StereoEye eye) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = WorldFromCameraRotation(pose.yaw_rad);
  t.translation() = EyeCentre(pose, baseline_m, eye);
  return t;
}

Vec3 UnprojectToCamera(const PinholeCamera& camera, const Vec2& pixel, double z_m) {
  return {(pixel.x() - camera.cx) / camera.fx * z_m, (pixel.y() - camera.cy) / camera.fy * z_m, z_m};
}

std::optional<Vec2> ProjectFromCamera(const PinholeCamera& camera, const Vec3& point_in_camera) {
  if (!(point_in_camera.z() > 0)) return std::nullopt;
  return Vec2(camera.fx * point_in_camera.x() / point_in_camera.z() + camera.cx,
              camera.fy * point_in_camera.y() / point_in_camera.z() + camera.cy);
}

std::optional<double> DepthFromDisparity(double fx, double baseline_m, double disparity_px) {
  if (!(disparity_px > 0)) return std::nullopt;
  return fx * baseline_m / disparity_px;
}

double DepthSigmaFromDisparitySigma(double fx, double baseline_m, double z_m, double disparity_sigma_px) {
  return z_m * z_m * disparity_sigma_px / (fx * baseline_m);
}

}  // namespace asbuilt
