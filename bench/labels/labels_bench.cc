// Measured accuracy and speed of ID-map → label conversion (issue 5,
// PAPER.md §3.3–3.4): pixel agreement with the exact labels, overall and in
// the 1-pixel boundary band, for the nominal colours vs calibrated centroids
// (by masks and by k-means), a threshold sweep, and conversion throughput.
//
// ID maps: (a) asbuilt's renderer (render/dataset_synth.h: random rooms,
// ID-map drift RenderOptions.id_drift at its default and stronger); (b) exact
// labels painted in the nominal colours with lighting drift and anti-aliased
// edges (labels/idmap_synth.h), on the Blender rooms' exact labels (shared
// data) and on procedural room labels; (c) optionally a folder given as
// argv[2] with idmaps/ (or idmap/) + labels/.

#include <chrono>
#include <thread>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "asbuilt/labels/agreement.h"
#include "asbuilt/labels/calibrate.h"
#include "asbuilt/labels/convert.h"
#include "asbuilt/labels/idmap_synth.h"
#include "asbuilt/labels/label_io.h"
#include "asbuilt/render/dataset_synth.h"
#include "asbuilt/render/renderer.h"
#include "bench/bench_util.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

struct Set {
  std::string name;
  std::vector<cv::Mat> labels, idmaps;
};

LabelAgreement Measure(const Set& s, const Palette& p, double threshold) {
  LabelAgreement a;
  for (std::size_t i = 0; i < s.idmaps.size(); ++i)
    a.Add(CompareLabels(ConvertIdMap(s.idmaps[i], p, threshold), s.labels[i]));
  return a;
}

// Even frames calibrate, odd frames are measured.
void Split(const Set& all, Set& train, Set& test) {
  train.name = test.name = all.name;
  for (std::size_t i = 0; i < all.idmaps.size(); ++i) {
    Set& s = i % 2 ? test : train;
    s.labels.push_back(all.labels[i]);
    s.idmaps.push_back(all.idmaps[i]);
  }
}

std::string Pct(double v) { return fmt::format("{:.2f} %", 100 * v); }

// The ID maps and exact labels of a dataset folder (idmaps/ or idmap/ + labels/).
Set ReadFolder(const std::string& name, const fs::path& dir) {
  Set s{name, {}, {}};
  fs::path idmaps = fs::exists(dir / "idmaps") ? dir / "idmaps" : dir / "idmap";
  for (const fs::path& p : ListImageFiles(idmaps)) {
    fs::path l = dir / "labels" / (p.stem().string() + ".png");
    if (!fs::exists(l)) continue;
    s.idmaps.push_back(ReadColourImage(p));
    s.labels.push_back(ReadLabelImage(l));
  }
  return s;
}

}  // namespace
}  // namespace asbuilt

