#include "asbuilt/mcp/tools.h"

#include <unistd.h>

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/scene/scene_json.h"

namespace asbuilt::mcp {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

class ToolsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("asbuilt_tools_test_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    tools_ = std::make_unique<SceneTools>(Workspace(root_ / "ws"), limits_);
  }
  void TearDown() override { fs::remove_all(root_); }

  // Calls a tool, expects success, returns its first text block.
  std::string Ok(std::string_view tool, const nlohmann::json& args = nullptr) {
    ToolResult r = tools_->Call(tool, args);
    EXPECT_FALSE(r.is_error) << tool << " " << args.dump() << " → " << (r.content.empty() ? "" : r.content.back().text);
    for (const ToolContent& c : r.content) {
      if (c.kind == ToolContent::Kind::kText) return c.text;
    }
    return "";
  }
  // Calls a tool, expects an error result, returns its message.
  std::string Fails(std::string_view tool, const nlohmann::json& args = nullptr) {
    ToolResult r = tools_->Call(tool, args);
    EXPECT_TRUE(r.is_error) << tool << " " << args.dump();
    return r.content.empty() ? "" : r.content.front().text;
  }
  void Classroom() {
    Ok("new_scene", {{"name", "classroom"}});
    Ok("add_room", {{"width_m", 6}, {"depth_m", 8}, {"height_m", 3}});
    Ok("add_door", {{"side", "east"}, {"width_m", 1.0}});
    Ok("add_window", {{"side", "north"}, {"width_m", 1.5}, {"count", 2}});
  }

  ToolLimits limits_;
  fs::path root_;
  std::unique_ptr<SceneTools> tools_;
};

TEST_F(ToolsTest, EveryToolHasASchemaAndDescription) {
  nlohmann::json list = tools_->ListJson();
  std::set<std::string> names;
  for (const auto& t : list) {
    names.insert(t["name"]);
    EXPECT_EQ(t["inputSchema"]["type"], "object") << t["name"];
    EXPECT_FALSE(t["description"].get<std::string>().empty());
    EXPECT_EQ(t["annotations"]["openWorldHint"], false);
  }
  for (const char* required : {"new_scene", "add_room", "add_door", "add_window", "add_furniture", "set_material",
                               "set_lighting", "place_rig", "scene_from_text", "describe_scene", "validate_scene",
                               "render_preview", "render_capture", "export_plan", "save_scene", "load_scene"}) {
    EXPECT_TRUE(names.count(required)) << required;
  }
}

TEST_F(ToolsTest, BuildsARoomWithADoorAndTwoWindowsAndExportsItsPlan) {
  Classroom();
  ToolResult r = tools_->Call("export_plan", nullptr);
  ASSERT_FALSE(r.is_error) << r.content[0].text;
  Plan plan = PlanFromJson(nlohmann::json::parse(r.content[0].text), "reply");
  ASSERT_EQ(plan.walls.size(), 4u);
  EXPECT_NEAR(plan.walls[0].Length(), 6.0, 1e-9);
  EXPECT_NEAR(plan.walls[1].Length(), 8.0, 1e-9);
  ASSERT_EQ(plan.openings.size(), 3u);
  int doors = 0, windows = 0;
  for (const PlanOpening& o : plan.openings) {
    if (o.kind == OpeningKind::kDoor) {
      ++doors;
      EXPECT_NEAR(o.width, 1.0, 1e-9);
      EXPECT_EQ(o.wall, 1);  // East wall: (6,0) → (6,8).
    } else {
      ++windows;
      EXPECT_NEAR(o.width, 1.5, 1e-9);
      EXPECT_EQ(o.wall, 2);  // North wall.
      EXPECT_NEAR(*o.sill, 0.9, 1e-9);
      // Each centred in one of two equal bays of the 6 m wall, as the text parser spaces them.
      const double centre = o.Centre().x();
      EXPECT_TRUE(std::abs(centre - 1.5) < 1e-9 || std::abs(centre - 4.5) < 1e-9) << centre;
    }
  }
  EXPECT_EQ(doors, 1);
  EXPECT_EQ(windows, 2);
  EXPECT_EQ(r.structured["walls"].size(), 4u);
  ASSERT_EQ(plan.rooms.size(), 1u);
  EXPECT_NEAR(plan.rooms[0].area_m2, 48.0, 1e-9);
}

