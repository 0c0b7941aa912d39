#include "asbuilt/render/renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/render/capture_render.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// A 4 × 3 m room, 2.5 m high: walls at y = 0 (wall 0), x = 4 (1), y = 3 (2),
// x = 0 (3). A closed door on wall 2 (the one a yaw-0 camera faces), a
// window on wall 1.
Scene TestRoom() {
  Scene s;
  s.seed = 3;
  Room r;
  r.name = "room";
  r.polygon = {{0, 0}, {4, 0}, {4, 3}, {0, 3}};
  r.height_m = 2.5;
  r.wall_thickness_m = 0.2;
  // Wall 2 runs from (4, 3) to (0, 3): offset 1.2 puts the door at x ∈ [1.9, 2.8].
  r.openings.push_back({.kind = OpeningKind::kDoor, .wall = 2, .offset_m = 1.2, .width_m = 0.9, .height_m = 2.0});
  r.openings.push_back(
      {.kind = OpeningKind::kWindow, .wall = 1, .offset_m = 0.8, .width_m = 1.2, .height_m = 1.0, .sill_m = 0.9});
  s.rooms.push_back(r);
  s.lights.push_back({.kind = LightKind::kArea, .position_m = Vec3(2, 1.5, 2.5)});
  s.lights.push_back({.kind = LightKind::kSun});
  return s;
}

StereoCamera SmallCamera(const Viewpoint& vp, double fx = 100.0) {
  PinholeCamera k{.width_px = 160, .height_px = 120, .fx = fx, .fy = fx, .cx = 79.5, .cy = 59.5};
  return {k, vp, 0.12};
}

RenderOptions FastOptions() { return {.samples_per_pixel = 2, .camera_effects = 0.0}; }

// Left-eye pixel of a world point (nullopt behind the camera).
std::optional<Vec2> ProjectLeft(const StereoCamera& cam, const Vec3& world) {
  Eigen::Isometry3d world_from_cam = WorldFromStereoEye(cam.viewpoint, cam.baseline_m, StereoEye::kLeft);
  return ProjectFromCamera(cam.camera, world_from_cam.inverse() * world);
}

TEST(RenderOptions, DefaultsAreValid) { EXPECT_NO_THROW(RenderOptions{}.Check()); }

TEST(RenderOptions, RejectsZeroSamplesNamingTheField) {
  try {
    RenderOptions{.samples_per_pixel = 0}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("RenderOptions.samples_per_pixel = 0"), std::string::npos);
  }
}

TEST(Render, DepthEqualsAnalyticDistanceOnWallAndFloor) {
  SceneRenderer renderer(TestRoom());
  // Facing wall 2 (y = 3) from y = 0.5: every wall pixel is 2.5 m away along z.
  StereoCamera cam = SmallCamera({Vec3(2.0, 0.5, 1.25), 0.0, 0.0});
  RenderedView v = renderer.Render(cam, FastOptions(), 0, false);
  const cv::Mat labels = AsMat(v.labels), depth_mm = AsMat(v.depth_mm);
  int wall_checked = 0, floor_checked = 0;
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 160; ++x) {
      int label = labels.at<std::uint8_t>(y, x);
      int depth = depth_mm.at<std::uint16_t>(y, x);
      double ray_z = (y - cam.camera.cy) / cam.camera.fy;  // Downward slope per metre of z.
      if (label == kLabelWall && y > 5 && y < 40 && x > 5 && x < 155) {
        EXPECT_NEAR(depth, 2500, 1) << "wall pixel " << x << "," << y;
        ++wall_checked;
      }
      // Floor: z = 1.25 / slope, in front of the skirting (2.488 m).
      if (ray_z > 0 && 1.25 / ray_z < 2.4 && label == kLabelBackground) {
        EXPECT_NEAR(depth, 1250.0 / ray_z, 1.0) << "floor pixel " << x << "," << y;
        ++floor_checked;
      }
    }
  }
  EXPECT_GT(wall_checked, 1000);
  EXPECT_GT(floor_checked, 300);
}

TEST(Render, PitchedCameraSeesTheCeilingAtTheRightDepth) {
  SceneRenderer renderer(TestRoom());
  Viewpoint vp{Vec3(1.0, 1.0, 1.25), 0.0, 60.0};
  RenderedView v = renderer.Render(SmallCamera(vp), FastOptions(), 0, false);
  // The centre ray of the left eye rises 60°: ceiling 1.25 m above → 1.25 / sin 60°.
  // The centre pixel (79.5, 59.5) is between pixels; (80, 59) is within 0.5 px.
  double expected_mm = 1250.0 / std::sin(DegToRad(60.0));
  int depth = AsMat(v.depth_mm).at<std::uint16_t>(59, 80);
  EXPECT_NEAR(depth, expected_mm, 0.01 * expected_mm);
}

