#include "dermis/sss/profiles/profile_table_io.h"

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <ostream>
#include <vector>

namespace dermis::sss {

namespace {

constexpr char kMagic[8] = {'D', 'R', 'M', 'S', 'P', 'T', 'B', 'L'};
// No table this library builds comes near these; a larger count is a damaged file.
constexpr uint64_t kMaxEntries = uint64_t(1) << 28;

template <class T>
void put(std::ostream& out, const T& v) {
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
bool get(std::istream& in, T& v) {
  return bool(in.read(reinterpret_cast<char*>(&v), sizeof v));
}
void put_vector(std::ostream& out, const std::vector<double>& v) {
  put(out, uint64_t(v.size()));
  out.write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(double)));
}
bool get_vector(std::istream& in, std::vector<double>& v) {
  uint64_t n = 0;
  if (!get(in, n) || n > kMaxEntries) return false;
  v.resize(n);
  if (!in.read(reinterpret_cast<char*>(v.data()), std::streamsize(n * sizeof(double)))) return false;
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

bool write_profile_table(std::ostream& out, const std::string& key, const ProfileTable& t) {
  out.write(kMagic, sizeof kMagic);
  put(out, kProfileTableFileVersion);
  put(out, uint64_t(key.size()));
  out.write(key.data(), std::streamsize(key.size()));
  put(out, int32_t(t.n_));
  for (double v : {t.x_min_, t.x_max_, t.log_x_min_, t.log_step_}) put(out, v);
  for (const std::vector<double>* v :
       {&t.albedos_, &t.x_, &t.log_scale_, &t.energy_, &t.source_energy_, &t.log_shape_, &t.cdf_})
    put_vector(out, *v);
  return bool(out);
}

std::shared_ptr<const ProfileTable> read_profile_table(std::istream& in, const std::string& key) {
  char magic[sizeof kMagic];
  uint32_t version = 0;
  uint64_t key_size = 0;
  if (!in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0) return nullptr;
  if (!get(in, version) || version != kProfileTableFileVersion) return nullptr;
  if (!get(in, key_size) || key_size != key.size()) return nullptr;
  std::string stored(key_size, '\0');
  if (!in.read(stored.data(), std::streamsize(key_size)) || stored != key) return nullptr;
  std::shared_ptr<ProfileTable> t(new ProfileTable());
  int32_t n = 0;
  if (!get(in, n) || n < 8) return nullptr;
  t->n_ = n;
  for (double* v : {&t->x_min_, &t->x_max_, &t->log_x_min_, &t->log_step_})
    if (!get(in, *v) || !std::isfinite(*v)) return nullptr;
  for (std::vector<double>* v :
       {&t->albedos_, &t->x_, &t->log_scale_, &t->energy_, &t->source_energy_, &t->log_shape_, &t->cdf_})
    if (!get_vector(in, *v)) return nullptr;
  if (in.peek() != std::char_traits<char>::eof()) return nullptr;  // trailing bytes: not this format
  // The sizes the table's own constructor gives them (tabulated.cpp).
  const std::size_t nodes = t->albedos_.size(), radial = std::size_t(n);
  if (nodes < 2 || t->x_.size() != radial + 1 || t->log_scale_.size() != nodes || t->energy_.size() != nodes ||
      t->source_energy_.size() != nodes || t->log_shape_.size() != nodes * radial ||
      t->cdf_.size() != nodes * (radial + 1) || !(t->x_min_ > 0 && t->x_max_ > t->x_min_))
    return nullptr;
  return t;
}

std::shared_ptr<const ProfileTable> cached_profile_table(const std::string& dir, const std::string& key,
                                                         const std::function<ProfileTable()>& build) {
  const std::filesystem::path path = std::filesystem::path(dir) / key;
  if (!dir.empty()) {
    std::ifstream in(path, std::ios::binary);
    if (in)
      if (auto table = read_profile_table(in, key)) return table;
  }
  auto table = std::make_shared<const ProfileTable>(build());
  if (dir.empty()) return table;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::filesystem::path tmp = path.string() + ".tmp" + std::to_string(::getpid());
  bool written;
  {
    std::ofstream out(tmp, std::ios::binary);
    written = out && write_profile_table(out, key, *table);
  }
  if (written) std::filesystem::rename(tmp, path, ec);
  if (!written || ec) std::filesystem::remove(tmp, ec);
  return table;
}

}  // namespace dermis::sss
