#ifndef ASBUILT_DATASET_MANIFEST_H_
#define ASBUILT_DATASET_MANIFEST_H_

// manifest.json — one training mix: which (image, label) pairs go to train,
// val and test, where each came from (real photo or synthetic render), and a
// checksum of each file so a run can prove what it trained on. Written by
// `asbuilt dataset mix`, read by `asbuilt train` / `asbuilt eval`.
//
//   {"version": 1, "config": "RS5050", "seed": 7,
//    "root": "data",                                   (optional)
//    "train": [{"image": "real/images/a.jpg", "label": "real/labels/a.png",
//               "source": "real", "sha256": "…", "label_sha256": "…"}],
//    "val": [...], "test": [...]}
//
// Paths are relative to `root`, which is itself relative to the manifest's
// folder (absent: the manifest's folder). Absolute paths are kept as they
// are. `sha256` is the SHA-256 of the image file, `label_sha256` that of the
// label file (both lowercase hex; optional when reading). `test` holds real
// pairs only, never mixed into train or val.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/formats/capture.h"  // FileReport

namespace asbuilt {

enum class PairSource : std::uint8_t { kReal, kSynthetic };
const char* PairSourceName(PairSource source);  // "real", "synthetic"

struct ManifestEntry {
  std::string image;  // Relative to Manifest::root (see Resolve()).
  std::string label;  // Single-channel 8-bit label PNG, ids {0,1,2,3,255}.
  PairSource source = PairSource::kReal;
  std::string sha256;        // Of the image file; empty: not recorded.
  std::string label_sha256;  // Of the label file; empty: not recorded.

  std::string ToString() const;
  bool operator==(const ManifestEntry&) const = default;
};

struct Manifest {
  int version = 1;
  std::string config;  // Mix name: "R100", "S100", "RS5050", … (free text allowed).
  std::uint64_t seed = 0;
  std::optional<std::string> root;  // Relative to the manifest's folder.
  std::vector<ManifestEntry> train;
  std::vector<ManifestEntry> val;
  std::vector<ManifestEntry> test;

  // Folder the file was read from or will be written to (not serialised).
  std::filesystem::path base_dir;
  // base_dir / root / relative, or `relative` itself when absolute.
  std::filesystem::path Resolve(const std::string& relative) const;

  // "Manifest(RS5050, seed 7: 900 train, 100 val, 40 test)".
  std::string ToString() const;
};

struct ReadManifestOptions {
  // Recompute every file's SHA-256 and compare with the recorded one. Reads
  // every file; off by default (existence is always checked).
  bool verify_checksums = false;
};

// Reads and validates a manifest. Throws InputError listing every problem
// with its field path (`manifest.json: train[3].label: file not found:
// /data/labels/x.png`): wrong types, unknown source, a bad checksum string,
// missing files, a pair listed twice, a test pair that also appears in train
// or val, a synthetic pair in test, a checksum mismatch (when verifying).
// Unknown keys are logged as warnings.
Manifest ReadManifest(const std::filesystem::path& path, const ReadManifestOptions& options = {});

// Every problem in a manifest (errors and warnings), without throwing; for
// `asbuilt validate`. Verifies checksums.
FileReport CheckManifestFile(const std::filesystem::path& path);

// Reads what can be read and reports every problem in `report` without
// throwing (entries with a missing file are kept); for `asbuilt dataset
// check`, which goes on with the pairs that exist.
Manifest ReadManifestLenient(const std::filesystem::path& path, const ReadManifestOptions& options, FileReport& report);

// Writes atomically. `manifest.base_dir` is ignored: paths are written as
// stored, so they must already be relative to path's folder (and root).
void WriteManifest(const Manifest& manifest, const std::filesystem::path& path);
nlohmann::json ManifestToJson(const Manifest& manifest);

// `path` relative to `base` (generic '/' separators, with "../" when it lies
// outside), so a tree moved as a whole keeps working. For building entries.
std::string RelativePathForManifest(const std::filesystem::path& path, const std::filesystem::path& base);

}  // namespace asbuilt

#endif  // ASBUILT_DATASET_MANIFEST_H_
