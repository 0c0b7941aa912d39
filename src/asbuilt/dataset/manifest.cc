#include "asbuilt/dataset/manifest.h"

#include <map>
#include <set>

#include <fmt/format.h>

#include "asbuilt/dataset/checksum.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

constexpr const char* kSplitNames[] = {"train", "val", "test"};

std::vector<ManifestEntry>& Split(Manifest& m, int i) { return i == 0 ? m.train : i == 1 ? m.val : m.test; }
const std::vector<ManifestEntry>& Split(const Manifest& m, int i) { return i == 0 ? m.train : i == 1 ? m.val : m.test; }

Manifest ParseManifest(const fs::path& path, const ReadManifestOptions& options, JsonDiagnostics& diag) {
  Manifest manifest;
  manifest.base_dir = path.parent_path();
  nlohmann::json root = ParseJsonFile(path, diag);
  if (!diag.ok()) return manifest;
  JsonField doc(root, diag);
  if (!doc.Object({"version", "config", "seed", "root", "train", "val", "test"})) return manifest;
  if (auto v = doc.Required("version").Integer()) {
    if (*v != 1) doc.Required("version").AddError(fmt::format("unsupported version {}, expected 1", *v));
  }
  if (auto v = doc.Required("config").String()) manifest.config = *v;
  if (auto v = doc.Optional("seed").Integer()) {
    if (*v < 0) {
      doc.Optional("seed").AddError(fmt::format("must be >= 0, got {}", *v));
    } else {
      manifest.seed = static_cast<std::uint64_t>(*v);
    }
  }
  if (auto v = doc.Optional("root").String()) {
    manifest.root = *v;
    std::error_code ec;
    if (!fs::is_directory(manifest.Resolve(""), ec)) {
      doc.Optional("root").AddError(fmt::format("folder not found: {}", manifest.Resolve("").string()));
    }
  }

  // Where each (image, label) pair was first listed, to catch duplicates and
  // test pairs leaking into training.
  std::map<std::pair<std::string, std::string>, std::string> seen;
  for (int s = 0; s < 3; ++s) {
    const char* split = kSplitNames[s];
    JsonField list = s == 2 ? doc.Optional(split) : doc.Required(split);
    if (!list.present()) continue;
    std::optional<std::size_t> n = list.ArraySize();
    for (std::size_t i = 0; n && i < *n; ++i) {
      JsonField e = list.At(i);
      if (!e.Object({"image", "label", "source", "sha256", "label_sha256"})) continue;
      ManifestEntry entry;
      auto read_file = [&](const char* key, const char* sha_key, std::string& out, std::string& sha_out) {
        JsonField f = e.Required(key);
        auto v = f.String();
        if (!v) return;
        if (v->empty()) {
          f.AddError("empty path");
          return;
        }
        out = *v;
        fs::path resolved = manifest.Resolve(*v);
        std::error_code ec;
        bool exists = fs::is_regular_file(resolved, ec);
        if (!exists) f.AddError(fmt::format("file not found: {}", resolved.string()));
        JsonField sha = e.Optional(sha_key);
        if (auto h = sha.String()) {
          if (!IsSha256Hex(*h)) {
            sha.AddError(fmt::format("expected 64 lowercase hex digits, got \"{}\"", *h));
          } else {
            sha_out = *h;
            if (exists && options.verify_checksums) {
              std::string actual = Sha256OfFile(resolved);
              if (actual != *h) {
                sha.AddError(fmt::format("checksum mismatch for {}: file has {}", resolved.string(), actual));
              }
            }
          }
        }
      };
      read_file("image", "sha256", entry.image, entry.sha256);
      read_file("label", "label_sha256", entry.label, entry.label_sha256);
      JsonField source = e.Required("source");
      if (auto v = source.String()) {
        if (*v == "real") {
          entry.source = PairSource::kReal;
        } else if (*v == "synthetic") {
          entry.source = PairSource::kSynthetic;
          if (s == 2) source.AddError("the test list holds real pairs only, got a synthetic pair");
        } else {
          source.AddError(fmt::format("expected \"real\" or \"synthetic\", got \"{}\"", *v));
        }
      }
      if (!entry.image.empty() && !entry.label.empty()) {
        std::string where = fmt::format("{}[{}]", split, i);
        auto [it, inserted] = seen.emplace(std::pair{entry.image, entry.label}, where);
        if (!inserted) {
          bool leak = s == 2 && it->second.rfind("test", 0) != 0;
          e.AddError(
              leak ? fmt::format("test pair {} is also listed in {} (test must stay held out)", entry.image, it->second)
                   : fmt::format("pair {} is listed twice (also {})", entry.image, it->second));
        }
      }
      Split(manifest, s).push_back(std::move(entry));
    }
  }
  return manifest;
}

}  // namespace

