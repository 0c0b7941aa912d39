// The bad-input suite (issue #10): every command, fed broken files and
// arguments, must exit 1 (bad input) or 2 (usage) with ONE message that names
// the file and says what is wrong — no signal, no uncaught-exception text, no
// hang, and no output file (final or temp) left behind.
//
// Table-driven: one row per case. A row names the files to create in its own
// folder ({d}), the command line, the exit code and the substrings the message
// must contain. File contents are literal text unless they start with '<':
//   <copy REL          a file of the base capture ({base}: 2 rendered views)
//   <trunc REL N       its first N bytes
//   <png WxH V         8-bit grey PNG filled with V (0..255) — `noise` for random
//   <rgb WxH V         3-channel PNG; <jpg WxH V the same as JPEG
//   <garbage           bytes that are no image, no JSON
//   <dir               an empty folder
// Rows whose command this build lacks (LibTorch-free builds have no train,
// segment, experiment) are skipped.

#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/cli/cli_test_util.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

struct FileSpec {
  std::string path;      // Relative to the case folder.
  std::string contents;  // Literal text, or a '<' directive (see the top).
};

struct Case {
  std::string name;
  std::vector<FileSpec> files;
  std::string args;                       // After `asbuilt`; {d}, {base}, {src} substituted.
  int exit_code;                          // 1 or 2.
  std::vector<std::string> must_contain;  // Substituted like args.
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name << ": asbuilt " << c.args; }

const int kTimeoutS = 60;

std::string Substitute(std::string s, const std::map<std::string, std::string>& vars) {
  for (const auto& [key, value] : vars) {
    for (std::size_t at = s.find(key); at != std::string::npos; at = s.find(key, at + value.size())) {
      s.replace(at, key.size(), value);
    }
  }
  return s;
}

struct Outcome {
  int status = -1;  // Shell exit status: 124/137 = timeout, 128+n = signal n.
  std::string out;
};

Outcome RunWithTimeout(const std::string& args) {
  testing_util::RunResult run = testing_util::RunAsbuilt(args, kTimeoutS);
  return {.status = run.exit_code, .out = std::move(run.out)};
}

cv::Mat Filled(const std::string& size, const std::string& value, int type) {
  int w = 0, h = 0;
  std::sscanf(size.c_str(), "%dx%d", &w, &h);
  cv::Mat m(h, w, type);
  if (value == "noise") {
    cv::RNG rng(7);
    rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  } else {
    m.setTo(cv::Scalar::all(std::stoi(value)));
  }
  return m;
}

void MakeFile(const fs::path& path, const std::string& contents, const fs::path& base) {
  fs::create_directories(path.parent_path());
  if (contents.empty() || contents[0] != '<') {
    std::ofstream(path, std::ios::binary) << contents;
    return;
  }
  std::istringstream in(contents.substr(1));
  std::string op, a, b;
  in >> op >> a >> b;
  if (op == "copy") {
    fs::copy_file(base / a, path, fs::copy_options::overwrite_existing);
  } else if (op == "trunc") {
    std::ifstream src(base / a, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(src)), {});
    bytes.resize(std::min<std::size_t>(bytes.size(), std::stoul(b)));
    std::ofstream(path, std::ios::binary) << bytes;
  } else if (op == "png") {
    ASSERT_TRUE(cv::imwrite(path.string(), Filled(a, b, CV_8UC1)));
  } else if (op == "rgb" || op == "jpg") {
    ASSERT_TRUE(cv::imwrite(path.string(), Filled(a, b, CV_8UC3)));
  } else if (op == "garbage") {
    std::ofstream(path, std::ios::binary) << "\x89PNG\r\n\x1a\n this is not really a picture \x01\x02\x03";
  } else if (op == "dir") {
    fs::create_directories(path);
  } else {
    FAIL() << "unknown directive " << contents;
  }
}

// Files the failed run created in the case folder (created inputs excluded).
std::vector<std::string> NewFiles(const fs::path& dir, const std::vector<std::string>& before) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::string rel = fs::relative(e.path(), dir).string();
    if (std::find(before.begin(), before.end(), rel) == before.end()) out.push_back(rel);
  }
  return out;
}

std::vector<std::string> ListFiles(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir).string());
  }
  return out;
}

// A capture.json of one frame; {L} {R} are the image paths, {CAM} the camera.
std::string CaptureJson(
    const std::string& left = "l.png", const std::string& right = "r.png",
    const std::string& camera =
        R"("width": 96, "height": 72, "fx": 60, "fy": 60, "cx": 47.5, "cy": 35.5, "baseline_m": 0.12)",
    const std::string& extra = "") {
  return R"({"version": 1, "camera": {)" + camera + R"(}, "rectified": true)" + extra +
         R"(, "frames": [{"index": 0, "left": ")" + left + R"(", "right": ")" + right +
         R"(", "yaw_deg": 0, "position_m": [0, 0, 1.5]}]})";
}

const std::string kCalib640 = R"(%YAML:1.0
---
image_width: 640
image_height: 480
K1: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 400., 0., 319.5, 0., 400., 239.5, 0., 0., 1. ]
D1: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ 0., 0., 0., 0., 0. ]
K2: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 400., 0., 319.5, 0., 400., 239.5, 0., 0., 1. ]
D2: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ 0., 0., 0., 0., 0. ]
R: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 1., 0., 0., 0., 1., 0., 0., 0., 1. ]
T: !!opencv-matrix
   rows: 3
   cols: 1
   dt: d
   data: [ -0.12, 0., 0. ]
rms: 0.3
)";

const std::string kCam96 =
    R"("width": 96, "height": 72, "fx": 60, "fy": 60, "cx": 47.5, "cy": 35.5, "baseline_m": 0.12)";

// Two good 96x72 views, to be combined with one broken thing per row.
const std::vector<FileSpec> kPair = {{"l.png", "<copy left/000.png"}, {"r.png", "<copy right/000.png"}};

