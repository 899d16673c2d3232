// Reading scene and mesh files whole, inflating gzip-compressed ones through zlib
// (pbrt-v4 scenes ship ".pbrt.gz" includes and ".ply.gz" meshes).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "dermis/core/load_monitor.h"

namespace dermis {

// The most bytes a gzip file may inflate to: 4 GiB. A larger result is taken as a corrupt
// file or a decompression bomb and reported, before memory runs out.
inline constexpr uint64_t kMaxDecompressedBytes = uint64_t(4) << 30;

// True when `head` starts with the gzip magic bytes.
bool has_gzip_magic(std::string_view head);

// A file that could not be read. what() is "path: reason"; reason() is the part after the
// path, for messages that name the file already.
class FileReadError : public std::runtime_error {
 public:
  FileReadError(const std::string& path, const std::string& reason);
  const std::string& path() const { return path_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string path_;
  std::string reason_;
};

// The contents of `path`. A file that starts with the gzip magic (whatever its name) is
// inflated, streaming, member after member (trailing zero padding is ignored); any other
// file is returned as it is. Throws FileReadError when the file cannot be opened or read,
// is a directory, holds gzip data that is corrupt or truncated ("gzip data is
// corrupt/truncated (zlib: ...)"), or inflates to more than `max_decompressed` bytes.
// With a `stage`, reports the fraction of the file's bytes read (compressed bytes for
// gzip) and throws Interrupted when cancelled.
std::string read_file_contents(const std::string& path, uint64_t max_decompressed = kMaxDecompressedBytes,
                               LoadStage* stage = nullptr);

}  // namespace dermis