TEST_F(ToolsTest, AddRoomRepliesWithNumberedWallsAndDirections) {
  std::string reply = Ok("add_room", {{"width_m", 4}, {"depth_m", 3}, {"origin", {1, 2}}});
  EXPECT_THAT(reply, HasSubstr("wall 0: (1.00, 2.00) → (5.00, 2.00), 4.00 m, faces south"));
  EXPECT_THAT(reply, HasSubstr("wall 1: (5.00, 2.00) → (5.00, 5.00), 3.00 m, faces east"));
  EXPECT_THAT(reply, HasSubstr("faces north"));
  EXPECT_THAT(reply, HasSubstr("faces west"));
}

TEST_F(ToolsTest, AddRoomReversesClockwisePolygonsAndRotates) {
  std::string reply = Ok("add_room", {{"polygon", {{0, 0}, {0, 3}, {4, 3}, {4, 0}}}});
  EXPECT_THAT(reply, HasSubstr("reversed"));
  EXPECT_GT(PolygonArea(tools_->scene().rooms[0].polygon), 0);
  Ok("add_room", {{"width_m", 2}, {"depth_m", 2}, {"origin", {10, 0}}, {"rotation_deg", 90}});
  const Room& r = tools_->scene().rooms[1];
  EXPECT_NEAR(r.polygon[1].x(), 10.0, 1e-9);
  EXPECT_NEAR(r.polygon[1].y(), 2.0, 1e-9);
}

TEST_F(ToolsTest, AddRoomArgumentErrorsSayWhatIsAllowed) {
  EXPECT_THAT(Fails("add_room", {{"width_m", 6}, {"depth_m", 8}, {"polygon", {{0, 0}, {1, 0}, {1, 1}}}}),
              HasSubstr("either width_m and depth_m"));
  EXPECT_THAT(Fails("add_room", {{"width_m", 6}}), HasSubstr("arguments.depth_m: required with width_m"));
  EXPECT_THAT(Fails("add_room", {{"width_m", -6}, {"depth_m", 8}}),
              HasSubstr("arguments.width_m: must be > 0 and <= 200, got -6"));
  EXPECT_THAT(Fails("add_room", {{"width_m", "six"}, {"depth_m", 8}}),
              HasSubstr("arguments.width_m: must be a finite number, got \"six\""));
  EXPECT_THAT(Fails("add_room", {{"width_m", 6}, {"depth_m", 8}, {"colour", "red"}}),
              HasSubstr("arguments.colour: unknown argument; allowed: width_m, depth_m"));
  // Self-intersecting polygon: the scene's own validation, scene unchanged.
  EXPECT_THAT(Fails("add_room", {{"polygon", {{0, 0}, {4, 4}, {4, 0}, {0, 4}}}}), HasSubstr("nothing was changed"));
  EXPECT_TRUE(tools_->scene().rooms.empty());
}

TEST_F(ToolsTest, OpeningErrorsNameTheArgument) {
  EXPECT_THAT(Fails("add_door", {{"wall", 0}}), HasSubstr("no room yet"));
  Ok("add_room", {{"width_m", 4}, {"depth_m", 3}, {"height_m", 2.5}});
  EXPECT_THAT(Fails("add_door", {{"wall", 7}}), HasSubstr("arguments.wall: room 0 has walls 0..3, got 7"));
  EXPECT_THAT(Fails("add_door", nlohmann::json::object()), HasSubstr("give either wall"));
  EXPECT_THAT(Fails("add_door", {{"wall", 0}, {"room", 3}}),
              HasSubstr("arguments.room: the scene has rooms 0..0, got 3"));
  EXPECT_THAT(Fails("add_window", {{"wall", 0}, {"height_m", 2}, {"sill_m", 1}}),
              HasSubstr("arguments.height_m: sill 1.00 m + height 2.00 m = 3.00 m is above the 2.50 m ceiling"));
  EXPECT_THAT(Fails("add_door", {{"wall", 1}, {"offset_m", 2.5}, {"width_m", 0.9}}),
              HasSubstr("arguments.offset_m: the door would end at 3.40 m but wall 1 is 3.00 m long"));
  EXPECT_THAT(Fails("add_window", {{"wall", 1}, {"count", 3}, {"width_m", 1.2}}), HasSubstr("do not fit on wall 1"));
  EXPECT_THAT(Fails("add_door", {{"side", "up"}}), HasSubstr("arguments.side: must be one of \"north\""));
  // Overlap with an existing opening: scene validation, nothing changed.
  Ok("add_door", {{"wall", 0}, {"offset_m", 1}});
  EXPECT_THAT(Fails("add_window", {{"wall", 0}, {"offset_m", 1.2}, {"width_m", 1}}),
              HasSubstr("would make the scene invalid"));
  EXPECT_EQ(tools_->scene().rooms[0].openings.size(), 1u);
}