const char* PairSourceName(PairSource source) { return source == PairSource::kReal ? "real" : "synthetic"; }

std::string ManifestEntry::ToString() const {
  return fmt::format("ManifestEntry({}, {}, {})", image, label, PairSourceName(source));
}

fs::path Manifest::Resolve(const std::string& relative) const {
  fs::path p(relative);
  if (p.is_absolute()) return p;
  fs::path base = base_dir;
  if (root) base = fs::path(*root).is_absolute() ? fs::path(*root) : base_dir / *root;
  return relative.empty() ? base : base / p;
}

std::string Manifest::ToString() const {
  return fmt::format("Manifest({}, seed {}: {} train, {} val, {} test)", config.empty() ? "?" : config, seed,
                     train.size(), val.size(), test.size());
}

Manifest ReadManifest(const fs::path& path, const ReadManifestOptions& options) {
  JsonDiagnostics diag(path.string());
  Manifest manifest = ParseManifest(path, options, diag);
  diag.ThrowIfErrors();
  diag.LogWarnings();
  return manifest;
}

FileReport CheckManifestFile(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  ParseManifest(path, {.verify_checksums = true}, diag);
  return {diag.errors(), diag.warnings()};
}

Manifest ReadManifestLenient(const fs::path& path, const ReadManifestOptions& options, FileReport& report) {
  JsonDiagnostics diag(path.string());
  Manifest manifest = ParseManifest(path, options, diag);
  report = {diag.errors(), diag.warnings()};
  return manifest;
}

nlohmann::json ManifestToJson(const Manifest& manifest) {
  nlohmann::json j;
  j["version"] = manifest.version;
  j["config"] = manifest.config;
  j["seed"] = manifest.seed;
  if (manifest.root) j["root"] = *manifest.root;
  for (int s = 0; s < 3; ++s) {
    nlohmann::json list = nlohmann::json::array();
    for (const ManifestEntry& e : Split(manifest, s)) {
      nlohmann::json je = {{"image", e.image}, {"label", e.label}, {"source", PairSourceName(e.source)}};
      if (!e.sha256.empty()) je["sha256"] = e.sha256;
      if (!e.label_sha256.empty()) je["label_sha256"] = e.label_sha256;
      list.push_back(std::move(je));
    }
    j[kSplitNames[s]] = std::move(list);
  }
  return j;
}

void WriteManifest(const Manifest& manifest, const fs::path& path) {
  WriteFileAtomic(path, ManifestToJson(manifest).dump(1) + "\n");
}

std::string RelativePathForManifest(const fs::path& path, const fs::path& base) {
  std::error_code ec;
  fs::path abs_path = fs::weakly_canonical(fs::absolute(path), ec);
  if (ec) abs_path = fs::absolute(path);
  fs::path abs_base = fs::weakly_canonical(fs::absolute(base.empty() ? fs::path(".") : base), ec);
  if (ec) abs_base = fs::absolute(base);
  fs::path rel = abs_path.lexically_relative(abs_base);
  return rel.empty() ? abs_path.generic_string() : rel.generic_string();
}

}  // namespace asbuilt
