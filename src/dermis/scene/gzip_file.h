// Reading scene and mesh files, inflating gzip-compressed ones through zlib (pbrt-v4
// scenes ship ".pbrt.gz" includes and ".ply.gz" meshes): whole, or a chunk at a time.
#pragma once

#include <cstdint>
#include <memory>
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

// A file's contents a chunk at a time, never whole (a scene's grid medium may be hundreds of
// megabytes of text): its bytes, or for a file that starts with the gzip magic (whatever its
// name) their inflation, member after member (trailing zero padding is ignored). Throws
// FileReadError as read_file_contents does: when the file cannot be opened, on opening;
// when it cannot be read on, is corrupt or inflates past `max_decompressed`, from next().
class FileChunks {
 public:
  explicit FileChunks(const std::string& path, uint64_t max_decompressed = kMaxDecompressedBytes);
  ~FileChunks();
  FileChunks(const FileChunks&) = delete;
  FileChunks& operator=(const FileChunks&) = delete;

  // The next bytes of the contents; empty at their end. Valid until the next call.
  std::string_view next();
  // The fraction of the file's bytes read so far (compressed bytes for gzip).
  double fraction_read() const;
  // About how many bytes the contents hold (gzip: its trailer's word, if plausible; else 0).
  uint64_t size_hint() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
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
