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

constexpr size_t kInputChunk = size_t(1) << 18;   // file bytes read at a time
constexpr size_t kOutputChunk = size_t(1) << 20;  // inflated bytes handed out at a time
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

// The uncompressed size the last member's trailer states (RFC 1952 ISIZE, modulo 2^32), if
// plausible for the compressed size; only used to size an output buffer.
// The file position is restored.
uint64_t gzip_size_hint(std::FILE* f, uint64_t compressed, uint64_t limit) {
  long at = std::ftell(f);
  unsigned char t[4];
  bool ok = at >= 0 && compressed >= 18 && std::fseek(f, -4, SEEK_END) == 0 && std::fread(t, 1, 4, f) == 4;
  if (at < 0 || std::fseek(f, at, SEEK_SET) != 0) ok = false;
  std::clearerr(f);
  if (!ok) return 0;
  uint64_t isize = uint64_t(t[0]) | uint64_t(t[1]) << 8 | uint64_t(t[2]) << 16 | uint64_t(t[3]) << 24;
  return std::min({isize, compressed * kMaxDeflateRatio, limit});
}

}  // namespace

struct FileChunks::Impl {
  std::string path;
  File file;
  uint64_t size = 0, consumed = 0, limit = 0, hint = 0;
  std::vector<unsigned char> in = std::vector<unsigned char>(kInputChunk);
  // gzip only:
  bool gzip = false;
  z_stream zs{};
  bool zs_ready = false, eof = false, between_members = false, done = false;
  uint64_t produced = 0;
  std::vector<char> out;

  ~Impl() {
    if (zs_ready) inflateEnd(&zs);
  }

  std::string_view next_plain() {
    const size_t got = read_some(file.get(), in.data(), in.size(), path);
    consumed += got;
    return {reinterpret_cast<const char*>(in.data()), got};
  }

  FileReadError corrupt(const char* why) const {
    return FileReadError(path, fmt::format("gzip data is corrupt/truncated (zlib: {})", why));
  }

  std::string_view next_gzip() {
    while (!done) {
      if (zs.avail_in == 0 && !eof) {
        const size_t got = read_some(file.get(), in.data(), in.size(), path);
        consumed += got;
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
          done = eof;
          continue;
        }
        if (inflateReset(&zs) != Z_OK) throw corrupt("inflateReset failed");
        between_members = false;
      }
      zs.next_out = reinterpret_cast<Bytef*>(out.data());
      zs.avail_out = uInt(out.size());
      const int rc = inflate(&zs, Z_NO_FLUSH);
      const size_t n = out.size() - zs.avail_out;
      produced += n;
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
      if (n > 0) return {out.data(), n};
    }
    return {};
  }
};

FileChunks::FileChunks(const std::string& path, uint64_t max_decompressed) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.path = path;
  m.limit = max_decompressed;
  // Only regular files: a FIFO would block in fopen, a device such as /dev/zero never ends.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec) throw FileReadError(path, ec.message());
  if (std::filesystem::is_directory(status)) throw FileReadError(path, "it is a directory");
  if (!std::filesystem::is_regular_file(status))
    throw FileReadError(path, "it is not a regular file (a device, FIFO or socket); only files are read");
  m.file.reset(std::fopen(path.c_str(), "rb"));
  if (!m.file) throw FileReadError(path, std::strerror(errno));
  m.size = file_size(path);
  unsigned char magic[2];
  const size_t got = read_some(m.file.get(), magic, 2, path);
  m.gzip = has_gzip_magic({reinterpret_cast<char*>(magic), got});
  if (std::fseek(m.file.get(), 0, SEEK_SET) != 0) throw FileReadError(path, std::strerror(errno));
  m.hint = m.size;
  if (!m.gzip) return;
  m.hint = gzip_size_hint(m.file.get(), m.size, m.limit);
  // 16 + MAX_WBITS: a gzip wrapper (not zlib's own), the largest window.
  if (inflateInit2(&m.zs, 16 + MAX_WBITS) != Z_OK) throw FileReadError(path, "zlib could not be initialised");
  m.zs_ready = true;
  m.out.resize(kOutputChunk);
}

FileChunks::~FileChunks() = default;

std::string_view FileChunks::next() { return impl_->gzip ? impl_->next_gzip() : impl_->next_plain(); }

double FileChunks::fraction_read() const {
  return impl_->size > 0 ? std::min(1.0, double(impl_->consumed) / double(impl_->size)) : 1.0;
}

uint64_t FileChunks::size_hint() const { return impl_->hint; }

// RFC 1952, section 2.3.1: every gzip member starts with ID1 = 0x1f, ID2 = 0x8b.
bool has_gzip_magic(std::string_view head) {
  return head.size() >= 2 && static_cast<unsigned char>(head[0]) == 0x1f && static_cast<unsigned char>(head[1]) == 0x8b;
}

FileReadError::FileReadError(const std::string& path, const std::string& reason)
    : std::runtime_error(fmt::format("{}: {}", path, reason)), path_(path), reason_(reason) {}

std::string read_file_contents(const std::string& path, uint64_t max_decompressed, LoadStage* stage) {
  FileChunks chunks(path, max_decompressed);
  std::string out;
  out.reserve(size_t(chunks.size_hint()));
  while (true) {
    const std::string_view chunk = chunks.next();
    if (chunk.empty()) break;
    out.append(chunk);
    if (stage) stage->update(chunks.fraction_read());
  }
  return out;
}

}  // namespace dermis
