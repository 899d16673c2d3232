#include "dermis/render/exr_header_check.h"

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <fstream>

namespace dermis {

namespace {

constexpr uint32_t kMagic = 20000630;    // 76 2f 31 01, little-endian
constexpr uint32_t kMultiPart = 0x1000;  // version flag: several headers
constexpr uint32_t kLongNames = 0x400;   // names up to 255 bytes instead of 31
constexpr int kMaxAttributes = 1 << 16;  // far beyond any real header

uint32_t le32(const unsigned char* b) { return b[0] | (b[1] << 8) | (b[2] << 16) | (uint32_t(b[3]) << 24); }

}  // namespace

std::string exr_header_problem(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";  // OpenImageIO reports what it cannot open
  std::error_code ec;
  const std::uintmax_t file_bytes = std::filesystem::file_size(path, ec);
  if (ec) return "";
  unsigned char head[8];
  if (!in.read(reinterpret_cast<char*>(head), 8) || le32(head) != kMagic) return "";
  const uint32_t flags = le32(head + 4) & ~0xffu;
  const std::size_t max_name = (flags & kLongNames) ? 255 : 31;
  std::uintmax_t pos = 8;
  // A null-terminated name of at most max_name bytes; "" at the end of a header.
  auto read_name = [&](std::string& s, std::string& problem) {
    s.clear();
    for (;;) {
      const int c = in.get();
      if (c == EOF) {
        problem = "the header ends inside a name";
        return false;
      }
      ++pos;
      if (c == 0) return true;
      if (s.size() == max_name) {
        problem = fmt::format("a name in the header is longer than {} bytes", max_name);
        return false;
      }
      s.push_back(char(c));
    }
  };
  const bool multi_part = flags & kMultiPart;
  std::string name, type, problem;
  for (int part = 0;; ++part) {
    int attributes = 0;
    for (;; ++attributes) {
      if (!read_name(name, problem)) return problem;
      if (name.empty()) break;  // end of this header
      if (attributes == kMaxAttributes) return fmt::format("the header has more than {} attributes", kMaxAttributes);
      if (!read_name(type, problem)) return problem;
      unsigned char size_bytes[4];
      if (!in.read(reinterpret_cast<char*>(size_bytes), 4)) return "the header ends inside an attribute's size";
      pos += 4;
      const int32_t size = int32_t(le32(size_bytes));
      if (size < 0) return fmt::format("attribute \"{}\" claims a negative size ({})", name, size);
      if (std::uintmax_t(size) > file_bytes - pos)
        return fmt::format(
            "attribute \"{}\" ({}) claims {} bytes but the file holds only {} more: a corrupt or "
            "truncated file",
            name, type, size, file_bytes - pos);
      in.seekg(size, std::ios::cur);
      pos += std::uintmax_t(size);
    }
    // Single-part: one header. Multi-part: headers until an empty one (its first byte 0).
    if (!multi_part || attributes == 0) return "";
  }
}

}  // namespace dermis