TEST(Render, RightImageIsTheLeftShiftedByTheDisparity) {
  Scene s = TestRoom();
  s.rooms[0].openings.clear();
  s.materials.push_back({.name = "wall",
                         .base_color = Vec3(0.7, 0.6, 0.5),
                         .texture = TextureKind::kWallpaper,
                         .texture_scale_m = 0.2,
                         .secondary_color = Vec3(0.2, 0.3, 0.5)});
  SceneRenderer renderer(s);
  // fx = 100, B = 0.12, Z = 1.5 → d = 8 px exactly.
  StereoCamera cam = SmallCamera({Vec3(2.0, 1.5, 1.25), 0.0, 0.0});
  RenderedView v = renderer.Render(cam, {.samples_per_pixel = 8, .camera_effects = 0.0}, 0, true);
  const cv::Mat labels = AsMat(v.labels);
  cv::Mat l, r;
  cv::cvtColor(AsMat(v.left), l, cv::COLOR_BGR2GRAY);
  cv::cvtColor(AsMat(v.right), r, cv::COLOR_BGR2GRAY);
  double shifted = 0, unshifted = 0;
  int n = 0;
  for (int y = 10; y < 40; ++y) {
    for (int x = 30; x < 130; ++x) {
      ASSERT_EQ(labels.at<std::uint8_t>(y, x), kLabelWall);
      shifted += std::abs(l.at<std::uint8_t>(y, x) - r.at<std::uint8_t>(y, x - 8));
      unshifted += std::abs(l.at<std::uint8_t>(y, x) - r.at<std::uint8_t>(y, x));
      ++n;
    }
  }
  shifted /= n;
  unshifted /= n;
  EXPECT_LT(shifted, 4.0);
  EXPECT_GT(unshifted, 3.0 * shifted);
}

TEST(Render, ProjectedDoorAndWindowCornersLandOnTheirLabels) {
  SceneRenderer renderer(TestRoom());
  // Door clear opening on y = 3: x ∈ [1.9, 2.8], z ∈ [0, 2.0]; corners inset 3 cm.
  const std::vector<Vec3> door = {{1.93, 3, 0.03}, {2.77, 3, 0.03}, {2.77, 3, 1.97}, {1.93, 3, 1.97}};
  // Window on x = 4 (wall 1 from (4, 0) to (4, 3)): y ∈ [0.8, 2.0], z ∈ [0.9, 1.9].
  const std::vector<Vec3> window = {{4, 0.83, 0.93}, {4, 1.97, 0.93}, {4, 1.97, 1.87}, {4, 0.83, 1.87}};
  struct Case {
    std::vector<Vec3> corners;
    double yaw_deg;
    std::uint8_t label;
  };
  for (const Case& c : {Case{door, 0.0, kLabelDoor}, Case{window, -90.0, kLabelWindow}}) {
    StereoCamera cam = SmallCamera({Vec3(2.0, 1.5, 1.3), c.yaw_deg, 0.0}, 70.0);
    RenderedView v = renderer.Render(cam, FastOptions(), 0, false);
    for (std::size_t k = 0; k < c.corners.size(); ++k) {
      auto px = ProjectLeft(cam, c.corners[k]);
      ASSERT_TRUE(px.has_value());
      int u = static_cast<int>(std::lround(px->x())), w = static_cast<int>(std::lround(px->y()));
      ASSERT_TRUE(u >= 0 && u < 160 && w >= 0 && w < 120) << u << "," << w;
      EXPECT_EQ(AsMat(v.labels).at<std::uint8_t>(w, u), c.label) << "corner " << k << " at " << u << "," << w;
    }
  }
}

