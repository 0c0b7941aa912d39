#include "asbuilt/plan/dxf.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/plan/reconstruct.h"
#include "asbuilt/plan/sample.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

// Debian's python3 with python3-ezdxf: the independent DXF reader.
const char* kPython = "/usr/bin/python3";

struct ShellResult {
  int exit_code = -1;
  std::string out;
};

ShellResult Shell(const std::string& cmd) {
  ShellResult r;
  std::FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

bool HaveEzdxf() { return Shell(std::string(kPython) + " -c 'import ezdxf'").exit_code == 0; }

ShellResult CheckWithEzdxf(const Plan& plan, const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("asbuilt_dxf_" + name);
  fs::create_directories(dir);
  WritePlan(plan, dir / "plan.json");
  WritePlanDxf(plan, dir / "plan.dxf");
  std::string script = std::string(ASBUILT_SOURCE_DIR) + "/src/asbuilt/plan/dxf_check.py";
  return Shell(fmt::format("{} {} {} {}", kPython, script, (dir / "plan.dxf").string(), (dir / "plan.json").string()));
}

TEST(PlanDxf, EzdxfAuditsCleanAndReadsBackWallsAndDimensionsTo1mm) {
  if (!HaveEzdxf()) GTEST_SKIP() << "python3-ezdxf not installed";
  fs::path truth = fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public/p02_L_shape/truth.json";
  if (!fs::exists(truth)) GTEST_SKIP() << "shared data not present: " << truth;
  ShellResult r = CheckWithEzdxf(ReadPlan(truth), "truth");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out.rfind("ok: 6 walls, 9 dimensions", 0), 0u) << r.out;
}

TEST(PlanDxf, ReconstructedRotatedPlanWithUncertaintiesPassesTheReader) {
  if (!HaveEzdxf()) GTEST_SKIP() << "python3-ezdxf not installed";
  Plan truth;
  std::vector<Vec2> c = {{0, 0}, {5, 0}, {5, 4}, {0, 4}};
  Eigen::Rotation2Dd rot(DegToRad(31));
  for (Vec2& p : c) p = rot * p + Vec2(2, -1);
  for (int i = 0; i < 4; ++i) truth.walls.push_back({.start = c[i], .end = c[(i + 1) % 4], .height = 2.6});
  Vec2 d = (c[1] - c[0]).normalized();
  truth.openings.push_back({.kind = OpeningKind::kDoor,
                            .wall = 0,
                            .start = c[0] + 1.0 * d,
                            .end = c[0] + 1.9 * d,
                            .width = 0.9,
                            .height = 2.0,
                            .sill = 0.0});
  truth.rooms.push_back({.polygon = c, .area_m2 = 20});
  PlanResult r = ReconstructPlan(SamplePointsFromPlan(truth, {}, 5), {});
  ShellResult run = CheckWithEzdxf(r.plan, "reconstructed");
  EXPECT_EQ(run.exit_code, 0) << run.out;
}

TEST(PlanDxf, WritesMetresAndTheLayers) {
  Plan plan;
  plan.walls.push_back({.start = {0, 0}, .end = {3, 0}});
  std::string dxf = PlanToDxf(plan);
  EXPECT_NE(dxf.find("$INSUNITS\n 70\n6\n"), std::string::npos);
  EXPECT_NE(dxf.find("AC1015"), std::string::npos);
  for (const char* layer : {"WALLS", "DOORS", "WINDOWS", "DIMENSIONS", "TEXT"}) {
    EXPECT_NE(dxf.find(std::string("\n  2\n") + layer + "\n"), std::string::npos) << layer;
  }
  EXPECT_EQ(dxf.substr(dxf.size() - 8), "  0\nEOF\n");
}

}  // namespace
}  // namespace asbuilt
