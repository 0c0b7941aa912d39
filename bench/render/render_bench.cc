// Renderer benchmark → bench/results/render.md:
//  1. stereo pairs/s at 640×480 with RGB + ID map + labels + depth (example
//     classroom), at the sample counts asbuilt uses (2: dataset synth, 4: captures);
//  2. Blender Cycles rendering the same scene (scene/blender_export.h script)
//     at the 16 samples the Blender reference data used, same run;
//  3. Mrays/s of the renderer vs a bare Embree primary-ray loop (the ceiling);
//  4. peak and current RSS from the 10th to the 1,000th rendered view
//     (dataset synth: a new room every 8 views, 160×120, 1 spp).
// Environment: ASBUILT_BENCH_NO_BLENDER=1 skips Blender; ASBUILT_BENCH_MEMORY_VIEWS=N
// changes the 1,000.

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/render/dataset_synth.h"
#include "asbuilt/render/ray_tracer.h"
#include "asbuilt/render/renderer.h"
#include "asbuilt/scene/blender_export.h"
#include "asbuilt/scene/scene_json.h"
#include "bench/bench_util.h"

namespace fs = std::filesystem;
using namespace asbuilt;

namespace {

double Seconds(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double CurrentRssMiB() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * static_cast<double>(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// Primary rays only, both eyes, nearest hit with glass: what Embree alone does.
double BareEmbreeMraysPerSecond(const SceneRenderer& renderer, const StereoCamera& cam) {
  RayTracer tracer(renderer.mesh());
  const PinholeCamera& k = cam.camera;
  auto run = [&] {
    std::atomic<long> hits{0};
    for (StereoEye eye : {StereoEye::kLeft, StereoEye::kRight}) {
      Eigen::Isometry3d world_from_cam = WorldFromStereoEye(cam.viewpoint, cam.baseline_m, eye);
      Eigen::Matrix3f rot = world_from_cam.linear().cast<float>();
      Vec3f c = world_from_cam.translation().cast<float>();
      tbb::parallel_for(tbb::blocked_range2d<int>(0, k.height_px, 16, 0, k.width_px, 16),
                        [&](const tbb::blocked_range2d<int>& r) {
                          long local = 0;
                          for (int y = r.rows().begin(); y < r.rows().end(); ++y) {
                            for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                              Vec3f d((x - k.cx) / k.fx, (y - k.cy) / k.fy, 1.0f);
                              RayHit hit;
                              local += tracer.Intersect(c, rot * d.normalized(), 0.0f, 1e5f, true, &hit);
                            }
                          }
                          hits += local;
                        });
    }
  };
  run();  // Warm-up.
  double s = bench::MedianSeconds(5, run);
  return 2.0 * k.width_px * k.height_px / s / 1e6;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out_path = bench::ResultsPath(argc, argv, "render");
  Scene scene = ReadScene(fs::path(ASBUILT_SOURCE_DIR) / "examples" / "classroom.json");
  scene.rig.width_px = 640;
  scene.rig.height_px = 480;
  SceneRenderer renderer(scene);
  std::vector<Viewpoint> views = ResolveViewpoints(scene);
  const PinholeCamera camera = scene.rig.Camera();

  // 1. asbuilt: stereo pairs with RGB + ID + labels + depth.
  struct Run {
    int spp;
    double seconds_per_pair;
    double mrays;
  };
  std::vector<Run> runs;
  const int kViews = 4;
  for (int spp : {2, 4}) {
    std::vector<double> times;
    double rays = 0, secs = 0;
    for (int v = 0; v < kViews; ++v) {
      auto start = std::chrono::steady_clock::now();
      RenderedView view = renderer.Render({camera, views[v * 3 % views.size()], scene.rig.baseline_m},
                                          {.samples_per_pixel = spp}, v, true);
      double t = Seconds(start);
      times.push_back(t);
      rays += static_cast<double>(view.rays_traced);
      secs += t;
    }
    runs.push_back({spp, bench::Median(times), rays / secs / 1e6});
    fmt::print(stderr, "asbuilt spp {}: {:.3f} s per stereo pair\n", spp, runs.back().seconds_per_pair);
  }
  double bare = BareEmbreeMraysPerSecond(renderer, {camera, views[0], scene.rig.baseline_m});

  // 2. Blender Cycles on the same scene, same machine, same run.
  double blender_seconds = -1, blender_total = -1;
  std::string blender_note;
  const int kBlenderSamples = 16;
  if (std::getenv("ASBUILT_BENCH_NO_BLENDER") == nullptr && std::system("blender --version >/dev/null 2>&1") == 0) {
    fs::path dir = fs::temp_directory_path() / fmt::format("asbuilt_bench_blender_{}", ::getpid());
    fs::create_directories(dir);
    Scene one = scene;
    one.turn.reset();
    one.viewpoints = {views[0]};
    WriteBlenderScript(one, {.samples = kBlenderSamples, .denoise = false}, dir / "build.py");
    // Startup + scene build alone (no frame), then one stereo frame; the
    // difference is the render time of one stereo pair.
    auto s0 = std::chrono::steady_clock::now();
    int rc0 = std::system(
        fmt::format("blender -b -t 2 -P {} >{} 2>&1", (dir / "build.py").string(), (dir / "setup.log").string())
            .c_str());
    double setup = Seconds(s0);
    auto s1 = std::chrono::steady_clock::now();
    int rc1 = std::system(fmt::format("blender -b -t 2 -P {} -o {}/ -f 1 >{} 2>&1", (dir / "build.py").string(),
                                      (dir / "out").string(), (dir / "render.log").string())
                              .c_str());
    blender_total = Seconds(s1);
    if (rc0 == 0 && rc1 == 0) {
      blender_seconds = blender_total - setup;
    } else {
      blender_note = fmt::format(" (blender failed: exit {}/{}; see {})", rc0, rc1, dir.string());
    }
  } else {
    blender_note = " (Blender not run: not installed or ASBUILT_BENCH_NO_BLENDER set)";
  }

  // 4. Memory over many views (dataset synth: a new room every 8 items).
  int memory_views = 1000;
  if (const char* e = std::getenv("ASBUILT_BENCH_MEMORY_VIEWS")) memory_views = std::max(20, std::atoi(e));
  fs::path synth_dir = fs::temp_directory_path() / fmt::format("asbuilt_bench_synth_{}", ::getpid());
  DatasetSynthOptions synth;
  synth.count = memory_views;
  synth.width_px = 160;
  synth.height_px = 120;
  synth.render.samples_per_pixel = 1;
  double peak10 = 0, rss10 = 0, peak_end = 0, rss_end = 0;
  auto synth_start = std::chrono::steady_clock::now();
  SynthesizeDataset(synth_dir, synth, [&](const ProgressUpdate& u) {
    if (u.done == 10) {
      peak10 = bench::PeakRssMiB();
      rss10 = CurrentRssMiB();
    }
    if (u.done == u.total) {
      peak_end = bench::PeakRssMiB();
      rss_end = CurrentRssMiB();
    }
  });
  double synth_seconds = Seconds(synth_start);
  fs::remove_all(synth_dir);

  // Report.
  std::string md = "## render — Embree CPU ray tracer\n\n";
  md += fmt::format(
      "Example classroom (`examples/classroom.json`, {} triangles), 640×480 stereo pairs with RGB (both eyes) + "
      "ID map + labels + depth (left), one bounce, denoised, camera effects; {} views per setting, median; "
      "{} hardware threads.\n\n",
      renderer.mesh().TriangleCount(), kViews, std::thread::hardware_concurrency());
  md += "| renderer | samples/px | s per stereo pair | stereo pairs/s | × vs Blender |\n|---|---|---|---|---|\n";
  for (const Run& r : runs) {
    md += fmt::format("| asbuilt | {} | {:.3f} | {:.2f} | {} |\n", r.spp, r.seconds_per_pair, 1.0 / r.seconds_per_pair,
                      blender_seconds > 0 ? fmt::format("{:.1f}×", blender_seconds / r.seconds_per_pair) : "—");
  }
  md += fmt::format("| Blender {} Cycles (CPU, `-t 2`) | {} | {} | {} | 1× |\n\n", "3.4", kBlenderSamples,
                    blender_seconds > 0 ? fmt::format("{:.2f}", blender_seconds) : "—",
                    blender_seconds > 0 ? fmt::format("{:.3f}", 1.0 / blender_seconds) : "—");
  if (blender_seconds > 0) {
    md += fmt::format(
        "Blender: one stereo frame of the same scene (`scene export-blender` script, {} samples, no denoiser, "
        "object-index pass for labels) = {:.1f} s wall including startup and scene build; the table gives that "
        "minus a setup-only run. 16 samples is what the Blender reference data (`blender-rooms-public`) used; "
        "asbuilt's dataset synth uses 2, its captures 4.{}\n\n",
        kBlenderSamples, blender_total, blender_note);
  } else {
    md += "Blender: not measured" + blender_note + ".\n\n";
  }
  md += "| rays | Mrays/s |\n|---|---|\n";
  for (const Run& r : runs)
    md += fmt::format("| asbuilt, all rays (primary, shadow, bounce), spp {} | {:.2f} |\n", r.spp, r.mrays);
  md += fmt::format("| bare Embree primary-ray loop (ceiling) | {:.2f} |\n\n", bare);
  md += fmt::format(
      "Memory over {} views (`dataset synth`, 160×120, 1 spp, a new room every 8 views, {:.1f} s): peak RSS "
      "{:.1f} MiB after view 10, {:.1f} MiB after view {} ({:+.1f} %); current RSS {:.1f} → {:.1f} MiB.\n",
      memory_views, synth_seconds, peak10, peak_end, memory_views, 100.0 * (peak_end - peak10) / std::max(peak10, 1e-9),
      rss10, rss_end);
  // Context: other work on the machine slows everything by the same factor.
  std::ifstream loadavg("/proc/loadavg");
  double load1 = 0;
  loadavg >> load1;
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  md += fmt::format(
      "\nLoad average at the end: {:.1f} on {} hardware threads; this process's own CPU time: {:.0f} s.\n", load1,
      std::thread::hardware_concurrency(), static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec));
  bench::WriteSection(out_path, md);
  return 0;
}