TEST(Render, DoorLabelAreaMatchesTheProjectedOpeningWithCasing) {
  SceneRenderer renderer(TestRoom());
  StereoCamera cam = SmallCamera({Vec3(2.35, 0.6, 1.2), 0.0, 0.0}, 60.0);
  RenderedView v = renderer.Render(cam, FastOptions(), 0, false);
  // Door incl. casing: x ∈ [1.9 − 0.07, 2.8 + 0.07], z ∈ [0, 2.0 + 0.07] on y = 3.
  std::vector<cv::Point2f> poly;
  for (const Vec3& p : {Vec3(1.83, 3, 0), Vec3(2.87, 3, 0), Vec3(2.87, 3, 2.07), Vec3(1.83, 3, 2.07)}) {
    auto px = ProjectLeft(cam, p);
    ASSERT_TRUE(px.has_value());
    poly.emplace_back(static_cast<float>(px->x()), static_cast<float>(px->y()));
  }
  const cv::Mat labels = AsMat(v.labels);
  int inside = 0, labelled = 0;
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 160; ++x) {
      if (cv::pointPolygonTest(poly, cv::Point2f(x, y), false) >= 0) ++inside;
      if (labels.at<std::uint8_t>(y, x) == kLabelDoor) ++labelled;
    }
  }
  double perimeter = cv::arcLength(poly, true);
  EXPECT_GT(inside, 1000);
  EXPECT_NEAR(labelled, inside, perimeter) << "within a one-pixel band";
}

TEST(Render, SameSeedGivesIdenticalImagesAndAnotherSeedDoesNot) {
  SceneRenderer renderer(TestRoom());
  StereoCamera cam = SmallCamera({Vec3(2.0, 1.0, 1.4), 30.0, 0.0});
  RenderOptions o{.samples_per_pixel = 2, .camera_effects = 1.0, .seed = 5};
  RenderedView a = renderer.Render(cam, o, 7);
  RenderedView b = renderer.Render(cam, o, 7);
  EXPECT_TRUE(a.left.SamePixels(b.left));
  EXPECT_TRUE(a.right.SamePixels(b.right));
  EXPECT_TRUE(a.idmap.SamePixels(b.idmap));
  o.seed = 6;
  RenderedView c = renderer.Render(cam, o, 7);
  EXPECT_GT(cv::norm(AsMat(a.left), AsMat(c.left), cv::NORM_L1), 0);
  EXPECT_TRUE(a.labels.SamePixels(c.labels)) << "labels do not depend on the seed";
}

TEST(Render, IdMapColoursStayNearTheirClassColour) {
  SceneRenderer renderer(TestRoom());
  StereoCamera cam = SmallCamera({Vec3(2.6, 1.2, 1.3), 20.0, 0.0}, 70.0);
  RenderedView v = renderer.Render(cam, {.samples_per_pixel = 2, .id_drift = 0.15, .camera_effects = 0.0}, 0, false);
  const cv::Mat labels = AsMat(v.labels), idmap = AsMat(v.idmap);
  for (int y = 0; y < 120; y += 3) {
    for (int x = 0; x < 160; x += 3) {
      const auto& nominal = kIdMapColors[labels.at<std::uint8_t>(y, x)];
      cv::Vec3b c = idmap.at<cv::Vec3b>(y, x);
      double d = std::hypot(std::hypot(c[2] - nominal[0], c[1] - nominal[1]), c[0] - nominal[2]);
      EXPECT_LT(d, 90.0) << x << "," << y;
    }
  }
}

TEST(RenderCapture, WritesACaptureThatValidatesAndResumes) {
  fs::path dir = fs::path(ASBUILT_BINARY_DIR) / "render_test_capture";
  fs::remove_all(dir);
  Scene s = TestRoom();
  s.rig.width_px = 96;
  s.rig.height_px = 72;
  CaptureRenderOptions o{.render = {.samples_per_pixel = 1, .camera_effects = 0.3}, .views = 3};
  CaptureRenderSummary first = RenderCapture(s, dir, o);
  EXPECT_EQ(first.rendered, 3);
  Capture c = ReadCapture(dir / "capture.json");
  ASSERT_EQ(c.frames.size(), 3u);
  EXPECT_EQ(c.camera.width, 96);
  EXPECT_DOUBLE_EQ(c.camera.cx, 47.5);
  EXPECT_DOUBLE_EQ(c.frames[1].yaw_deg, 120.0);
  ASSERT_TRUE(c.frames[0].depth.has_value());
  EXPECT_EQ(ReadDepthImage(c.Resolve(*c.frames[0].depth)).type(), CV_16U);
  EXPECT_EQ(ReadLabelImage(c.Resolve(*c.frames[0].labels)).size(), cv::Size(96, 72));
  EXPECT_TRUE(fs::exists(dir / "truth.json"));
  EXPECT_TRUE(fs::exists(dir / "idmap" / "002.png"));

  fs::remove(dir / "right" / "001.png");
  CaptureRenderSummary second = RenderCapture(s, dir, o);
  EXPECT_EQ(second.skipped, 2);
  EXPECT_EQ(second.rendered, 1);
  EXPECT_TRUE(fs::exists(dir / "right" / "001.png"));
}

