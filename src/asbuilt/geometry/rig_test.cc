#include "asbuilt/geometry/rig.h"

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {

void ExpectNear(const Vec3& a, const Vec3& b, double tol = 1e-12) {
  EXPECT_NEAR((a - b).norm(), 0.0, tol) << a.transpose() << " vs " << b.transpose();
}

TEST(Yaw, ZeroLooksAlongPlusYAndNinetyAlongMinusX) {
  ExpectNear(ForwardFromYaw(0), Vec3(0, 1, 0));
  ExpectNear(RightFromYaw(0), Vec3(1, 0, 0));
  ExpectNear(ForwardFromYaw(DegToRad(90)), Vec3(-1, 0, 0));
  ExpectNear(RightFromYaw(DegToRad(90)), Vec3(0, 1, 0));
}

TEST(WorldFromCamera, IsRightHandedRotation) {
  Mat3 r = WorldFromCameraRotation(DegToRad(37));
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  EXPECT_NEAR((r.transpose() * r - Mat3::Identity()).norm(), 0.0, 1e-12);
}

TEST(EyeCentre, LeftEyeSitsHalfBaselineToTheLeft) {
  RigPose pose{.position_m = Vec3(2.1, 1.6, 1.45), .yaw_rad = DegToRad(90)};
  ExpectNear(EyeCentre(pose, 0.12, StereoEye::kLeft), Vec3(2.1, 1.54, 1.45));
  ExpectNear(EyeCentre(pose, 0.12, StereoEye::kRight), Vec3(2.1, 1.66, 1.45));
}

// The projection recipe of shared/data/blender-rooms-public/README.md.
TEST(WorldFromCamera, MatchesBlenderRoomsProjectionRecipe) {
  PinholeCamera cam = PinholeCamera::FromHorizontalFov(640, 480, 80);
  RigPose pose{.position_m = Vec3(1, 2, 1.5), .yaw_rad = DegToRad(-30)};
  Vec3 p_world(0.3, 5.0, 0.4);
  Vec3 c_left = EyeCentre(pose, 0.12, StereoEye::kLeft);
  Vec3 q = p_world - c_left;
  Vec3 r = RightFromYaw(pose.yaw_rad), f = ForwardFromYaw(pose.yaw_rad);
  double x = q.dot(r), y = -q.z(), z = q.dot(f);
  Vec2 expected(cam.fx * x / z + cam.cx, cam.fy * y / z + cam.cy);

  Eigen::Isometry3d world_from_cam = WorldFromCamera(pose, 0.12, StereoEye::kLeft);
  auto uv = ProjectFromCamera(cam, world_from_cam.inverse() * p_world);
  ASSERT_TRUE(uv);
  EXPECT_NEAR((*uv - expected).norm(), 0.0, 1e-9);
  // And back.
  Vec3 back = world_from_cam * UnprojectToCamera(cam, *uv, z);
  ExpectNear(back, p_world, 1e-9);
}

TEST(Stereo, DisparityIsPositiveAndGivesDepth) {
  PinholeCamera cam = PinholeCamera::FromHorizontalFov(640, 480, 80);
  RigPose pose{.position_m = Vec3(0, 0, 1.5), .yaw_rad = DegToRad(20)};
  Vec3 p_world = pose.position_m + 3.0 * ForwardFromYaw(pose.yaw_rad) + Vec3(0.2, 0, 0.3);
  auto ul = ProjectFromCamera(cam, WorldFromCamera(pose, 0.12, StereoEye::kLeft).inverse() * p_world);
  auto ur = ProjectFromCamera(cam, WorldFromCamera(pose, 0.12, StereoEye::kRight).inverse() * p_world);
  ASSERT_TRUE(ul && ur);
  EXPECT_NEAR(ul->y(), ur->y(), 1e-9);
  double d = ul->x() - ur->x();
  EXPECT_GT(d, 0);
  double z = (WorldFromCamera(pose, 0.12, StereoEye::kLeft).inverse() * p_world).z();
  EXPECT_NEAR(*DepthFromDisparity(cam.fx, 0.12, d), z, 1e-9);
  EXPECT_FALSE(DepthFromDisparity(cam.fx, 0.12, 0.0));
}

TEST(PinholeCamera, CentreIsHalfPixelInsideOpenCvConvention) {
  PinholeCamera cam = PinholeCamera::FromHorizontalFov(640, 480, 80);
  EXPECT_DOUBLE_EQ(cam.cx, 319.5);
  EXPECT_DOUBLE_EQ(cam.cy, 239.5);
  EXPECT_NEAR(cam.fx, 381.3611, 1e-4);
  EXPECT_NEAR(cam.HorizontalFovDeg(), 80.0, 1e-9);
}

TEST(PinholeCamera, CheckNamesTheField) {
  PinholeCamera cam;
  cam.fx = 0;
  try {
    cam.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "PinholeCamera.fx = 0, must be > 0");
  }
}

TEST(PinholeCamera, PrintsItself) {
  EXPECT_EQ(PinholeCamera{}.ToString(), "PinholeCamera(640x480 fx=400.000 fy=400.000 cx=319.500 cy=239.500)");
}

}  // namespace
}  // namespace asbuilt
