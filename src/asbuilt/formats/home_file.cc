#include "asbuilt/formats/home_file.h"

#include <map>

#include <fmt/format.h>

#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

// A room's name becomes a folder name: no separators, not "." or "..".
std::optional<std::string> FolderNameProblem(const std::string& name) {
  if (name.empty()) return "must not be empty";
  if (name == "." || name == "..") return fmt::format("\"{}\" cannot name a folder", name);
  for (char c : name) {
    if (c == '/' || c == '\\' || static_cast<unsigned char>(c) < 0x20) {
      return fmt::format("\"{}\" cannot name a folder (no '/', '\\' or control characters)", name);
    }
  }
  return std::nullopt;
}

Home ParseHome(const nlohmann::json& root, const fs::path& path, JsonDiagnostics& diag) {
  Home home;
  home.file = path;
  JsonField doc(root, diag);
  if (!doc.Object({"version", "kind", "rooms"})) return home;
  if (auto v = doc.Required("version").Integer(); v && *v != 1) {
    doc.Required("version").AddError(fmt::format("unsupported version {}, expected 1", *v));
  }
  if (auto k = doc.Required("kind").String(); k && *k != "home") {
    doc.Required("kind").AddError(fmt::format("expected \"home\", got \"{}\"", *k));
  }
  JsonField rooms = doc.Required("rooms");
  const auto n = rooms.ArraySize(1);
  std::map<std::string, std::size_t> first_of_name;
  const fs::path base = path.parent_path();
  for (std::size_t i = 0; n && i < *n; ++i) {
    JsonField r = rooms.At(i);
    if (!r.Object({"name", "capture", "hint", "labels"})) continue;
    HomeRoom room;
    if (auto name = r.Required("name").String()) {
      room.name = *name;
      if (auto problem = FolderNameProblem(*name)) {
        r.Required("name").AddError(*problem);
      } else if (auto [it, fresh] = first_of_name.emplace(*name, i); !fresh) {
        r.Required("name").AddError(
            fmt::format("\"{}\" is also rooms[{}]'s name: names must differ", *name, it->second));
      }
    }
    if (auto capture = r.Required("capture").String()) {
      if (capture->empty()) r.Required("capture").AddError("must name a capture.json");
      room.capture = base / *capture;
    }
    if (JsonField h = r.Optional("hint"); h.present() && h.Object({"position_m", "yaw_deg"})) {
      HomeRoomHint hint;
      if (auto p = h.Required("position_m").NumberArray(2)) hint.position_m = Vec2((*p)[0], (*p)[1]);
      if (auto y = h.Optional("yaw_deg").Number()) hint.yaw_deg = *y;
      room.hint = hint;
    }
    if (auto labels = r.Optional("labels").String()) room.labels = base / *labels;
    home.rooms.push_back(std::move(room));
  }
  return home;
}

}  // namespace

Home ReadHome(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  nlohmann::json root = ParseJsonFile(path, diag);
  Home home = diag.ok() ? ParseHome(root, path, diag) : Home{};
  diag.ThrowIfErrors();
  diag.LogWarnings();
  return home;
}

FileReport CheckHomeFile(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  nlohmann::json root = ParseJsonFile(path, diag);
  if (diag.ok()) ParseHome(root, path, diag);
  return {diag.errors(), diag.warnings()};
}

bool IsHomeFile(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  const nlohmann::json root = ParseJsonFile(path, diag);
  return diag.ok() && root.is_object() && root.contains("kind") && root["kind"] == "home";
}

}  // namespace asbuilt