TEST(RenderCapture, RejectsPitchedViewsNamingTheViewpoint) {
  Scene s = TestRoom();
  s.viewpoints.push_back({Vec3(2, 1.5, 1.5), 0.0, 10.0});
  try {
    RenderCapture(s, fs::path(ASBUILT_BINARY_DIR) / "render_test_pitched", {});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems()[0].field_path, "viewpoints[0].pitch_deg");
  }
}

// A 16 × 16 photo: a checkerboard of two colours, for photo albedo tests.
std::shared_ptr<const Photo> CheckerPhoto(PhotoKind kind) {
  auto p = std::make_shared<Photo>();
  p->kind = kind;
  p->path = "checker";
  cv::Mat linear_rgb(16, 16, CV_32FC3);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      linear_rgb.at<cv::Vec3f>(y, x) =
          ((x / 4 + y / 4) % 2) ? cv::Vec3f(0.6f, 0.3f, 0.1f) : cv::Vec3f(0.2f, 0.1f, 0.05f);
    }
  }
  p->linear_rgb = AsImage(linear_rgb);
  p->mean = Vec3f(0.4f, 0.2f, 0.075f);
  p->mean_luminance = 0.2126f * 0.4f + 0.7152f * 0.2f + 0.0722f * 0.075f;
  return p;
}

TEST(Render, AnEmptySceneLookRendersExactlyAsBefore) {
  Scene scene = TestRoom();
  SceneRenderer plain(scene), looked(scene, SceneLook{});
  StereoCamera cam = SmallCamera({Vec3(2.0, 1.5, 1.3), 0.0, 0.0}, 70.0);
  RenderedView a = plain.Render(cam, FastOptions(), 4, false), b = looked.Render(cam, FastOptions(), 4, false);
  EXPECT_TRUE(a.left.SamePixels(b.left));
  EXPECT_TRUE(a.labels.SamePixels(b.labels));
}

TEST(Render, PhotosAndANextRoomChangeColoursNotLabels) {
  Scene scene = TestRoom();
  scene.rooms[0].openings[0].open_deg = 80.0;  // The door (to the outside) stands open.
  SceneLook look;
  look.albedo["wall"] = {.photo = CheckerPhoto(PhotoKind::kPaper), .size_m = 0.4, .colour = 1.0};
  look.outside = CheckerPhoto(PhotoKind::kEnvironment);
  look.outside_gain = 3.0;
  look.mesh.next_room_depth_m = 3.0;
  SceneRenderer plain(scene), looked(scene, look);
  for (double yaw : {0.0, -90.0}) {  // The door, the window.
    StereoCamera cam = SmallCamera({Vec3(2.0, 1.5, 1.3), yaw, 0.0}, 70.0);
    RenderedView a = plain.Render(cam, FastOptions(), 1, false), b = looked.Render(cam, FastOptions(), 1, false);
    EXPECT_TRUE(a.labels.SamePixels(b.labels)) << "yaw " << yaw;
    EXPECT_GT(cv::norm(AsMat(a.left), AsMat(b.left), cv::NORM_L1) / (160.0 * 120.0), 5.0) << "yaw " << yaw;
    if (yaw == 0.0) {
      // Through the doorway the next room's far wall (3 m behind the 0.2 m
      // wall) is farther than the closet's back (1.2 m).
      auto centre = ProjectLeft(cam, Vec3(2.35, 3.0, 1.0));
      ASSERT_TRUE(centre.has_value());
      int u = static_cast<int>(std::lround(centre->x())), v = static_cast<int>(std::lround(centre->y()));
      EXPECT_EQ(AsMat(b.labels).at<std::uint8_t>(v, u), kLabelDoor);
      EXPECT_GT(AsMat(b.depth_mm).at<std::uint16_t>(v, u), AsMat(a.depth_mm).at<std::uint16_t>(v, u) + 1000);
    }
  }
}

