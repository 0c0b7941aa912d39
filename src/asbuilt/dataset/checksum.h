#ifndef ASBUILT_DATASET_CHECKSUM_H_
#define ASBUILT_DATASET_CHECKSUM_H_

// SHA-256 of files and bytes (OpenSSL), as lowercase hex — the checksums
// recorded in manifests, comparable with `sha256sum`.

#include <filesystem>
#include <string>
#include <string_view>

namespace asbuilt {

// Throws InputError(file, "", "cannot read: …") if the file cannot be read.
std::string Sha256OfFile(const std::filesystem::path& path);
std::string Sha256OfBytes(std::string_view bytes);

// True for 64 lowercase hex digits.
bool IsSha256Hex(std::string_view text);

}  // namespace asbuilt

#endif  // ASBUILT_DATASET_CHECKSUM_H_