TEST_F(ToolsTest, DiagonalSideOfARotatedRoom) {
  Ok("add_room", {{"width_m", 4}, {"depth_m", 4}, {"rotation_deg", 45}});
  Ok("add_window", {{"side", "north-west"}});
  int wall = tools_->scene().rooms[0].openings[0].wall;
  EXPECT_EQ(WallCompassName(tools_->scene().rooms[0], wall), "north-west");
  EXPECT_THAT(Fails("add_window", {{"side", "north"}}), HasSubstr("no wall of this room faces north"));
}

TEST_F(ToolsTest, FurnitureMaterialsLightingAndRig) {
  Classroom();
  Ok("add_furniture", {{"centre", {3, 4}}, {"kind", "table"}});
  EXPECT_NEAR(tools_->scene().furniture[0].size_m.x(), 1.6, 1e-9);
  Ok("add_furniture", {{"centre", {1, 1}}, {"size_m", {0.5, 0.5, 1}}, {"yaw_deg", 30}});
  EXPECT_THAT(Fails("add_furniture", {{"centre", {1, 1}}, {"size_m", {0, 1, 1}}}),
              HasSubstr("arguments.size_m[0]: must be > 0"));

  std::string m = Ok("set_material",
                     {{"name", "brick"}, {"base_color", {0.6, 0.3, 0.2}}, {"texture", "tiles"}, {"apply_to", "walls"}});
  EXPECT_THAT(m, HasSubstr("applied to 1 walls"));
  EXPECT_EQ(tools_->scene().rooms[0].wall_material, "brick");
  EXPECT_THAT(Fails("set_material", {{"name", "x"}, {"texture", "marble"}}),
              HasSubstr("arguments.texture: must be one of \"none\", \"plaster\""));

  Ok("set_lighting", {{"kind", "area"}, {"intensity", 2}});
  ASSERT_EQ(tools_->scene().lights.size(), 1u);
  EXPECT_NEAR(tools_->scene().lights[0].position_m.x(), 3.0, 1e-9);  // Room centre.
  Ok("set_lighting", {{"mode", "add"}, {"kind", "sun"}, {"ambient", 0.3}});
  EXPECT_EQ(tools_->scene().lights.size(), 2u);
  EXPECT_EQ(tools_->scene().environment.ambient, 0.3);

  std::string rig = Ok("place_rig", {{"step_deg", 45}});
  EXPECT_THAT(rig, HasSubstr("8 views"));
  EXPECT_EQ(CountViews(tools_->scene()), 8u);
  Ok("place_rig", {{"position", {2, 2}}, {"yaws_deg", {0, 90}}, {"width_px", 320}, {"height_px", 240}});
  EXPECT_EQ(CountViews(tools_->scene()), 2u);
  EXPECT_EQ(tools_->scene().rig.width_px, 320);
  EXPECT_THAT(Fails("place_rig", {{"position", {20, 20}}}), HasSubstr("would make the scene invalid"));
}

TEST_F(ToolsTest, LimitsOnViewsAndImageSize) {
  Classroom();
  EXPECT_THAT(Fails("place_rig", {{"step_deg", 1}}),
              HasSubstr("a full turn at 1 ° steps is 360 views; the limit is 72"));
  EXPECT_THAT(Fails("place_rig", {{"width_px", 8000}}),
              HasSubstr("arguments.width_px: must be an integer >= 16 and <= 1920, got 8000"));
  EXPECT_THAT(Fails("render_preview", {{"width_px", 100000}}), HasSubstr("arguments.width_px"));
}

