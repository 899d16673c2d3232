#include "dermis/scene/gzip_file.h"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

namespace dermis {

namespace {

constexpr size_t kInputChunk = size_t(1) << 18;   // compressed bytes read at a time
constexpr size_t kOutputChunk = size_t(1) << 20;  // least growth of the output buffer
// Deflate expands at most 1032:1, so a trailer size beyond that is not trusted as a hint.
constexpr uint64_t kMaxDeflateRatio = 1032;

struct CloseFile {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, CloseFile>;

// Reads up to `n` bytes; throws on a read error (not at the end of the file).
size_t read_some(std::FILE* f, unsigned char* buf, size_t n, const std::string& path) {
  size_t got = std::fread(buf, 1, n, f);
  if (got < n && std::ferror(f)) throw FileReadError(path, std::strerror(errno));
  return got;
}

uint64_t file_size(const std::string& path) {
  std::error_code ec;
  uintmax_t n = std::filesystem::file_size(path, ec);
  return ec ? 0 : uint64_t(n);
}

// `head`: the bytes already read from the start of the file.
std::string read_plain(std::FILE* f, const std::string& path, std::string_view head, LoadStage* stage) {
  const uint64_t size = file_size(path);
  std::string out;
  out.reserve(size_t(size));
  out.append(head);
  std::vector<unsigned char> buf(kInputChunk);
  while (size_t got = read_some(f, buf.data(), buf.size(), path)) {
    out.append(reinterpret_cast<char*>(buf.data()), got);
    if (stage && size > 0) stage->update(double(out.size()) / double(size));
  }
  return out;
}

// The uncompressed size the last member's trailer states (RFC 1952 ISIZE, modulo 2^32), if
// plausible for the compressed size; only used to size the output buffer.
// The file position is restored.
uint64_t size_hint(std::FILE* f, uint64_t compressed, uint64_t limit) {
  long at = std::ftell(f);
  unsigned char t[4];
  bool ok = at >= 0 && compressed >= 18 && std::fseek(f, -4, SEEK_END) == 0 && std::fread(t, 1, 4, f) == 4;
  if (at < 0 || std::fseek(f, at, SEEK_SET) != 0) ok = false;
  std::clearerr(f);
  if (!ok) return 0;
  uint64_t isize = uint64_t(t[0]) | uint64_t(t[1]) << 8 | uint64_t(t[2]) << 16 | uint64_t(t[3]) << 24;
  return std::min({isize, compressed * kMaxDeflateRatio, limit});
}

// `head`: the bytes already read from the start of the file (the magic).
std::string inflate_gzip(std::FILE* f, const std::string& path, std::string_view head, uint64_t limit,
                         LoadStage* stage) {
  auto corrupt = [&path](const char* why) {
    return FileReadError(path, fmt::format("gzip data is corrupt/truncated (zlib: {})", why));
  };
  z_stream zs{};
  // 16 + MAX_WBITS: a gzip wrapper (not zlib's own), the largest window.
  if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) throw FileReadError(path, "zlib could not be initialised");
  struct End {
    z_stream* zs;
    ~End() { inflateEnd(zs); }
  } end{&zs};

  std::string out;
  const uint64_t compressed = file_size(path);
  out.reserve(size_t(size_hint(f, compressed, limit)));
  const uint64_t cap = limit < UINT64_MAX ? limit + 1 : limit;  // one byte past the limit tells it was passed

  std::vector<unsigned char> in(std::max(kInputChunk, head.size()));
  std::copy(head.begin(), head.end(), in.begin());
  zs.next_in = in.data();
  zs.avail_in = uInt(head.size());
  bool eof = false, between_members = false;
  uint64_t produced = 0, consumed = head.size();
  for (;;) {
    if (zs.avail_in == 0 && !eof) {
      size_t got = read_some(f, in.data(), in.size(), path);
      consumed += got;
      if (stage && compressed > 0) stage->update(double(consumed) / double(compressed));
      eof = got == 0;
      zs.next_in = in.data();
      zs.avail_in = uInt(got);
    }
    if (between_members) {
      // After a member: another member follows, or zero padding, or the end of the file.
      while (zs.avail_in > 0 && *zs.next_in == 0) {
        ++zs.next_in;
        --zs.avail_in;
      }
      if (zs.avail_in == 0) {
        if (eof) break;
        continue;
      }
      if (inflateReset(&zs) != Z_OK) throw corrupt("inflateReset failed");
      between_members = false;
    }
    if (produced == out.size()) {
      uint64_t want = std::min<uint64_t>(std::max<uint64_t>(out.capacity(), produced + kOutputChunk), cap);
      out.resize(size_t(want));
    }
    zs.next_out = reinterpret_cast<Bytef*>(out.data()) + produced;
    zs.avail_out = uInt(std::min<uint64_t>(out.size() - produced, uint64_t(1) << 30));
    uInt room = zs.avail_out;
    int rc = inflate(&zs, Z_NO_FLUSH);
    produced += room - zs.avail_out;
    if (produced > limit)
      throw FileReadError(path, fmt::format("gzip data inflates to more than {} bytes, the limit for one file "
                                            "(a corrupt file or a decompression bomb?)",
                                            limit));
    switch (rc) {
      case Z_OK:
        break;
      case Z_STREAM_END:
        between_members = true;
        break;
      case Z_BUF_ERROR:  // no progress possible: input is needed
        if (zs.avail_in == 0 && eof) throw corrupt("unexpected end of file");
        break;
      case Z_MEM_ERROR:
        throw FileReadError(path, "out of memory while inflating gzip data");
      default:  // Z_DATA_ERROR, Z_NEED_DICT, Z_STREAM_ERROR
        throw corrupt(zs.msg ? zs.msg : "invalid data");
    }
  }
  out.resize(size_t(produced));
  return out;
}

}  // namespace

// RFC 1952, section 2.3.1: every gzip member starts with ID1 = 0x1f, ID2 = 0x8b.
bool has_gzip_magic(std::string_view head) {
  return head.size() >= 2 && static_cast<unsigned char>(head[0]) == 0x1f && static_cast<unsigned char>(head[1]) == 0x8b;
}

FileReadError::FileReadError(const std::string& path, const std::string& reason)
    : std::runtime_error(fmt::format("{}: {}", path, reason)), path_(path), reason_(reason) {}

std::string read_file_contents(const std::string& path, uint64_t max_decompressed, LoadStage* stage) {
  // Only regular files: a FIFO would block in fopen, a device such as /dev/zero never ends.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec) throw FileReadError(path, ec.message());
  if (std::filesystem::is_directory(status)) throw FileReadError(path, "it is a directory");
  if (!std::filesystem::is_regular_file(status))
    throw FileReadError(path, "it is not a regular file (a device, FIFO or socket); only files are read");
  File f(std::fopen(path.c_str(), "rb"));
  if (!f) throw FileReadError(path, std::strerror(errno));
  unsigned char bytes[2];
  std::string_view head(reinterpret_cast<char*>(bytes), read_some(f.get(), bytes, 2, path));
  if (has_gzip_magic(head)) return inflate_gzip(f.get(), path, head, max_decompressed, stage);
  return read_plain(f.get(), path, head, stage);
}

}  // namespace dermis