int main(int argc, char** argv) {
  using namespace asbuilt;
  const std::string out_path = bench::ResultsPath(argc, argv, "labels");
  const fs::path rooms = fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public";
  const double kThreshold = ConvertOptions{}.threshold;

  struct Drift {
    const char* name;
    IdMapDriftOptions options;
  };
  const Drift drifts[] = {
      {"moderate (defaults)", {}},
      {"strong",
       {.brightness_min = 0.45,
        .brightness_max = 1.05,
        .saturation_min = 0.6,
        .hue_shift_deg = 10,
        .class_reflectance = 0.12,
        .noise_sigma = 4}},
  };

  std::vector<Set> sets;
  // (a) The renderer's own ID maps.
  const fs::path tmp = fs::temp_directory_path() / "asbuilt_bench_labels";
  fs::remove_all(tmp);
  for (double id_drift : {RenderOptions{}.id_drift, 0.5, 1.0}) {
    DatasetSynthOptions o{.count = 24, .seed = 11};
    o.render.id_drift = id_drift;
    o.render.samples_per_pixel = 1;
    fs::path dir = tmp / fmt::format("render_{}", id_drift);
    DatasetSynthSummary r = SynthesizeDataset(dir, o);
    std::fprintf(stderr, "labels bench: %s\n", r.BriefReport().c_str());
    Set s = ReadFolder(fmt::format("asbuilt renderer {}x{}, id_drift {}{}", o.width_px, o.height_px, id_drift,
                                   id_drift == RenderOptions{}.id_drift ? " (default)" : ""),
                       dir);
    if (!s.idmaps.empty()) sets.push_back(std::move(s));
  }
  // (b) Painted drift.
  for (const Drift& d : drifts) {
    if (fs::exists(rooms)) {
      Set s{fmt::format("Blender-room labels, {} drift", d.name), {}, {}};
      std::uint64_t seed = 1;
      for (const char* room : {"p01_rect_1door_2win", "p02_L_shape"}) {
        for (int i = 0; i < 12; ++i) {
          s.labels.push_back(ReadLabelImage(rooms / room / fmt::format("labels/{:03d}.png", i)));
          IdMapDriftOptions o = d.options;
          o.seed = seed++;
          s.idmaps.push_back(SynthesizeIdMap(s.labels.back(), Palette::Nominal(), o));
        }
      }
      sets.push_back(std::move(s));
    }
    Set p{fmt::format("procedural rooms 640x480, {} drift", d.name), {}, {}};
    for (int i = 0; i < 24; ++i) {
      p.labels.push_back(SyntheticRoomLabels(640, 480, 1000 + i));
      IdMapDriftOptions o = d.options;
      o.seed = 5000 + i;
      p.idmaps.push_back(SynthesizeIdMap(p.labels.back(), Palette::Nominal(), o));
    }
    sets.push_back(std::move(p));
  }
  if (argc > 2) {  // (c) A folder of ID maps with exact labels.
    Set s = ReadFolder(fmt::format("ID maps of {}", fs::path(argv[2]).filename().string()), argv[2]);
    if (!s.idmaps.empty()) sets.push_back(std::move(s));
  }

  std::string md = "## labels: ID map → label conversion\n\n";
  md += fmt::format(
      "Pixel agreement with the exact labels (ignore pixels excluded) on drifted ID maps: even frames calibrate, odd "
      "frames are measured. Band = pixels within 1 px of a label change. Threshold {} (RGB distance) unless swept. "
      "Target ≥ 99.5 % overall with calibration.\n\n",
      kThreshold);
  md += "| ID maps | palette | overall | band (1 px) | interior | band share |\n|---|---|---|---|---|---|\n";
  std::string sweep = "\nThreshold sweep (overall agreement / band):\n\n| ID maps | palette |";
  const double thresholds[] = {20, 40, 60, 80, 100, 140, 200, 442};
  for (double t : thresholds) sweep += fmt::format(" T={} |", t);
  sweep += "\n|---|---|";
  for (std::size_t i = 0; i < std::size(thresholds); ++i) sweep += "---|";
  sweep += "\n";

  for (const Set& all : sets) {
    Set train, test;
    Split(all, train, test);
    struct Named {
      const char* name;
      Palette palette;
    };
    std::vector<Named> palettes = {
        {"nominal", Palette::Nominal()},
        {"calibrated (masks)", CalibrateWithMasks({}, train.idmaps, train.labels).palette},
        {"calibrated (k-means, no masks)", CalibrateByClustering({}, train.idmaps).palette},
    };
    for (const Named& n : palettes) {
      LabelAgreement a = Measure(test, n.palette, kThreshold);
      md += fmt::format("| {} ({} maps) | {} | {} | {} | {} | {} |\n", all.name, test.idmaps.size(), n.name,
                        Pct(a.Overall()), Pct(a.Band()), Pct(a.Interior()),
                        Pct(static_cast<double>(a.band_pixels) / a.pixels));
      if (n.palette.threshold) {
        LabelAgreement s = Measure(test, n.palette, *n.palette.threshold);
        md += fmt::format("| {} ({} maps) | {}, suggested T={:.0f} | {} | {} | {} | {} |\n", all.name,
                          test.idmaps.size(), n.name, *n.palette.threshold, Pct(s.Overall()), Pct(s.Band()),
                          Pct(s.Interior()), Pct(static_cast<double>(s.band_pixels) / s.pixels));
      }
      sweep += fmt::format("| {} | {} |", all.name, n.name);
      for (double t : thresholds) {
        LabelAgreement s = Measure(test, n.palette, t);
        sweep += fmt::format(" {:.2f} / {:.1f} |", 100 * s.Overall(), 100 * s.Band());
      }
      sweep += "\n";
    }
    std::fprintf(stderr, "labels bench: %s done\n", all.name.c_str());
  }
  md += sweep;

  // The nominal colours must be the renderer's.
  bool same = true;
  for (int id = 0; id < 4; ++id) {
    for (int c = 0; c < 3; ++c) same = same && Palette::Nominal().colours[id].rgb[c] == kIdMapColors[id][c];
  }
  md += fmt::format("\nNominal palette equals the renderer's kIdMapColors: {}.\n",
                    same ? "yes" : "NO — fix labels/palette.cc");

  // Throughput: batch conversion of 640x480 PNG files (decode + convert +
  // encode + atomic write), and the in-memory conversion alone.
  std::vector<fs::path> files;
  const Set* first = &sets.front();
  for (const Set& s : sets) {
    if (s.name.rfind("procedural", 0) == 0) {
      first = &s;
      break;
    }
  }
  for (int rep = 0; rep < 4; ++rep) {
    for (std::size_t i = 0; i < first->idmaps.size(); ++i) {
      files.push_back(tmp / "idmap" / fmt::format("{:03d}.png", files.size()));
      WriteImageAtomic(files.back(), first->idmaps[i]);
    }
  }
  Palette p = CalibrateWithMasks({}, first->idmaps, first->labels).palette;
  double mem_s = bench::MedianSeconds(5, [&] {
    for (const cv::Mat& m : first->idmaps) ConvertIdMap(m, p, kThreshold);
  });
  double mpx = 0;
  for (const cv::Mat& m : first->idmaps) mpx += m.total() / 1e6;
  ConvertSummary one, all;
  double one_s = bench::MedianSeconds(3, [&] { one = ConvertIdMapFiles({.num_threads = 1}, p, files, tmp / "out1"); });
  double all_s = bench::MedianSeconds(3, [&] { all = ConvertIdMapFiles({}, p, files, tmp / "outN"); });
  md += fmt::format(
      "\nSpeed ({} files of 640x480): in-memory conversion {:.0f} Mpx/s (one thread); batch with PNG decode/encode "
      "and atomic writes: {:.0f} files/s on 1 thread, {:.0f} files/s on all cores ({} cores).\n",
      files.size(), mpx / mem_s, files.size() / one_s, files.size() / all_s, std::thread::hardware_concurrency());
  fs::remove_all(tmp);
  bench::WriteSection(out_path, md);
  return 0;
}