TEST_F(ToolsTest, SceneSizeLimits) {
  limits_.max_rooms = 2;
  limits_.max_openings = 2;
  limits_.max_furniture = 1;
  tools_ = std::make_unique<SceneTools>(Workspace(root_ / "ws"), limits_);
  Ok("add_room", {{"width_m", 6}, {"depth_m", 8}});
  Ok("add_room", {{"width_m", 2}, {"depth_m", 2}, {"origin", {10, 0}}});
  EXPECT_THAT(Fails("add_room", {{"width_m", 2}, {"depth_m", 2}, {"origin", {20, 0}}}),
              HasSubstr("3 rooms; the limit is 2"));
  Ok("add_window", {{"wall", 2}, {"count", 2}});
  EXPECT_THAT(Fails("add_door", {{"wall", 0}}), HasSubstr("3 doors and windows; the limit is 2"));
  Ok("add_furniture", {{"centre", {1, 1}}});
  EXPECT_THAT(Fails("add_furniture", {{"centre", {2, 2}}}), HasSubstr("the limit is 1"));
}

TEST_F(ToolsTest, DescribeAndValidate) {
  std::string empty = Ok("describe_scene");
  EXPECT_THAT(empty, HasSubstr("needs at least one room"));
  ToolResult v = tools_->Call("validate_scene", nullptr);
  EXPECT_FALSE(v.is_error);
  EXPECT_EQ(v.structured["valid"], false);
  Classroom();
  std::string d = Ok("describe_scene");
  EXPECT_THAT(d, HasSubstr("6.00 × 8.00 m room"));
  EXPECT_THAT(d, HasSubstr("wall 1:"));
  EXPECT_THAT(d, HasSubstr("no rig views yet"));
  v = tools_->Call("validate_scene", nullptr);
  EXPECT_EQ(v.structured["valid"], true);
  EXPECT_THAT(v.content[0].text, HasSubstr("valid"));
  EXPECT_THAT(Fails("validate_scene", {{"strict", true}}), HasSubstr("this tool takes no arguments"));
}

TEST_F(ToolsTest, RenderPreviewReturnsAPngImage) {
  Classroom();
  ToolResult r = tools_->Call("render_preview", {{"width_px", 300}});
  ASSERT_FALSE(r.is_error) << r.content[0].text;
  ASSERT_GE(r.content.size(), 1u);
  EXPECT_EQ(r.content[0].kind, ToolContent::Kind::kImage);
  EXPECT_EQ(r.content[0].mime_type, "image/png");
  EXPECT_EQ(r.content[0].data.substr(0, 8), "iVBORw0K");  // base64 of "\x89PNG\r\n".
  nlohmann::json j = r.ToJson();
  EXPECT_EQ(j["content"][0]["type"], "image");
  EXPECT_EQ(j["content"][0]["mimeType"], "image/png");
}

TEST_F(ToolsTest, FilesStayInsideTheWorkspace) {
  Classroom();
  Ok("export_plan", {{"path", "plans/truth.json"}});
  EXPECT_NO_THROW(ReadPlan(root_ / "ws" / "plans" / "truth.json"));
  EXPECT_THAT(Fails("export_plan", {{"path", "/tmp/evil.json"}}), HasSubstr("absolute path"));
  EXPECT_THAT(Fails("save_scene", {{"path", "../evil.json"}}), HasSubstr("contains \"..\""));
  EXPECT_THAT(Fails("save_scene", {{"path", "a.txt"}}), HasSubstr("must end in .json"));
  fs::create_directories(root_ / "outside");
  fs::create_directory_symlink(root_ / "outside", root_ / "ws" / "link");
  EXPECT_THAT(Fails("save_scene", {{"path", "link/s.json"}}), HasSubstr("leads outside the workspace"));
  EXPECT_THAT(Fails("load_scene", {{"path", "link/s.json"}}), HasSubstr("leads outside the workspace"));
  EXPECT_FALSE(fs::exists(root_ / "outside" / "s.json"));
}

TEST_F(ToolsTest, SaveAndLoadRoundTrip) {
  Classroom();
  Ok("place_rig", {{"step_deg", 30}});
  Ok("save_scene", {{"path", "scenes/classroom.json"}});
  nlohmann::json saved = SceneToJson(tools_->scene());
  Ok("new_scene");
  EXPECT_TRUE(tools_->scene().rooms.empty());
  std::string reply = Ok("load_scene", {{"path", "scenes/classroom.json"}});
  EXPECT_THAT(reply, HasSubstr("6.00 × 8.00 m room"));
  EXPECT_EQ(SceneToJson(tools_->scene()), saved);
  EXPECT_THAT(Fails("load_scene", {{"path", "scenes/missing.json"}}), HasSubstr("is not a file"));
}