TEST(Render, AGlazedDoorIsDoorOverItsWholeOpeningAndShowsTheOutside) {
  Scene solid = TestRoom(), glazed = TestRoom();
  glazed.rooms[0].openings[0].glazed = true;
  for (const MeshObject& o : BuildSceneMesh(glazed).objects) {
    EXPECT_EQ(o.name.find("closet"), std::string::npos) << o.name;  // Nothing walls off the view outside.
    if (o.role == SurfaceRole::kGlass && o.name.find("door") != std::string::npos) {
      EXPECT_EQ(o.label, kLabelDoor);
    }
  }
  StereoCamera cam = SmallCamera({Vec3(2.35, 0.6, 1.2), 0.0, 0.0}, 60.0);
  RenderedView a = SceneRenderer(solid).Render(cam, FastOptions(), 0, false);
  RenderedView b = SceneRenderer(glazed).Render(cam, FastOptions(), 0, false);
  // Same labels: door over the opening with its casing, glass, frame and all.
  EXPECT_TRUE(a.labels.SamePixels(b.labels));
  // Through the pane (upper middle of the leaf) the outside shows, not the white leaf.
  auto pane = ProjectLeft(cam, Vec3(2.55, 3.0, 1.5));  // Beside the glazing bar.
  ASSERT_TRUE(pane.has_value());
  cv::Rect box(static_cast<int>(pane->x()) - 3, static_cast<int>(pane->y()) - 3, 7, 7);
  EXPECT_GT(cv::norm(AsMat(a.left)(box), AsMat(b.left)(box), cv::NORM_L1) / 49.0, 30.0);
  // A wide glazed door is a pair of leaves (French doors), one hinged at each jamb.
  glazed.rooms[0].openings[0].width_m = 1.6;
  glazed.rooms[0].openings[0].offset_m = 0.9;
  glazed.rooms[0].openings[0].open_deg = 70.0;
  for (const MeshObject& o : BuildSceneMesh(glazed).objects) {
    if (o.role == SurfaceRole::kGlass && o.label == kLabelDoor) {
      EXPECT_EQ(o.triangles.size(), 4u) << "two panes";
    }
  }
}

TEST(Render, AMirrorReflectsTheRoomAndIsBackground) {
  Scene plain = TestRoom();
  plain.materials.push_back({.name = "mirror", .base_color = Vec3(0.9, 0.9, 0.9), .roughness = 0.02});
  // Hung on wall 2 left of the door (x ∈ [0.4, 1.4], z ∈ [1.0, 1.8]).
  plain.furniture.push_back({.name = "mirror",
                             .centre_m = Vec2(0.9, 3.0 - 0.0225),
                             .size_m = Vec3(1.0, 0.025, 0.8),
                             .elevation_m = 1.0,
                             .material = "furniture"});
  Scene mirrored = plain;
  mirrored.furniture.back().material = "mirror";
  StereoCamera cam = SmallCamera({Vec3(1.5, 1.0, 1.4), 0.0, 0.0}, 70.0);
  RenderedView a = SceneRenderer(plain).Render(cam, FastOptions(), 0, false);
  RenderedView b = SceneRenderer(mirrored).Render(cam, FastOptions(), 0, false);
  EXPECT_TRUE(a.labels.SamePixels(b.labels));
  auto centre = ProjectLeft(cam, Vec3(0.9, 2.97, 1.4));
  ASSERT_TRUE(centre.has_value());
  int u = static_cast<int>(std::lround(centre->x())), v = static_cast<int>(std::lround(centre->y()));
  EXPECT_EQ(AsMat(b.labels).at<std::uint8_t>(v, u), kLabelBackground);
  cv::Rect box(u - 3, v - 3, 7, 7);
  EXPECT_GT(cv::norm(AsMat(a.left)(box), AsMat(b.left)(box), cv::NORM_L1) / 49.0, 15.0);
}

TEST(Render, ACeilingInTheWallsPaintIsStillBackground) {
  Scene plain = TestRoom(), painted = TestRoom();
  painted.rooms[0].ceiling_material = painted.rooms[0].wall_material;
  StereoCamera cam = SmallCamera({Vec3(2.0, 1.0, 1.4), 0.0, 30.0}, 70.0);  // Up at the wall–ceiling edge.
  RenderedView a = SceneRenderer(plain).Render(cam, FastOptions(), 0, false);
  RenderedView b = SceneRenderer(painted).Render(cam, FastOptions(), 0, false);
  EXPECT_TRUE(a.labels.SamePixels(b.labels));
  const cv::Mat labels = AsMat(b.labels);
  EXPECT_EQ(labels.at<std::uint8_t>(2, 80), kLabelBackground);  // Top row: the ceiling.
  EXPECT_GT(cv::countNonZero(labels == kLabelBackground), 1000);
  EXPECT_GT(cv::norm(AsMat(a.left), AsMat(b.left), cv::NORM_L1), 0.0);
}