std::vector<FileSpec> With(std::vector<FileSpec> a, const std::vector<FileSpec>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

const std::string kPlanOk = R"({"version": 1, "units": "m", "walls": [{"start": [0, 0], "end": [4, 0]},
  {"start": [4, 0], "end": [4, 3]}, {"start": [4, 3], "end": [0, 3]}, {"start": [0, 3], "end": [0, 0]}]})";

std::string Lines(const std::string& line, int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += line + "\n";
  return s;
}

std::string CollinearPoints() {
  std::string s;
  for (int i = 0; i < 200; ++i)
    s += "wall " + std::to_string(i * 0.02) + " 1.0 " + std::to_string(0.5 + (i % 10) * 0.2) + "\n";
  return s;
}

std::vector<Case> Cases() {
  const std::string cap_ok = CaptureJson();
  return {
      // ---------------------------------------------------------------- usage (exit 2)
      {"UnknownCommand", {}, "frobnicate", 2, {"unknown command", "frobnicate"}},
      {"HelpUnknownCommand", {}, "help frobnicate", 2, {"frobnicate"}},
      {"SurveyNoOutput", {}, "survey {d}/capture.json", 2, {"--out"}},
      {"RenderZeroSize", {}, "render {src}/examples/classroom.json -o {d}/out --size 0x0", 2, {"--size"}},
      {"RenderZeroSpp", {}, "render {src}/examples/classroom.json -o {d}/out --spp 0", 2, {"samples-per-pixel"}},
      {"RenderNegativeViews", {}, "render {src}/examples/classroom.json -o {d}/out --views -3", 2, {"views"}},
      {"DisparityBadRange", kPair, "disparity {d}/l.png {d}/r.png -o {d}/out/d.pfm --num-disparities 15", 2, {"16"}},
      {"CalibrateBadBoard",
       kPair,
       "calibrate --left {d}/l.png --right {d}/r.png --board 0x0 -o {d}/out/c.yml",
       2,
       {"board"}},
      {"SceneRandomZeroCount", {}, "scene random --count 0 -o {d}/out", 2, {"count"}},
      {"DatasetSynthNegativeCount", {}, "dataset synth -o {d}/out --count -1", 2, {"count"}},
      {"McpZeroViews", {}, "mcp --workspace {d}/ws --max-views 0", 2, {"max_views"}},
      {"DemoZeroViews", {}, "demo -o {d}/out --views 0", 2, {"views"}},
      {"PlanNegativeEpsilon",
       {{"p.txt", Lines("wall 0 0 1", 3)}},
       "plan {d}/p.txt -o {d}/out --epsilon-m -1",
       2,
       {"--epsilon-m: must be > 0"}},
      {"TrainBadArch", {}, "train --images {d}/img -o {d}/out --arch b9", 2, {"b9"}},
      {"ToyRoomsZeroCount", {}, "experiment toy-rooms -o {d}/out --count 0", 2, {"count"}},

      // ---------------------------------------------------------------- validate
      {"ValidateMissing", {}, "validate {d}/nope.json", 1, {"{d}/nope.json"}},
      {"ValidateEmptyFile", {{"c.json", ""}}, "validate {d}/c.json", 1, {"{d}/c.json"}},
      {"ValidateMalformedJson", {{"c.json", R"({"version": 1, "camera": )"}}, "validate {d}/c.json", 1, {"{d}/c.json"}},
      {"ValidateFolder", {{"folder", "<dir"}}, "validate {d}/folder", 1, {"{d}/folder"}},
      {"ValidateCaptureWrongType",
       With(
           kPair,
           {{"c.json",
             CaptureJson(
                 "l.png", "r.png",
                 R"("width": "wide", "height": 72, "fx": 60, "fy": 60, "cx": 47.5, "cy": 35.5, "baseline_m": 0.12)")}}),
       "validate {d}/c.json",
       1,
       {"{d}/c.json", "camera.width"}},
      {"ValidateCaptureInfinity",
       With(kPair,
            {{"c.json",
              CaptureJson(
                  "l.png", "r.png",
                  R"("width": 96, "height": 72, "fx": 1e999, "fy": 60, "cx": 47.5, "cy": 35.5, "baseline_m": 0.12)")}}),
       "validate {d}/c.json",
       1,
       {"{d}/c.json", "1e999"}},
      {"ValidateCaptureNaNToken",
       With(kPair,
            {{"c.json",
              CaptureJson(
                  "l.png", "r.png",
                  R"("width": 96, "height": 72, "fx": NaN, "fy": 60, "cx": 47.5, "cy": 35.5, "baseline_m": 0.12)")}}),
       "validate {d}/c.json",
       1,
       {"{d}/c.json"}},
      {"ValidateCaptureZeroBaseline",
       With(kPair,
            {{"c.json",
              CaptureJson(
                  "l.png", "r.png",
                  R"("width": 96, "height": 72, "fx": 60, "fy": 60, "cx": 47.5, "cy": 35.5, "baseline_m": 0)")}}),
       "validate {d}/c.json",
       1,
       {"{d}/c.json", "baseline"}},
      {"ValidateCaptureNegativeSize",
       With(kPair,
            {{"c.json",
              CaptureJson(
                  "l.png", "r.png",
                  R"("width": -96, "height": 72, "fx": 60, "fy": 60, "cx": 47.5, "cy": 35.5, "baseline_m": 0.12)")}}),
       "validate {d}/c.json",
       1,
       {"{d}/c.json", "width"}},
      {"ValidateCaptureAbsurdFocal",
       With(kPair,
            {{"c.json",
              CaptureJson(
                  "l.png", "r.png",
                  R"("width": 96, "height": 72, "fx": 1e9, "fy": 60, "cx": 47.5, "cy": 35.5, "baseline_m": 0.12)")}}),
       "validate {d}/c.json",
       1,
       {"{d}/c.json", "fx"}},
      {"ValidateCaptureMissingImage", {{"c.json", cap_ok}}, "validate {d}/c.json", 1, {"{d}/c.json", "l.png"}},
      {"ValidatePlanWrongType",
       {{"p.json", R"({"version": 1, "units": "m", "walls": [{"start": "here", "end": [1, 0]}]})"}},
       "validate {d}/p.json",
       1,
       {"{d}/p.json", "walls[0].start"}},
      {"ValidatePlanNegativeThickness",
       {{"p.json", R"({"version": 1, "units": "m", "walls": [{"start": [0, 0], "end": [1, 0], "thickness": -0.2}]})"}},
       "validate {d}/p.json",
       1,
       {"{d}/p.json", "thickness"}},
      {"ValidateSceneNegativeHeight",
       {{"s.json", R"({"version": 1, "rooms": [{"polygon": [[0,0],[4,0],[4,3],[0,3]], "height_m": -3}]})"}},
       "validate --kind scene {d}/s.json",
       1,
       {"{d}/s.json", "height_m"}},
      {"ValidateManifestMissingFiles",
       {{"m.json",
         R"({"version": 1, "train": [{"image": "nope.png", "label": "nope_l.png"}], "val": [], "test": []})"}},
       "validate --kind manifest {d}/m.json",
       1,
       {"{d}/m.json"}},

      // ---------------------------------------------------------------- survey
      {"SurveyMissingCapture", {}, "survey {d}/capture.json -o {d}/out --no-report", 1, {"{d}/capture.json"}},
      {"SurveyMalformedCapture",
       {{"capture.json", "{\"version\": 1,"}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"{d}/capture.json"}},
      {"SurveyMissingLeft",
       {{"r.png", "<copy right/000.png"}, {"capture.json", cap_ok}},
       "survey {d}/capture.json -o {d}/out --capture-labels",
       1,
       {"l.png", "not found"}},
      {"SurveyTruncatedPng",
       {{"l.png", "<trunc left/000.png 200"}, {"r.png", "<copy right/000.png"}, {"capture.json", cap_ok}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"l.png"}},
      {"SurveyCorruptPng",
       {{"l.png", "<garbage"}, {"r.png", "<copy right/000.png"}, {"capture.json", cap_ok}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"l.png"}},
      {"SurveyTruncatedJpeg",
       {{"l.jpg", "<jpg 96x72 noise"}, {"r.jpg", "<jpg 96x72 noise"}, {"capture.json", CaptureJson("l.jpg", "r.jpg")}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"r.jpg"}},  // r.jpg is truncated below (see TruncateAfter).
      {"SurveyLeftRightDifferentSizes",
       {{"l.png", "<copy left/000.png"}, {"r.png", "<rgb 64x48 noise"}, {"capture.json", cap_ok}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"r.png", "64x48"}},
      {"SurveyImageNotCameraSize",
       {{"l.png", "<rgb 64x48 noise"}, {"r.png", "<rgb 64x48 noise"}, {"capture.json", cap_ok}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"l.png", "64x48"}},
      {"SurveyCalibrationForAnotherSize",
       With(
           kPair,
           {{"calib.yml", kCalib640},
            {"capture.json",
             R"({"version": 1, "camera": {)" + kCam96 +
                 R"(}, "rectified": false, "calibration": "calib.yml", "frames": [{"index": 0, "left": "l.png", "right": "r.png", "yaw_deg": 0, "position_m": [0, 0, 1.5]}]})"}}),
       "survey {d}/capture.json -o {d}/out",
       1,
       {"calib.yml", "640x480"}},
      {"SurveyCalibrationGarbage",
       With(
           kPair,
           {{"calib.yml", "<garbage"},
            {"capture.json",
             R"({"version": 1, "camera": {)" + kCam96 +
                 R"(}, "rectified": false, "calibration": "calib.yml", "frames": [{"index": 0, "left": "l.png", "right": "r.png", "yaw_deg": 0, "position_m": [0, 0, 1.5]}]})"}}),
       "survey {d}/capture.json -o {d}/out",
       1,
       {"calib.yml"}},
      {"SurveyNoFrames",
       {{"capture.json", R"({"version": 1, "camera": {)" + kCam96 + R"(}, "rectified": true, "frames": []})"}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"{d}/capture.json", "frames"}},
      {"SurveySegmentationWithNoWall",
       With(kPair, {{"capture.json", cap_ok}, {"labels/000.png", "<png 96x72 0"}}),
       "survey {d}/capture.json -o {d}/out --labels {d}/labels",
       1,
       {"wall"}},
      {"SurveyAllInvalidDisparity",
       {{"l.png", "<rgb 96x72 128"},
        {"r.png", "<rgb 96x72 128"},
        {"capture.json", cap_ok},
        {"labels/000.png", "<png 96x72 1"}},
       "survey {d}/capture.json -o {d}/out --labels {d}/labels",
       1,
       {"{d}/capture.json"}},
      {"SurveyLabelsWrongSize",
       With(kPair, {{"capture.json", cap_ok}, {"labels/000.png", "<png 40x30 1"}}),
       "survey {d}/capture.json -o {d}/out --labels {d}/labels",
       1,
       {"{d}/l.png", "40x30"}},
      {"SurveyMissingModel",
       With(kPair, {{"capture.json", cap_ok}}),
       "survey {d}/capture.json -o {d}/out --model {d}/nope.pt",
       1,
       {"{d}/nope.pt"}},
      // Mono and panorama captures (issue 22): the camera height is required, a
      // panorama must be 2:1, yaw must be a finite number.
      {"SurveyPanoramaNotTwoToOne",
       {{"pano.jpg", "<jpg 96x72 128"},
        {"capture.json", R"({"version": 1, "kind": "panorama", "panorama": "pano.jpg", "position_m": [0, 0, 1.4]})"}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"{d}/capture.json", "panorama", "96x72", "twice as wide as high"}},
      {"SurveyPanoramaNoCameraHeight",
       {{"pano.jpg", "<jpg 128x64 128"},
        {"capture.json", R"({"version": 1, "kind": "panorama", "panorama": "pano.jpg"})"}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"{d}/capture.json", "position_m"}},
      {"SurveyPanoramaZeroCameraHeight",
       {{"pano.jpg", "<jpg 128x64 128"},
        {"capture.json", R"({"version": 1, "kind": "panorama", "panorama": "pano.jpg", "position_m": [0, 0, 0]})"}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"{d}/capture.json", "position_m", "height above the floor"}},
      {"SurveyPanoramaCorrupt",
       {{"pano.jpg", "<garbage"},
        {"capture.json", R"({"version": 1, "kind": "panorama", "panorama": "pano.jpg", "position_m": [0, 0, 1.4]})"}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"{d}/pano.jpg"}},
      {"SurveyMonoNaNYaw",
       {{"v.png", "<rgb 96x72 128"},
        {"capture.json",
         R"({"version": 1, "kind": "mono", "camera": {"width": 96, "height": 72, "fx": 60, "fy": 60, "cx": 47.5, "cy": 35.5}, "frames": [{"index": 0, "image": "v.png", "yaw_deg": NaN, "position_m": [0, 0, 1.4]}]})"}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"{d}/capture.json"}},
      {"SurveyMonoInfiniteYaw",
       {{"v.png", "<rgb 96x72 128"},
        {"capture.json",
         R"({"version": 1, "kind": "mono", "camera": {"width": 96, "height": 72, "fx": 60, "fy": 60, "cx": 47.5, "cy": 35.5}, "frames": [{"index": 0, "image": "v.png", "yaw_deg": 1e999, "position_m": [0, 0, 1.4]}]})"}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"{d}/capture.json", "1e999"}},
      {"SurveyMonoNaNStringYaw",
       {{"v.png", "<rgb 96x72 128"},
        {"capture.json",
         R"({"version": 1, "kind": "mono", "camera": {"width": 96, "height": 72, "fx": 60, "fy": 60, "cx": 47.5, "cy": 35.5}, "frames": [{"index": 0, "image": "v.png", "yaw_deg": "NaN", "position_m": [0, 0, 1.4]}]})"}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"{d}/capture.json", "frames[0].yaw_deg"}},
      {"SurveyMonoNoCameraHeight",
       {{"v.png", "<rgb 96x72 128"},
        {"capture.json",
         R"({"version": 1, "kind": "mono", "camera": {"width": 96, "height": 72, "fx": 60, "fy": 60, "cx": 47.5, "cy": 35.5}, "frames": [{"index": 0, "image": "v.png", "yaw_deg": 0}]})"}},
       "survey {d}/capture.json -o {d}/out",
       1,
       {"{d}/capture.json", "frames[0].position_m"}},
      {"SurveyMonoTiltedView",
       {{"v.png", "<rgb 96x72 128"},
        {"capture.json",
         R"({"version": 1, "kind": "mono", "camera": {"width": 96, "height": 72, "fx": 60, "fy": 60, "cx": 47.5, "cy": 35.5}, "frames": [{"index": 0, "image": "v.png", "yaw_deg": 0, "pitch_deg": 20, "position_m": [0, 0, 1.4]}]})"}},
       "survey {d}/capture.json -o {d}/out --labels {d}",
       1,
       {"{d}/capture.json", "frames[0].pitch_deg", "level"}},
      {"ValidatePanoramaNotTwoToOne",
       {{"pano.png", "<png 96x72 128"},
        {"c.json", R"({"version": 1, "kind": "panorama", "panorama": "pano.png", "position_m": [0, 0, 1.4]})"}},
       "validate {d}/c.json",
       1,
       {"{d}/c.json", "panorama", "twice as wide as high"}},

      // ---------------------------------------------------------------- points
      {"PointsMissingLabelsFolder",
       With(kPair, {{"capture.json", cap_ok}}),
       "points {d}/capture.json --labels {d}/labels -o {d}/out",
       1,
       {"{d}/labels"}},
      {"PointsCorruptLabel",
       With(kPair, {{"capture.json", cap_ok}, {"labels/000.png", "<garbage"}}),
       "points {d}/capture.json --labels {d}/labels -o {d}/out",
       1,
       {"000.png"}},
      {"PointsEmptyLabelsFolder",
       With(kPair, {{"capture.json", cap_ok}, {"labels", "<dir"}}),
       "points {d}/capture.json --labels {d}/labels -o {d}/out",
       1,
       {"{d}/labels"}},
      {"PointsAllInvalidDisparity",
       {{"l.png", "<rgb 96x72 128"},
        {"r.png", "<rgb 96x72 128"},
        {"capture.json", cap_ok},
        {"labels/000.png", "<png 96x72 1"}},
       "points {d}/capture.json --labels {d}/labels -o {d}/out",
       1,
       {"{d}/capture.json", "no point"}},

      // ---------------------------------------------------------------- plan / eval
      {"ReviewNotASurvey", {{"a.txt", "x"}}, "review {d} --no-open", 1, {"not a folder written by `asbuilt survey`"}},
      {"ReviewMissingFolder", {}, "review {d}/nope --no-open", 1, {"{d}/nope", "not a folder"}},
      {"ReviewBrokenInput", {{"review/input.json", "{\"kind\": "}}, "review {d} --no-open", 1, {"input.json"}},
      {"ReviewUnknownKind",
       {{"review/input.json", R"({"points": "points.bin", "kind": "sphere"})"}},
       "review {d} --no-open",
       1,
       {"input.json", "sphere"}},
      {"ReviewOlderSurvey",
       {{"review/input.json", R"({"points": "points.txt", "kind": "panorama"})"}},
       "review {d} --no-open",
       1,
       {"input.json", "older asbuilt survey"}},
      {"ReviewBadPort", {{"a.txt", "x"}}, "review {d} --port 70000 --no-open", 2, {"port", "70000"}},
      {"PlanMissingPoints", {}, "plan {d}/p.txt -o {d}/out", 1, {"{d}/p.txt"}},
      {"PlanEmptyPoints", {{"p.txt", ""}}, "plan {d}/p.txt -o {d}/out", 1, {"{d}/p.txt"}},
      {"PlanMalformedLine", {{"p.txt", "wall 1 2\n"}}, "plan {d}/p.txt -o {d}/out", 1, {"{d}/p.txt", "line 1"}},
      {"PlanNaNPoint",
       {{"p.txt", "wall nan 2 1\nwall 1 2 1\n"}},
       "plan {d}/p.txt -o {d}/out",
       1,
       {"{d}/p.txt", "line 1"}},
      {"PlanUnknownClass", {{"p.txt", "ceiling 1 2 1\n"}}, "plan {d}/p.txt -o {d}/out", 1, {"{d}/p.txt", "ceiling"}},
      {"PlanTooFewPoints", {{"p.txt", Lines("wall 1 2 1", 3)}}, "plan {d}/p.txt -o {d}/out", 1, {"{d}/p.txt", "wall"}},
      {"PlanCollinearPoints", {{"p.txt", CollinearPoints()}}, "plan {d}/p.txt -o {d}/out", 1, {"{d}/p.txt"}},
      {"PlanCaptureWithoutLabels",
       With(kPair, {{"capture.json", cap_ok}}),
       "plan {d}/capture.json -o {d}/out",
       1,
       {"{d}/capture.json", "labels"}},
      {"EvalPlanMalformed",
       {{"plan.json", "{\"walls\": ["}, {"truth.json", kPlanOk}},
       "eval plan {d}/plan.json {d}/truth.json",
       1,
       {"{d}/plan.json"}},
      {"EvalPlanMissingTruth",
       {{"plan.json", kPlanOk}},
       "eval plan {d}/plan.json {d}/truth.json --json {d}/out/s.json",
       1,
       {"{d}/truth.json"}},
      {"EvalPlanInfinity",
       {{"plan.json", R"({"version": 1, "units": "m", "walls": [{"start": [0, 0], "end": [1e999, 0]}]})"},
        {"truth.json", kPlanOk}},
       "eval plan {d}/plan.json {d}/truth.json",
       1,
       {"{d}/plan.json", "1e999"}},

      // ---------------------------------------------------------------- scene
      {"SceneTruthMissing", {}, "scene truth {d}/s.json -o {d}/out/t.json", 1, {"{d}/s.json"}},
      {"SceneTruthMalformed",
       {{"s.json", "{\"rooms\": [}"}},
       "scene truth {d}/s.json -o {d}/out/t.json",
       1,
       {"{d}/s.json"}},
      {"SceneDescribeWrongType",
       {{"s.json", R"({"version": 1, "rooms": "many"})"}},
       "scene describe {d}/s.json",
       1,
       {"{d}/s.json", "rooms"}},
      {"SceneExportZeroArea",
       {{"s.json", R"({"version": 1, "rooms": [{"polygon": [[0,0],[0,0],[0,0]], "height_m": 3}]})"}},
       "scene export-blender {d}/s.json -o {d}/out/b.py",
       1,
       {"{d}/s.json"}},
      {"SceneTextNoRoom", {}, "scene text \"\" -o {d}/out/s.json", 1, {"text"}},

      // ---------------------------------------------------------------- render / dataset synth
      {"RenderMissingScene", {}, "render {d}/s.json -o {d}/out", 1, {"{d}/s.json"}},
      {"RenderSceneNaN",
       {{"s.json", R"({"version": 1, "rooms": [{"polygon": [[0,0],[1e999,0],[4,3],[0,3]], "height_m": 3}]})"}},
       "render {d}/s.json -o {d}/out --views 1 --size 32x24",
       1,
       {"{d}/s.json"}},
      {"RenderSceneZeroHeight",
       {{"s.json", R"({"version": 1, "rooms": [{"polygon": [[0,0],[4,0],[4,3],[0,3]], "height_m": 0}]})"}},
       "render {d}/s.json -o {d}/out --views 1 --size 32x24",
       1,
       {"{d}/s.json"}},
      {"RenderSceneIsFolder", {{"s.json", "<dir"}}, "render {d}/s.json -o {d}/out", 1, {"{d}/s.json"}},

      // ---------------------------------------------------------------- calibrate / rectify / disparity
      {"CalibrateNoChessboard",
       {{"l0.png", "<rgb 96x72 noise"},
        {"r0.png", "<rgb 96x72 noise"},
        {"l1.png", "<rgb 96x72 90"},
        {"r1.png", "<rgb 96x72 90"}},
       "calibrate --left {d}/l0.png {d}/l1.png --right {d}/r0.png {d}/r1.png -o {d}/out/c.yml",
       1,
       {"{d}/l0.png", "board found"}},
      {"CalibrateMissingImage",
       {{"l0.png", "<rgb 96x72 noise"}},
       "calibrate --left {d}/l0.png --right {d}/r0.png -o {d}/out/c.yml",
       1,
       {"{d}/r0.png"}},
      {"CalibrateCountMismatch",
       {{"l0.png", "<rgb 96x72 noise"}, {"l1.png", "<rgb 96x72 noise"}, {"r0.png", "<rgb 96x72 noise"}},
       "calibrate --left {d}/l0.png {d}/l1.png --right {d}/r0.png -o {d}/out/c.yml",
       2,
       {"--right", "2 left images but 1"}},
      {"CalibrateEmptyGlob",
       {{"imgs", "<dir"}},
       "calibrate --left '{d}/imgs/*.png' --right '{d}/imgs/*.png' -o {d}/out/c.yml",
       2,
       {"{d}/imgs/*.png"}},
      {"CalibrateCorruptImage",
       {{"l0.png", "<garbage"}, {"r0.png", "<rgb 96x72 noise"}},
       "calibrate --left {d}/l0.png --right {d}/r0.png -o {d}/out/c.yml",
       1,
       {"{d}/l0.png"}},
      {"RectifyMissingCalibration",
       kPair,
       "rectify --calibration {d}/c.yml --left {d}/l.png --right {d}/r.png -o {d}/out",
       1,
       {"{d}/c.yml"}},
      {"RectifyGarbageCalibration",
       With(kPair, {{"c.yml", "<garbage"}}),
       "rectify --calibration {d}/c.yml --left {d}/l.png --right {d}/r.png -o {d}/out",
       1,
       {"{d}/c.yml"}},
      {"RectifyCalibrationForAnotherSize",
       With(kPair, {{"c.yml", kCalib640}}),
       "rectify --calibration {d}/c.yml --left {d}/l.png --right {d}/r.png -o {d}/out",
       1,
       {"{d}/l.png", "640x480"}},
      {"RectifyDifferentSizes",
       {{"c.yml", kCalib640}, {"l.png", "<rgb 640x480 noise"}, {"r.png", "<rgb 320x240 noise"}},
       "rectify --calibration {d}/c.yml --left {d}/l.png --right {d}/r.png -o {d}/out",
       1,
       {"{d}/r.png", "320x240"}},
      {"RectifyTruncatedJpeg",
       {{"c.yml", kCalib640}, {"l.jpg", "<jpg 640x480 noise"}, {"r.jpg", "<jpg 640x480 noise"}},
       "rectify --calibration {d}/c.yml --left {d}/l.jpg --right {d}/r.jpg -o {d}/out",
       1,
       {"r.jpg"}},
      {"DisparityMissingLeft",
       {{"r.png", "<copy right/000.png"}},
       "disparity {d}/l.png {d}/r.png -o {d}/out/d.pfm",
       1,
       {"{d}/l.png"}},
      {"DisparityDifferentSizes",
       {{"l.png", "<copy left/000.png"}, {"r.png", "<rgb 64x48 noise"}},
       "disparity {d}/l.png {d}/r.png -o {d}/out/d.pfm",
       1,
       {"r.png", "64x48"}},
      {"DisparityTruncatedPng",
       {{"l.png", "<trunc left/000.png 300"}, {"r.png", "<copy right/000.png"}},
       "disparity {d}/l.png {d}/r.png -o {d}/out/d.pfm",
       1,
       {"{d}/l.png"}},

      // ---------------------------------------------------------------- labels / dataset
      {"LabelsConvertEmptyFolder", {{"ids", "<dir"}}, "labels convert {d}/ids -o {d}/out", 1, {"{d}/ids"}},
      {"LabelsConvertCorruptIdMap", {{"ids/000.png", "<garbage"}}, "labels convert {d}/ids -o {d}/out", 1, {"000.png"}},
      {"LabelsConvertMalformedPalette",
       {{"ids/000.png", "<rgb 32x24 40"}, {"pal.json", "[1, 2"}},
       "labels convert {d}/ids --palette {d}/pal.json -o {d}/out",
       1,
       {"{d}/pal.json"}},
      {"LabelsCalibrateEmptyFolder",
       {{"ids", "<dir"}},
       "labels calibrate --idmaps {d}/ids -o {d}/out/pal.json",
       1,
       {"{d}/ids"}},
      {"LabelsImportMissing", {}, "labels import {d}/ann --format ade20k -o {d}/out", 1, {"{d}/ann"}},
      {"LabelsImportBadFormat", {{"ann", "<dir"}}, "labels import {d}/ann --format coco -o {d}/out", 2, {"coco"}},
      {"LabelsCompareDifferentSizes",
       {{"p/000.png", "<png 32x24 1"}, {"e/000.png", "<png 16x12 1"}},
       "labels compare {d}/p {d}/e",
       1,
       {"000.png"}},
      {"DatasetMixEmptyFolders",
       {{"real", "<dir"}, {"syn", "<dir"}},
       "dataset mix --real {d}/real --synthetic {d}/syn -o {d}/out/m.json",
       1,
       {"{d}/real"}},
      {"DatasetCheckManifestMissingFiles",
       {{"m.json",
         R"({"version": 1, "train": [{"image": "nope.png", "label": "nope_l.png"}], "val": [], "test": []})"}},
       "dataset check {d}/m.json",
       1,
       {"nope.png"}},
      {"DatasetCheckMalformedManifest", {{"m.json", "{\"train\": [1,"}}, "dataset check {d}/m.json", 1, {"{d}/m.json"}},
      {"DatasetCheckEmptyFolder", {{"ds", "<dir"}}, "dataset check {d}/ds", 1, {"{d}/ds"}},
      {"DatasetCheckLabelSizeMismatch",
       {{"ds/images/a.png", "<rgb 32x24 40"}, {"ds/labels/a.png", "<png 16x12 1"}},
       "dataset check {d}/ds",
       1,
       {"a.png", "16x12"}},

      // ---------------------------------------------------------------- pano / eval zind
      {"PanoViewsNotTwoToOne",
       {{"p.png", "<rgb 96x72 9"}},
       "pano views {d}/p.png -o {d}/out",
       1,
       {"{d}/p.png", "96x72"}},
      {"PanoViewsCorruptImage", {{"p.jpg", "<garbage"}}, "pano views {d}/p.jpg -o {d}/out", 1, {"{d}/p.jpg"}},
      {"PanoViewsMissingImage", {}, "pano views {d}/p.jpg -o {d}/out", 1, {"{d}/p.jpg", "no such file"}},
      {"PanoViewsAbsurdPitch",
       {{"p.png", "<rgb 64x32 9"}},
       "pano views {d}/p.png -o {d}/out --pitch 95",
       2,
       {"--pitch-deg: must be > -90 and < 90, got 95"}},
      {"PanoViewsBadSize", {{"p.png", "<rgb 64x32 9"}}, "pano views {d}/p.png -o {d}/out --size 0x48", 2, {"--size"}},
      {"PanoViewsZindMalformed",
       {{"tour/zind_data.json", "{\"merger\": ["}},
       "pano views pano_1 --zind {d}/tour -o {d}/out",
       1,
       {"{d}/tour/zind_data.json"}},
      {"PanoViewsZindBadDoors",
       {{"tour/p.jpg", "<jpg 64x32 9"}, {"tour/zind_data.json", R"({"scale_meters_per_coordinate": {"f": 2},
        "merger": {"f": {"c": {"p": {"pano_1": {"is_primary": true, "camera_height": 1, "ceiling_height": 1.5, "image_path": "p.jpg",
        "floor_plan_transformation": {"translation": [0, 0], "rotation": 0, "scale": 1},
        "layout_raw": {"vertices": [[0, 0], [1, 0], [1, 1]], "doors": [[0, 0]]}}}}}}})"}},
       "pano views pano_1 --zind {d}/tour -o {d}/out",
       1,
       {"{d}/tour/zind_data.json", "merger.f.c.p.pano_1.layout_raw.doors"}},
      {"PanoViewsZindUnknownPano",
       {{"tour/p.jpg", "<jpg 64x32 9"}, {"tour/zind_data.json", R"({"scale_meters_per_coordinate": {"f": 2},
        "merger": {"f": {"c": {"p": {"pano_1": {"is_primary": true, "camera_height": 1, "ceiling_height": 1.5, "image_path": "p.jpg",
        "floor_plan_transformation": {"translation": [0, 0], "rotation": 0, "scale": 1},
        "layout_raw": {"vertices": [[0, 0], [1, 0], [1, 1]]}}}}}}})"}},
       "pano views pano_9 --zind {d}/tour -o {d}/out",
       1,
       {"{d}/tour/zind_data.json", "pano_9"}},
      {"LearnSurveyNotReviewed",
       {{"s/summary.json", "{}"}},
       "learn {d}/s -o {d}/out --config R100",
       1,
       {"{d}/s", "asbuilt review"}},
      {"LearnRendersWithoutSynthetic", {{"s/summary.json", "{}"}}, "learn {d}/s -o {d}/out", 2, {"--synthetic"}},
      {"TrainFinetuneMissingModel", {}, "train --finetune {d}/nope.pt --images {d}/img -o {d}/out", 1, {"{d}/nope.pt"}},
      {"EvalZindMissingTour",
       {},
       "eval zind --model {src}/models/segformer_b0_asbuilt.pt --zind {d}/tour -o {d}/out",
       1,
       {"{d}/tour"}},
      {"EvalZindBadViews",
       {},
       "eval zind --model {src}/models/segformer_b0_asbuilt.pt --zind {d}/tour -o {d}/out --views 0",
       2,
       {"--views: must be an integer >= 1"}},

      // ---------------------------------------------------------------- mcp
      {"McpWorkspaceIsAFile", {{"ws", "just a file"}}, "mcp --workspace {d}/ws", 1, {"{d}/ws"}},

      // ---------------------------------------------------------------- train / segment / eval seg / experiment
      // (LibTorch)
      {"TrainEmptyImageFolder",
       {{"img", "<dir"}, {"lab", "<dir"}},
       "train --images {d}/img --labels {d}/lab -o {d}/out --arch tiny --epochs 1",
       1,
       {"{d}/img"}},
      {"TrainManifestMissingFiles",
       {{"m.json",
         R"({"version": 1, "train": [{"image": "nope.png", "label": "nope_l.png"}], "val": [], "test": []})"}},
       "train --manifest {d}/m.json -o {d}/out --arch tiny --epochs 1",
       1,
       {"nope.png"}},
      {"TrainMalformedManifest",
       {{"m.json", "[["}},
       "train --manifest {d}/m.json -o {d}/out --arch tiny --epochs 1",
       1,
       {"{d}/m.json"}},
      {"TrainCorruptImage",
       {{"img/a.png", "<garbage"},
        {"lab/a.png", "<png 32x24 1"},
        {"img/b.png", "<rgb 32x24 9"},
        {"lab/b.png", "<png 32x24 1"}},
       "train --images {d}/img --labels {d}/lab -o {d}/out --arch tiny --epochs 1 --scale 32x24 --crop 32x24",
       1,
       {"a.png"}},
      {"TrainLabelSizeMismatch",
       {{"img/a.png", "<rgb 32x24 9"},
        {"lab/a.png", "<png 16x12 1"},
        {"img/b.png", "<rgb 32x24 9"},
        {"lab/b.png", "<png 32x24 1"}},
       "train --images {d}/img --labels {d}/lab -o {d}/out --arch tiny --epochs 1 --scale 32x24 --crop 32x24",
       1,
       {"a.png", "16x12"}},
      {"TrainCorruptInit",
       {{"img/a.png", "<rgb 32x24 9"},
        {"lab/a.png", "<png 32x24 1"},
        {"img/b.png", "<rgb 32x24 9"},
        {"lab/b.png", "<png 32x24 1"},
        {"init.pt", "<garbage"}},
       "train --images {d}/img --labels {d}/lab -o {d}/out --arch tiny --epochs 1 --init {d}/init.pt",
       1,
       {"{d}/init.pt"}},
      {"SegmentCorruptModel",
       {{"a.png", "<rgb 32x24 9"}, {"m.pt", "<garbage"}},
       "segment --model {d}/m.pt {d}/a.png -o {d}/out",
       1,
       {"{d}/m.pt"}},
      {"SegmentTruncatedModel",
       {{"a.png", "<rgb 32x24 9"}, {"m.pt", "<trunc {src}/models/segformer_b0_asbuilt.pt 5000"}},
       "segment --model {d}/m.pt {d}/a.png -o {d}/out",
       1,
       {"{d}/m.pt"}},
      {"SegmentCorruptImage",
       {{"a.png", "<garbage"}},
       "segment --model {src}/models/segformer_b0_asbuilt.pt {d}/a.png -o {d}/out",
       1,
       {"{d}/a.png"}},
      {"SegmentEmptyFolder",
       {{"imgs", "<dir"}},
       "segment --model {src}/models/segformer_b0_asbuilt.pt {d}/imgs -o {d}/out",
       1,
       {"{d}/imgs"}},
      {"EvalSegMissingModel",
       {{"img/a.png", "<rgb 32x24 9"}, {"lab/a.png", "<png 32x24 1"}},
       "eval seg --model {d}/nope.pt --images {d}/img --labels {d}/lab",
       1,
       {"{d}/nope.pt"}},
      {"ExperimentRatiosEmptyFolders",
       {{"real", "<dir"}, {"syn", "<dir"}},
       "experiment ratios --real {d}/real --synthetic {d}/syn -o {d}/out --arch tiny --epochs 1",
       1,
       {"{d}/real"}},
  };
}

