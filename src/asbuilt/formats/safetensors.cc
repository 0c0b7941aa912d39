#include "asbuilt/formats/safetensors.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {

constexpr std::uint64_t kMaxHeaderBytes = 100u << 20;  // The reference implementation's limit.

std::uint64_t ReadU64Le(std::string_view bytes) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[static_cast<size_t>(i)]);
  return v;
}

void AppendU64Le(std::string& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

}  // namespace

std::int64_t SafeTensor::numel() const {
  std::int64_t n = 1;
  for (std::int64_t d : shape) n *= d;
  return n;
}

int SafeTensorDtypeBytes(std::string_view dtype) {
  if (dtype == "F64" || dtype == "I64" || dtype == "U64") return 8;
  if (dtype == "F32" || dtype == "I32" || dtype == "U32") return 4;
  if (dtype == "F16" || dtype == "BF16" || dtype == "I16" || dtype == "U16") return 2;
  if (dtype == "I8" || dtype == "U8" || dtype == "BOOL") return 1;
  return 0;
}

SafeTensorsFile ParseSafeTensors(std::string_view bytes, const std::string& file) {
  if (bytes.size() < 8) throw InputError(file, "", "too short for a safetensors file (no header length)");
  const std::uint64_t n = ReadU64Le(bytes);
  if (n > kMaxHeaderBytes || n > bytes.size() - 8) {
    throw InputError(file, "", fmt::format("header length {} exceeds the file ({} bytes)", n, bytes.size()));
  }
  nlohmann::json header = nlohmann::json::parse(bytes.substr(8, n), nullptr, /*allow_exceptions=*/false);
  if (header.is_discarded() || !header.is_object()) throw InputError(file, "", "header is not a JSON object");
  const std::string_view data = bytes.substr(8 + n);

  SafeTensorsFile out;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> spans;
  for (auto it = header.begin(); it != header.end(); ++it) {
    const std::string& name = it.key();
    const nlohmann::json& h = it.value();
    if (name == "__metadata__") {
      if (!h.is_object()) throw InputError(file, name, "must be an object of strings");
      for (auto m = h.begin(); m != h.end(); ++m) {
        if (!m.value().is_string()) throw InputError(file, name + "." + m.key(), "must be a string");
        out.metadata[m.key()] = m.value().get<std::string>();
      }
      continue;
    }
    if (!h.is_object() || !h.contains("dtype") || !h.contains("shape") || !h.contains("data_offsets")) {
      throw InputError(file, name, "needs dtype, shape and data_offsets");
    }
    SafeTensor t;
    if (!h["dtype"].is_string() || SafeTensorDtypeBytes(h["dtype"].get<std::string>()) == 0) {
      throw InputError(file, name + ".dtype", fmt::format("unknown dtype {}", h["dtype"].dump()));
    }
    t.dtype = h["dtype"].get<std::string>();
    if (!h["shape"].is_array()) throw InputError(file, name + ".shape", "must be an array");
    std::uint64_t numel = 1;
    for (const auto& d : h["shape"]) {
      if (!d.is_number_unsigned()) throw InputError(file, name + ".shape", "dimensions must be integers ≥ 0");
      const std::uint64_t v = d.get<std::uint64_t>();
      if (v != 0 && numel > std::numeric_limits<std::uint32_t>::max() / std::max<std::uint64_t>(v, 1)) {
        throw InputError(file, name + ".shape", "too many elements");
      }
      numel *= v;
      t.shape.push_back(static_cast<std::int64_t>(v));
    }
    const nlohmann::json& o = h["data_offsets"];
    if (!o.is_array() || o.size() != 2 || !o[0].is_number_unsigned() || !o[1].is_number_unsigned()) {
      throw InputError(file, name + ".data_offsets", "must be two integers [begin, end]");
    }
    const std::uint64_t b = o[0].get<std::uint64_t>(), e = o[1].get<std::uint64_t>();
    const std::uint64_t want = numel * static_cast<std::uint64_t>(SafeTensorDtypeBytes(t.dtype));
    if (b > e || e > data.size()) {
      throw InputError(file, name + ".data_offsets",
                       fmt::format("[{}, {}] outside the data ({} bytes)", b, e, data.size()));
    }
    if (e - b != want) {
      throw InputError(file, name + ".data_offsets",
                       fmt::format("span of {} bytes, but the shape and dtype need {}", e - b, want));
    }
    t.data.assign(data.substr(b, e - b));
    spans.emplace_back(b, e);
    out.tensors.emplace(name, std::move(t));
  }
  // The data must be tiled exactly: sorted spans, each starting where the last ended.
  std::sort(spans.begin(), spans.end());
  std::uint64_t at = 0;
  for (const auto& [b, e] : spans) {
    if (b != at)
      throw InputError(file, "data_offsets", fmt::format("tensor data overlaps or leaves a gap at byte {}", at));
    at = e;
  }
  if (at != data.size()) {
    throw InputError(file, "", fmt::format("{} bytes after the last tensor", data.size() - at));
  }
  return out;
}

SafeTensorsFile ReadSafeTensors(const std::filesystem::path& path) {
  return ParseSafeTensors(ReadFile(path), path.string());
}

std::string SerializeSafeTensors(const SafeTensorsFile& file) {
  nlohmann::json header = nlohmann::json::object();
  std::uint64_t offset = 0;
  for (const auto& [name, t] : file.tensors) {
    const int bytes = SafeTensorDtypeBytes(t.dtype);
    CheckArgument(bytes > 0, fmt::format("safetensors: tensor {} has unknown dtype {}", name, t.dtype));
    CheckArgument(static_cast<std::uint64_t>(t.numel()) * static_cast<std::uint64_t>(bytes) == t.data.size(),
                  fmt::format("safetensors: tensor {} holds {} bytes, its shape needs {}", name, t.data.size(),
                              t.numel() * bytes));
    header[name] = {{"dtype", t.dtype}, {"shape", t.shape}, {"data_offsets", {offset, offset + t.data.size()}}};
    offset += t.data.size();
  }
  if (!file.metadata.empty()) header["__metadata__"] = file.metadata;
  std::string text = header.dump();
  text.append((8 - text.size() % 8) % 8, ' ');
  std::string out;
  out.reserve(8 + text.size() + offset);
  AppendU64Le(out, text.size());
  out += text;
  for (const auto& [name, t] : file.tensors) out += t.data;
  return out;
}

void WriteSafeTensors(const std::filesystem::path& path, const SafeTensorsFile& file) {
  WriteFileAtomic(path, SerializeSafeTensors(file));
}

}  // namespace asbuilt
