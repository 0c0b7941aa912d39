#include "asbuilt/dataset/pairs.h"

#include <algorithm>
#include <cctype>
#include <map>

#include <fmt/format.h>

#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/text.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

// Regular files of `dir` with an accepted extension, by stem. Throws on an
// unreadable folder or on two files with one stem.
std::map<std::string, fs::path> FilesByStem(const fs::path& dir, bool png_only) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string(), "", "not a folder");
  std::map<std::string, fs::path> out;
  fs::directory_iterator it(dir, ec);
  if (ec) throw InputError(dir.string(), "", "cannot read: " + ec.message());
  for (const fs::directory_entry& entry : it) {
    const fs::path& p = entry.path();
    std::string name = p.filename().string();
    if (name.empty() || name[0] == '.' || IsAtomicTempName(p)) continue;
    if (!entry.is_regular_file(ec)) continue;
    if (png_only ? AsciiLower(p.extension().string()) != ".png" : !IsImageExtension(p)) continue;
    auto [pos, inserted] = out.emplace(p.stem().string(), p);
    if (!inserted) {
      throw InputError(
          p.string(), "",
          fmt::format("two files share the stem '{}' (also {})", p.stem().string(), pos->second.filename().string()));
    }
  }
  return out;
}

void Append(PairListing& into, PairListing from, const std::string& prefix) {
  for (ImagePair& p : from.pairs) {
    p.name = prefix.empty() ? p.name : prefix + "/" + p.name;
    into.pairs.push_back(std::move(p));
  }
  for (auto& p : from.images_without_label) into.images_without_label.push_back(std::move(p));
  for (auto& p : from.labels_without_image) into.labels_without_image.push_back(std::move(p));
}

// Depth-first over the tree; `prefix` is the path of `dir` below the top.
void CollectDataset(const fs::path& dir, const std::string& prefix, int depth, PairListing& out, bool& found) {
  std::error_code ec;
  if (fs::is_directory(dir / "labels", ec)) {
    for (const char* images : {"images", "left"}) {
      if (fs::is_directory(dir / images, ec)) {
        Append(out, ListPairs(dir / images, dir / "labels"), prefix);
        found = true;
        return;
      }
    }
  }
  if (depth >= 8) return;
  std::vector<fs::path> subdirs;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    std::string name = entry.path().filename().string();
    if (!name.empty() && name[0] != '.' && entry.is_directory(ec)) subdirs.push_back(entry.path());
  }
  std::sort(subdirs.begin(), subdirs.end());
  for (const fs::path& sub : subdirs) {
    std::string name = sub.filename().string();
    CollectDataset(sub, prefix.empty() ? name : prefix + "/" + name, depth + 1, out, found);
  }
}

}  // namespace

std::string ImagePair::ToString() const { return fmt::format("{} ({}, {})", name, image.string(), label.string()); }

std::string PairListing::ToString() const {
  auto plural = [](std::size_t n, const char* word, const char* words) {
    return fmt::format("{} {}", n, n == 1 ? word : words);
  };
  return fmt::format("{} ({}, {})", plural(pairs.size(), "pair", "pairs"),
                     plural(images_without_label.size(), "image without label", "images without label"),
                     plural(labels_without_image.size(), "label without image", "labels without image"));
}

PairListing ListPairs(const fs::path& images_dir, const fs::path& labels_dir) {
  std::map<std::string, fs::path> images = FilesByStem(images_dir, /*png_only=*/false);
  std::map<std::string, fs::path> labels = FilesByStem(labels_dir, /*png_only=*/true);
  PairListing out;
  for (const auto& [stem, image] : images) {
    auto it = labels.find(stem);
    if (it == labels.end()) {
      out.images_without_label.push_back(image);
    } else {
      out.pairs.push_back({stem, image, it->second});
    }
  }
  for (const auto& [stem, label] : labels) {
    if (!images.count(stem)) out.labels_without_image.push_back(label);
  }
  return out;
}

PairListing ListDatasetPairs(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir.string(), "", "not a folder");
  PairListing out;
  bool found = false;
  CollectDataset(dir, "", 0, out, found);
  if (!found) {
    throw InputError(dir.string(), "", "no dataset here: expected images/ + labels/ or left/ + labels/ (at any depth)");
  }
  std::sort(out.pairs.begin(), out.pairs.end(), [](const ImagePair& a, const ImagePair& b) { return a.name < b.name; });
  return out;
}

}  // namespace asbuilt
