#ifndef ASBUILT_FORMATS_SAFETENSORS_H_
#define ASBUILT_FORMATS_SAFETENSORS_H_

// safetensors files (https://github.com/huggingface/safetensors): the plain
// tensor container PyTorch users exchange weights in. asbuilt reads and
// writes it to move SegFormer weights between its LibTorch checkpoints and
// Python (`asbuilt model export|import`, tools/pytorch/). No LibTorch here:
// tensors are raw little-endian bytes with a dtype name and a shape.
//
// Layout: u64 little-endian N, N bytes of JSON header
//   {"name": {"dtype": "F32", "shape": [2, 3], "data_offsets": [0, 24]}, ...,
//    "__metadata__": {"key": "string value", ...}}
// then the data; offsets are relative to the end of the header, and the
// tensors tile the data exactly (no gaps, no overlaps).

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace asbuilt {

struct SafeTensor {
  std::string dtype;  // "F32", "F16", "BF16", "F64", "I64", "I32", "I16", "I8", "U8", "BOOL".
  std::vector<std::int64_t> shape;
  std::string data;  // numel × DtypeBytes(dtype) little-endian bytes.
  std::int64_t numel() const;
};

struct SafeTensorsFile {
  std::map<std::string, SafeTensor> tensors;
  std::map<std::string, std::string> metadata;  // "__metadata__" (string values only).
};

// Bytes per element of a dtype name; 0 when unknown.
int SafeTensorDtypeBytes(std::string_view dtype);

// Parses a whole file's bytes. Throws InputError(file, field path, message)
// on any inconsistency: short file, header length beyond the file, header
// not a JSON object, unknown dtype, negative dimension, offsets out of range
// or not matching the shape, gaps or overlaps, non-string metadata.
SafeTensorsFile ParseSafeTensors(std::string_view bytes, const std::string& file);
SafeTensorsFile ReadSafeTensors(const std::filesystem::path& path);

// Serialises (tensors in name order, header padded to 8 bytes) and writes
// atomically. Throws InvalidArgument when a tensor's data size does not
// match its shape and dtype.
std::string SerializeSafeTensors(const SafeTensorsFile& file);
void WriteSafeTensors(const std::filesystem::path& path, const SafeTensorsFile& file);

}  // namespace asbuilt

#endif  // ASBUILT_FORMATS_SAFETENSORS_H_