// Files whose content must be cut after creation (a JPEG truncated in the middle).
const std::map<std::string, std::pair<std::string, std::size_t>> kTruncateAfter = {
    {"SurveyTruncatedJpeg", {"r.jpg", 300}},
    {"RectifyTruncatedJpeg", {"r.jpg", 300}},
};

class BadInput : public ::testing::TestWithParam<Case> {
 protected:
  static fs::path BaseDir() { return fs::path(ASBUILT_BINARY_DIR) / "cli_bad_input_base"; }

  // Two rendered views of the example classroom: good images and labels.
  // ctest runs every case in its own process, in parallel: the first renders
  // the base capture under an exclusive lock, the others wait and reuse it.
  static void SetUpTestSuite() {
    fs::create_directories(BaseDir().parent_path());
    int lock = ::open((BaseDir().string() + ".lock").c_str(), O_CREAT | O_RDWR, 0644);
    ASSERT_GE(lock, 0);
    ::flock(lock, LOCK_EX);
    struct Unlock {
      int fd;
      ~Unlock() { ::close(fd); }
    } unlock{lock};
    if (fs::exists(BaseDir() / "done")) return;
    auto r = testing_util::RunAsbuilt("render " + std::string(ASBUILT_SOURCE_DIR) + "/examples/classroom.json -o " +
                                      BaseDir().string() + " --views 2 --size 96x72 --spp 1 --effects 0");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    std::ofstream(BaseDir() / "done") << "rendered\n";
  }