TEST_F(ToolsTest, LoadSceneReportsFileProblemsAndLimits) {
  fs::create_directories(root_ / "ws");
  std::ofstream(root_ / "ws" / "broken.json") << "{\"rooms\": [";
  EXPECT_THAT(Fails("load_scene", {{"path", "broken.json"}}), HasSubstr("broken.json"));
  std::ofstream(root_ / "ws" / "bad.json") << R"({"version": 1, "rooms": [{"polygon": [[0,0],[1,0]]}]})";
  EXPECT_THAT(Fails("load_scene", {{"path", "bad.json"}}), HasSubstr("rooms[0]"));
  // A valid scene that asks for too many views.
  Classroom();
  Scene big = tools_->scene();
  big.turn = TurnInPlace{.position_m = Vec3(3, 4, 1.5), .step_deg = 0.01};
  WriteScene(big, root_ / "ws" / "big.json");
  EXPECT_THAT(Fails("load_scene", {{"path", "big.json"}}), HasSubstr("36000 views; the limit is 72"));
  // Larger than the file limit.
  limits_.max_file_bytes = 100;
  tools_ = std::make_unique<SceneTools>(Workspace(root_ / "ws"), limits_);
  EXPECT_THAT(Fails("load_scene", {{"path", "big.json"}}), HasSubstr("the limit is 100"));
}

TEST_F(ToolsTest, SceneFromTextBuildsTheExampleRoom) {
  std::string reply = Ok("scene_from_text", {{"text",
                                              "a 6 by 8 m classroom, 3 m high, with a 1 m wide door on the east "
                                              "wall and two 1.5 m windows on the north wall"}});
  EXPECT_THAT(reply, HasSubstr("6.00 × 8.00 m"));
  ToolResult r = tools_->Call("export_plan", nullptr);
  ASSERT_FALSE(r.is_error) << r.content[0].text;
  EXPECT_EQ(r.structured["openings"].size(), 3u);
  EXPECT_THAT(Fails("scene_from_text", {{"text", std::string(5000, 'a')}}), HasSubstr("at most 4000 characters"));
}

TEST_F(ToolsTest, RandomSceneIsDeterministicPerSeedAndChecksItsOptions) {
  Ok("random_scene", {{"seed", 7}});
  std::string first = SceneToJson(tools_->scene()).dump();
  Ok("random_scene", {{"seed", 8}});
  EXPECT_NE(SceneToJson(tools_->scene()).dump(), first);
  Ok("random_scene", {{"seed", 7}});
  EXPECT_EQ(SceneToJson(tools_->scene()).dump(), first);
  EXPECT_THAT(Fails("random_scene", {{"max_openings", 40}}), HasSubstr("arguments.max_openings: must be"));
  EXPECT_THAT(Fails("random_scene", {{"min_side_m", 8.0}, {"max_side_m", 3.0}}), HasSubstr("max_side_m"));
}

TEST_F(ToolsTest, RandomHomeBuildsAValidHomeOfSeveralRooms) {
  Ok("random_home", {{"seed", 3}, {"rooms", 4}});
  EXPECT_EQ(tools_->scene().rooms.size(), 4u);
  EXPECT_TRUE(ValidateScene(tools_->scene()).empty());
  int doors = 0;
  for (const Room& room : tools_->scene().rooms) {
    for (const Opening& o : room.openings) doors += o.kind == OpeningKind::kDoor;
  }
  EXPECT_GE(doors, 6);  // A door joins each room to the others: both faces of three doors at least.
  const std::string first = SceneToJson(tools_->scene()).dump();
  Ok("random_home", {{"seed", 3}, {"rooms", 4}});
  EXPECT_EQ(SceneToJson(tools_->scene()).dump(), first);
  EXPECT_THAT(Fails("random_home", {{"rooms", 40}}), HasSubstr("arguments.rooms: must be"));
}

TEST_F(ToolsTest, RemoveItem) {
  Classroom();
  Ok("remove_item", {{"what", "opening"}, {"index", 0}});
  EXPECT_EQ(tools_->scene().rooms[0].openings.size(), 2u);
  EXPECT_THAT(Fails("remove_item", {{"what", "furniture"}, {"index", 0}}),
              HasSubstr("there is no furniture to remove"));
}

TEST_F(ToolsTest, ExportPlanOfAnInvalidSceneSaysWhatToFix) {
  EXPECT_THAT(Fails("export_plan"), HasSubstr("needs at least one room"));
}