TEST(Render, LayoutLabelsLookThroughFurnitureToTheWallAndDoorBehind) {
  Scene s = TestRoom();
  // A sideboard before wall 2 left of the door (x ∈ [0.4, 1.4]) and a chair
  // before the door (x ∈ [2.1, 2.6]), both 0.9 m high.
  s.furniture.push_back({.name = "sideboard", .centre_m = Vec2(0.9, 2.7), .size_m = Vec3(1.0, 0.5, 0.9)});
  s.furniture.push_back({.name = "chair", .centre_m = Vec2(2.35, 2.5), .size_m = Vec3(0.5, 0.5, 0.9)});
  StereoCamera cam = SmallCamera({Vec3(2.0, 0.5, 1.4), 0.0, -10.0}, 70.0);
  RenderOptions layout = FastOptions();
  layout.layout_labels = true;
  const SceneRenderer renderer(s);
  const cv::Mat hit = AsMat(renderer.Render(cam, FastOptions(), 0, false).labels);
  const cv::Mat rule = AsMat(renderer.Render(cam, layout, 0, false).labels);
  auto label_at = [&](const cv::Mat& labels, const Vec3& world) {
    auto px = ProjectLeft(cam, world);
    EXPECT_TRUE(px.has_value() && px->x() >= 0 && px->x() < 159.5 && px->y() >= 0 && px->y() < 119.5);
    return labels.at<std::uint8_t>(static_cast<int>(std::lround(px->y())), static_cast<int>(std::lround(px->x())));
  };
  const Vec3 sideboard_front(0.9, 2.45, 0.5), chair_front(2.35, 2.25, 0.5);
  EXPECT_EQ(label_at(hit, sideboard_front), kLabelBackground);
  EXPECT_EQ(label_at(rule, sideboard_front), kLabelWall);
  EXPECT_EQ(label_at(hit, chair_front), kLabelBackground);
  EXPECT_EQ(label_at(rule, chair_front), kLabelDoor);
  // The shell itself is labelled alike: floor before the furniture, wall above it.
  EXPECT_EQ(label_at(rule, Vec3(2.0, 2.0, 0.0)), kLabelBackground);
  EXPECT_EQ(label_at(rule, Vec3(0.9, 3.0, 1.5)), kLabelWall);
  const cv::Mat differ = hit != rule;
  EXPECT_EQ(cv::countNonZero(differ & (hit != kLabelBackground)), 0);  // Only furniture pixels change.
}

TEST(RandomViewEffects, PhoneProcessingLeavesTheOtherDrawsAlone) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    ViewEffects plain = RandomViewEffects(1.0, seed), phone = RandomViewEffects(1.0, seed, true);
    EXPECT_EQ(plain.chromatic_aberration_px, 0.0);
    EXPECT_EQ(plain.sharpen, 0.0);
    EXPECT_EQ(plain.saturation, 1.0);
    EXPECT_EQ(plain.white_balance, phone.white_balance);
    EXPECT_EQ(plain.vignetting, phone.vignetting);
    EXPECT_EQ(plain.blur_sigma_px, phone.blur_sigma_px);
    EXPECT_GT(phone.chromatic_aberration_px, 0.0);
    EXPECT_NE(phone.ToString().find("phone("), std::string::npos);
    EXPECT_EQ(plain.ToString().find("phone("), std::string::npos);
  }
}

TEST(DevelopImage, ChromaticAberrationKeepsGreenInPlace) {
  cv::Mat linear(40, 60, CV_32FC3, cv::Scalar(0.05, 0.05, 0.05));
  cv::rectangle(linear, cv::Rect(10, 10, 10, 10), cv::Scalar(0.5, 0.5, 0.5), cv::FILLED);
  ViewEffects clean, fringed;
  fringed.chromatic_aberration_px = 2.0;
  const cv::Mat a = AsMat(DevelopImage(AsImage(linear), clean, 1));
  const cv::Mat b = AsMat(DevelopImage(AsImage(linear), fringed, 1));
  std::vector<cv::Mat> ca, cb;
  cv::split(a, ca);
  cv::split(b, cb);
  EXPECT_EQ(cv::norm(ca[1], cb[1], cv::NORM_INF), 0.0);   // Green (BGR index 1).
  EXPECT_GT(cv::norm(ca[2], cb[2], cv::NORM_INF), 20.0);  // Red moved.
}

}  // namespace
}  // namespace asbuilt