  // LibTorch-free builds (ASBUILT_WITH_TORCH=OFF) list train and segment but refuse to run them.
  static bool HasTorch() {
    static const bool has =
        testing_util::RunAsbuilt("train --images /nonexistent -o /nonexistent").out.find("no LibTorch") ==
        std::string::npos;
    return has;
  }

  static const std::string& Help() {
    static const std::string help = testing_util::RunAsbuilt("help").out;
    return help;
  }
};

TEST_P(BadInput, ExitsWithOneClearMessageAndLeavesNothing) {
  const Case& c = GetParam();
  std::string command = c.args.substr(0, c.args.find(' '));
  if (command != "frobnicate" && Help().find("  " + command + " ") == std::string::npos) {
    GTEST_SKIP() << "this build has no `" << command << "` command";
  }
  bool needs_torch = command == "train" || command == "segment" || c.args.rfind("eval seg", 0) == 0 ||
                     c.args.rfind("experiment ratios", 0) == 0;
  if (needs_torch && !HasTorch()) GTEST_SKIP() << "this build has no LibTorch";
  fs::path base = BaseDir();
  ASSERT_TRUE(fs::exists(base / "capture.json"));
  fs::path d = testing_util::FreshTestDir("asbuilt_bad_input_");
  std::map<std::string, std::string> vars = {
      {"{d}", d.string()}, {"{base}", base.string()}, {"{src}", ASBUILT_SOURCE_DIR}};
  for (const FileSpec& f : c.files) {
    MakeFile(d / f.path, Substitute(f.contents, vars), base);  // base / "/abs" is "/abs".
  }
  if (auto it = kTruncateAfter.find(c.name); it != kTruncateAfter.end()) {
    fs::resize_file(d / it->second.first, it->second.second);
  }
  std::vector<std::string> before = ListFiles(d);

  Outcome r = RunWithTimeout(Substitute(c.args, vars));

  EXPECT_NE(r.status, 124) << "timed out";
  EXPECT_NE(r.status, 137) << "timed out (killed after " << kTimeoutS << " s)";
  EXPECT_EQ(r.status, c.exit_code) << r.out;
  for (const std::string& s : c.must_contain) {
    EXPECT_NE(r.out.find(Substitute(s, vars)), std::string::npos) << "message lacks '" << Substitute(s, vars) << "':\n"
                                                                  << r.out;
  }
  for (const char* crash : {"terminate called", "what():", "Segmentation fault", "Aborted", "core dumped",
                            "AddressSanitizer", "runtime error:", "Exception raised from"}) {
    EXPECT_EQ(r.out.find(crash), std::string::npos) << "crash text '" << crash << "':\n" << r.out;
  }
  // One message: exactly one error line from asbuilt (warnings may precede it).
  // Batch commands that check many files (validate, dataset check, labels,
  // calibrate's per-view rejections) list one line per bad file, then may end
  // with one `asbuilt <command>:` line; every other command prints exactly one.
  const bool report =
      command == "validate" || command == "labels" || command == "calibrate" || c.args.rfind("dataset check", 0) == 0;
  std::size_t errors = 0;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("asbuilt ", 0) == 0 || line.rfind("asbuilt:", 0) == 0) ++errors;
  }
  if (report) {
    EXPECT_LE(errors, 1u) << "more than one `asbuilt ...:` error line:\n" << r.out;
  } else {
    EXPECT_EQ(errors, 1u) << "expected one `asbuilt ...:` error line:\n" << r.out;
  }
  EXPECT_LT(r.out.size(), 4000u) << "message too long:\n" << r.out;
  std::vector<std::string> left = NewFiles(d, before);
  EXPECT_TRUE(left.empty()) << "output left behind: " << ::testing::PrintToString(left) << "\n" << r.out;
  if (!HasFailure()) fs::remove_all(d);
}

INSTANTIATE_TEST_SUITE_P(Cases, BadInput, ::testing::ValuesIn(Cases()),
                         [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

}  // namespace
}  // namespace asbuilt
