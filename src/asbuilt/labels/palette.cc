#include "asbuilt/labels/palette.h"

#include <cmath>

#include <fmt/format.h>

#include "asbuilt/formats/points_file.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

Palette ParsePalette(const fs::path& path, JsonDiagnostics& diag) {
  Palette palette;
  palette.method = "";
  nlohmann::json root = ParseJsonFile(path, diag);
  if (!diag.ok()) return palette;
  JsonField doc(root, diag);
  if (!doc.Object({"version", "method", "threshold", "colours"})) return palette;
  if (auto v = doc.Required("version").Integer()) {
    if (*v != 1) doc.Required("version").AddError(fmt::format("unsupported version {}, expected 1", *v));
  }
  if (auto v = doc.Optional("method").String()) palette.method = *v;
  if (auto v = doc.Optional("threshold").Positive()) palette.threshold = *v;
  JsonField colours = doc.Required("colours");
  std::optional<std::size_t> n = colours.ArraySize(1);
  for (std::size_t i = 0; n && i < *n; ++i) {
    JsonField c = colours.At(i);
    if (!c.Object({"class", "id", "rgb", "pixels", "rms_distance"})) continue;
    PaletteColour colour;
    JsonField id = c.Required("id");
    if (auto v = id.Integer()) {
      if (*v < 0 || *v > 3) {
        id.AddError(fmt::format("must be a label id 0..3 (background, wall, door, window), got {}", *v));
      } else {
        colour.id = static_cast<std::uint8_t>(*v);
      }
    }
    if (auto v = c.Optional("class").String()) {
      if (diag.ok() && *v != LabelIdName(colour.id)) {
        c.Optional("class").AddWarning(fmt::format("class \"{}\" does not match id {} ({}); the id is used", *v,
                                                   colour.id, LabelIdName(colour.id)));
      }
    }
    JsonField rgb = c.Required("rgb");
    if (auto v = rgb.NumberArray(3)) {
      for (int k = 0; k < 3; ++k) {
        if ((*v)[k] < 0 || (*v)[k] > 255) {
          rgb.AddError(fmt::format("channel {} = {} is outside 0..255", k, (*v)[k]));
          break;
        }
        colour.rgb[k] = (*v)[k];
      }
    }
    if (auto v = c.Optional("pixels").Integer()) {
      if (*v < 0) c.Optional("pixels").AddError(fmt::format("must be >= 0, got {}", *v));
      colour.pixels = *v;
    }
    if (auto v = c.Optional("rms_distance").NonNegative()) colour.rms_distance = *v;
    palette.colours.push_back(colour);
  }
  return palette;
}

}  // namespace

std::string LabelIdName(std::uint8_t id) {
  if (id <= 3) return LabelClassName(static_cast<LabelClass>(id));
  if (id == kLabelIgnore) return "ignore";
  return std::to_string(id);
}

std::string PaletteColour::ToString() const {
  return fmt::format("{} ({}): rgb({:.1f}, {:.1f}, {:.1f})", LabelIdName(id), id, rgb[0], rgb[1], rgb[2]);
}

Palette Palette::Nominal() {
  Palette p;
  p.method = "nominal";
  // Keep equal to render/renderer.h kIdMapColors (labels may not include
  // render: same layer); bench/labels checks the two agree.
  p.colours = {{0, {0, 0, 0}, 0}, {1, {200, 40, 40}, 0}, {2, {40, 180, 60}, 0}, {3, {40, 80, 200}, 0}};
  return p;
}

std::string Palette::ToString() const {
  std::string out = fmt::format("Palette({}:", method);
  for (std::size_t i = 0; i < colours.size(); ++i) {
    const PaletteColour& c = colours[i];
    out += fmt::format("{} {} rgb({:.1f}, {:.1f}, {:.1f})", i == 0 ? "" : ",", LabelIdName(c.id), c.rgb[0], c.rgb[1],
                       c.rgb[2]);
  }
  if (threshold) out += fmt::format("; threshold {:.1f}", *threshold);
  return out + ")";
}

Palette ReadPalette(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  Palette palette = ParsePalette(path, diag);
  diag.ThrowIfErrors();
  diag.LogWarnings();
  return palette;
}

FileReport CheckPaletteFile(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  ParsePalette(path, diag);
  return {diag.errors(), diag.warnings()};
}

nlohmann::json PaletteToJson(const Palette& palette) {
  nlohmann::json colours = nlohmann::json::array();
  for (const PaletteColour& c : palette.colours) {
    auto round1 = [](double v) { return std::round(v * 1000.0) / 1000.0; };
    nlohmann::json jc = {
        {"class", LabelIdName(c.id)}, {"id", c.id}, {"rgb", {round1(c.rgb[0]), round1(c.rgb[1]), round1(c.rgb[2])}}};
    if (c.pixels > 0) jc["pixels"] = c.pixels;
    if (c.rms_distance > 0) jc["rms_distance"] = round1(c.rms_distance);
    colours.push_back(std::move(jc));
  }
  nlohmann::json j = {{"version", 1}, {"method", palette.method}};
  if (palette.threshold) j["threshold"] = std::round(*palette.threshold * 1000.0) / 1000.0;
  j["colours"] = std::move(colours);
  return j;
}

void WritePalette(const Palette& palette, const fs::path& path) {
  WriteFileAtomic(path, PaletteToJson(palette).dump(2) + "\n");
}

}  // namespace asbuilt
