#ifndef ASBUILT_FORMATS_SYNTH_DATASET_H_
#define ASBUILT_FORMATS_SYNTH_DATASET_H_

// A synthetic dataset folder (`asbuilt dataset synth`) on disk: which files
// make item i, the one rule that says an item is complete (resume, merge,
// verify and `cluster status` all use it), and the run record that ties a
// folder to the options that made it (docs/formats.md "Synthetic datasets").
//
//   DIR/synth.json                 {"version": 1, "kind": "asbuilt-synth", "options": {...}}
//   DIR/images|labels|idmaps|depth/NNNNNN.png, DIR/meta/NNNNNN.json
//   DIR/synth_manifest.json        every item's files and their SHA-256 (dataset merge)
//
// Every file is written atomically (temp name + rename) and the meta file
// last, so an item whose files all exist under their final names is whole.

#include <array>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace asbuilt {

// The item subfolders, meta (written last) at the end.
inline constexpr std::array<const char*, 5> kSynthItemFolders = {"images", "labels", "idmaps", "depth", "meta"};

// DIR/<folder>/NNNNNN.{png,json} for each of kSynthItemFolders, in its order.
std::array<std::filesystem::path, 5> SynthItemFiles(const std::filesystem::path& dir, int index);
// "images/000012.png" etc.: the same, relative to DIR with '/' separators.
std::array<std::string, 5> SynthItemRelativeFiles(int index);

// Complete: every file of the item exists under its final name.
bool IsSynthItemComplete(const std::filesystem::path& dir, int index);

// Ties DIR to the options that make its items (`options` as the synth writes
// it: everything that changes an item's bytes, nothing that does not, such as
// the shard). A new folder gets DIR/synth.json; a folder made with the same
// options is accepted; a folder made with other options throws InputError
// naming each option that differs, and nothing is written.
void ClaimSynthDir(const std::filesystem::path& dir, const nlohmann::json& options);
// The same check, writing nothing (a dry run).
void CheckSynthDir(const std::filesystem::path& dir, const nlohmann::json& options);

// The options DIR/synth.json records. Throws InputError naming the file when
// it is missing or not a synth record.
nlohmann::json ReadSynthRecord(const std::filesystem::path& dir);

std::filesystem::path SynthRecordPath(const std::filesystem::path& dir);    // DIR/synth.json
std::filesystem::path SynthManifestPath(const std::filesystem::path& dir);  // DIR/synth_manifest.json

}  // namespace asbuilt

#endif  // ASBUILT_FORMATS_SYNTH_DATASET_H_