// A tiny scene that renders in well under a second per view.
void SmallCapturableScene(SceneTools& tools) {
  tools.Call("add_room", {{"width_m", 4}, {"depth_m", 3}});
  tools.Call("add_door", {{"side", "east"}});
  tools.Call("add_window", {{"side", "north"}});
  ToolResult r = tools.Call("place_rig", {{"yaws_deg", {0, 90, 180}}, {"width_px", 48}, {"height_px", 32}});
  ASSERT_FALSE(r.is_error) << r.content[0].text;
}

bool HasTempFolders(const fs::path& root) {
  for (const auto& e : fs::directory_iterator(root)) {
    if (e.path().filename().string().starts_with(kWorkspaceTempPrefix)) return true;
  }
  return false;
}

TEST_F(ToolsTest, RenderCaptureWritesACompleteFolderWithProgress) {
  SmallCapturableScene(*tools_);
  std::vector<std::int64_t> done;
  ToolCallContext ctx;
  ctx.progress = [&](const ProgressUpdate& u) { done.push_back(u.done); };
  ToolResult r = tools_->Call("render_capture", {{"output", "captures/a"}, {"samples_per_pixel", 1}}, ctx);
  ASSERT_FALSE(r.is_error) << r.content[0].text;
  fs::path out = root_ / "ws" / "captures" / "a";
  EXPECT_TRUE(fs::exists(out / "capture.json"));
  EXPECT_TRUE(fs::exists(out / "truth.json"));
  EXPECT_TRUE(fs::exists(out / "scene.json"));
  EXPECT_TRUE(fs::exists(out / "left" / "002.png"));
  EXPECT_EQ(done.back(), 3);
  EXPECT_FALSE(HasTempFolders(root_ / "ws"));
  // Again without overwrite: refused before rendering; with it: replaced.
  EXPECT_THAT(Fails("render_capture", {{"output", "captures/a"}}), HasSubstr("already exists"));
  EXPECT_FALSE(tools_->Call("render_capture", {{"output", "captures/a"}, {"overwrite", true}, {"samples_per_pixel", 1}})
                   .is_error);
  EXPECT_THAT(Fails("render_capture", {{"output", "../a"}}), HasSubstr("contains \"..\""));
}

TEST_F(ToolsTest, CancelledCaptureLeavesNothingBehind) {
  SmallCapturableScene(*tools_);
  std::stop_source stop;
  ToolCallContext ctx;
  ctx.stop = stop.get_token();
  ctx.progress = [&](const ProgressUpdate& u) {
    if (u.done >= 1) stop.request_stop();  // The client leaves after the first view.
  };
  ToolResult r = tools_->Call("render_capture", {{"output", "captures/b"}, {"samples_per_pixel", 1}}, ctx);
  EXPECT_TRUE(r.is_error);
  EXPECT_THAT(r.content[0].text, HasSubstr("cancelled"));
  EXPECT_FALSE(fs::exists(root_ / "ws" / "captures" / "b"));
  EXPECT_FALSE(HasTempFolders(root_ / "ws"));
}

TEST_F(ToolsTest, CameraPreviewRendersTheLeftView) {
  SmallCapturableScene(*tools_);
  ToolResult r = tools_->Call("render_preview", {{"view", "camera"}, {"width_px", 64}, {"view_index", 1}});
  ASSERT_FALSE(r.is_error) << r.content.back().text;
  EXPECT_EQ(r.content[0].kind, ToolContent::Kind::kImage);
  EXPECT_EQ(r.content[0].data.substr(0, 8), "iVBORw0K");
  EXPECT_THAT(Fails("render_preview", {{"view", "camera"}, {"view_index", 5}}),
              HasSubstr("arguments.view_index: the scene has views 0..2, got 5"));
}

TEST_F(ToolsTest, RenderCaptureNeedsAValidSceneWithViews) {
  EXPECT_THAT(Fails("render_capture", {{"output", "c"}}), HasSubstr("needs at least one room"));
  Ok("add_room", {{"width_m", 4}, {"depth_m", 3}});
  EXPECT_THAT(Fails("render_capture", {{"output", "c"}}), HasSubstr("call place_rig first"));
}

TEST_F(ToolsTest, ToolsMarkdownDocumentsEveryTool) {
  std::string md = tools_->ToolsMarkdown();
  EXPECT_THAT(md, HasSubstr("### `add_room`"));
  EXPECT_THAT(md, HasSubstr("| `width_m` |"));
}

}  // namespace
}  // namespace asbuilt::mcp
