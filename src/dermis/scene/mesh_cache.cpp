#include "dermis/scene/mesh_cache.h"

#include <fmt/format.h>
#include <zlib.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>
#include <type_traits>

#include "dermis/source_hashes.h"  // generated (cmake/source_hashes.cmake)

namespace dermis {

namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'D', 'R', 'M', 'S', 'M', 'E', 'S', 'H'};
// 2: the importer's code hash follows the version.
constexpr uint32_t kFormatVersion = 2;

static_assert(sizeof(Vec3) == 3 * sizeof(float) && std::is_trivially_copyable_v<Vec3>);
static_assert(sizeof(Vec2) == 2 * sizeof(float) && std::is_trivially_copyable_v<Vec2>);

uint32_t crc_of(const char* data, std::size_t n, uint32_t crc = 0) {
  while (n > 0) {  // zlib takes uInt lengths
    const uInt chunk = uInt(std::min<std::size_t>(n, 1u << 30));
    crc = uint32_t(crc32(crc, reinterpret_cast<const Bytef*>(data), chunk));
    data += chunk, n -= chunk;
  }
  return crc;
}

// What identifies the source file's contents: its size, modification time and CRC-32.
struct SourceState {
  std::string path;  // canonical
  uint64_t size = 0;
  int64_t mtime = 0;
  uint32_t crc = 0;
};

// The file's path, size and time (crc left 0): cheap, for the first comparison.
std::optional<SourceState> source_stat(const std::string& path) {
  std::error_code ec;
  SourceState s;
  s.path = fs::canonical(path, ec).string();
  if (ec) return std::nullopt;
  const auto size = fs::file_size(s.path, ec);
  if (ec) return std::nullopt;
  const auto mtime = fs::last_write_time(s.path, ec);
  if (ec) return std::nullopt;
  s.size = uint64_t(size);
  s.mtime = int64_t(mtime.time_since_epoch().count());
  return s;
}

// The CRC-32 of the file's bytes, reported to `stage` (if any) as fractions up to `upto`
// (throws Interrupted when cancelled); false when the file cannot be read whole.
bool add_crc(SourceState& s, LoadStage* stage, double upto) {
  std::ifstream in(s.path, std::ios::binary);
  if (!in) return false;
  std::vector<char> buffer(1 << 20);
  uint64_t read = 0;
  s.crc = 0;
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    const std::size_t got = std::size_t(in.gcount());
    s.crc = crc_of(buffer.data(), got, s.crc);
    read += got;
    if (stage && s.size > 0) stage->update(upto * double(read) / double(s.size));
  }
  return read == s.size;  // else the file changed while it was read
}

std::optional<SourceState> source_state(const std::string& path) {
  std::optional<SourceState> s = source_stat(path);
  if (!s || !add_crc(*s, nullptr, 0)) return std::nullopt;
  return s;
}

void put_bytes(std::string& out, const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); }
template <class T>
void put(std::string& out, const T& v) {
  put_bytes(out, &v, sizeof v);
}
void put_string(std::string& out, const std::string& s) {
  put(out, uint32_t(s.size()));
  out += s;
}
template <class T>
void put_array(std::string& out, const std::vector<T>& v) {
  put(out, uint64_t(v.size()));
  put_bytes(out, v.data(), v.size() * sizeof(T));
}

// Reads from a byte buffer; any read past its end sets `bad` and yields zeros.
struct Reader {
  const std::string& data;
  std::size_t at = 0;
  bool bad = false;
  bool take(void* p, std::size_t n) {
    if (bad || n > data.size() - at) return !(bad = true);
    std::memcpy(p, data.data() + at, n);
    at += n;
    return true;
  }
  template <class T>
  T get() {
    T v{};
    take(&v, sizeof v);
    return v;
  }
  std::string get_string() {
    const uint32_t n = get<uint32_t>();
    if (bad || n > data.size() - at) return bad = true, std::string();
    std::string s = data.substr(at, n);
    at += n;
    return s;
  }
  template <class T>
  void get_array(std::vector<T>& v) {
    const uint64_t n = get<uint64_t>();
    if (bad || n > (data.size() - at) / sizeof(T)) {
      bad = true;
      return;
    }
    v.resize(std::size_t(n));
    take(v.data(), std::size_t(n) * sizeof(T));
  }
};

// The header without the content's CRC (which follows it).
std::string stat_header(const SourceState& s) {
  std::string out(kMagic, sizeof kMagic);
  put(out, kFormatVersion);
  put_string(out, source_hash::kMeshImport);  // the code that imported it: another build's import is not read
  put_string(out, s.path);
  put(out, s.size);
  put(out, s.mtime);
  return out;
}
std::string header(const SourceState& s) {
  std::string out = stat_header(s);
  put(out, s.crc);
  return out;
}

}  // namespace

std::string mesh_cache_path(const std::string& cache_dir, const std::string& canonical_path) {
  return fmt::format("{}/mesh-v{}-{:08x}.bin", cache_dir, kFormatVersion,
                     crc_of(canonical_path.data(), canonical_path.size()));
}

namespace {

// The cached mesh of the file whose path, size and time are `source`'s: its content's CRC
// is computed only when the cache's header matches those (a likely hit), and then under
// the stage "reading NAME" with the monitor (so that a hit reports and obeys Ctrl-C as
// the import does; a miss reports nothing, and the import's own stage follows).
std::optional<ImportedMesh> load(const std::string& cache_dir, SourceState source, const LoadMonitor* monitor,
                                 bool with_stage) {
  std::ifstream in(mesh_cache_path(cache_dir, source.path), std::ios::binary);
  if (!in) return std::nullopt;
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The whole file's CRC first: a truncated or damaged cache is a miss.
  if (data.size() < sizeof(uint32_t)) return std::nullopt;
  uint32_t stored_crc;
  std::memcpy(&stored_crc, data.data() + data.size() - sizeof stored_crc, sizeof stored_crc);
  if (crc_of(data.data(), data.size() - sizeof stored_crc) != stored_crc) return std::nullopt;
  const std::string expected = stat_header(source);
  if (data.compare(0, expected.size(), expected) != 0) return std::nullopt;  // another file, or it changed
  std::optional<LoadStage> stage;
  if (with_stage) stage.emplace(monitor, "reading " + fs::path(source.path).filename().string());
  if (!add_crc(source, stage ? &*stage : nullptr, 0.9)) return std::nullopt;
  Reader r{data, expected.size()};
  if (r.get<uint32_t>() != source.crc) return std::nullopt;  // edited, size and time kept
  ImportedMesh m;
  r.get_array(m.mesh.positions);
  r.get_array(m.mesh.normals);
  r.get_array(m.mesh.uvs);
  r.get_array(m.mesh.indices);
  const uint32_t notes = r.get<uint32_t>();
  for (uint32_t i = 0; i < notes && !r.bad; ++i) m.notes.push_back(r.get_string());
  if (r.bad || r.at != data.size() - sizeof stored_crc) return std::nullopt;
  try {
    validate_mesh(m.mesh);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (stage) stage->finish();
  return m;
}

// Removes the cache files of meshes whose source file is gone (renders of temporary
// files would otherwise fill the directory), and unreadable ones; keeps `keep`.
void prune(const std::string& cache_dir, const std::string& keep) {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(cache_dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("mesh-", 0) != 0 || e.path().extension() != ".bin" || e.path().string() == keep) continue;
    std::string head(4096, '\0');
    {
      std::ifstream in(e.path(), std::ios::binary);
      in.read(head.data(), std::streamsize(head.size()));
      head.resize(std::size_t(in.gcount()));
    }
    Reader r{head, sizeof kMagic};
    const bool ours = head.compare(0, sizeof kMagic, std::string(kMagic, sizeof kMagic)) == 0;
    if (r.get<uint32_t>() >= 2) r.get_string();  // the format's version (any) and, from 2 on, the code hash
    const std::string source = r.get_string();
    std::error_code exists_ec;
    if (!ours || r.bad || !fs::exists(source, exists_ec)) fs::remove(e.path(), ec);
  }
}

bool save(const std::string& cache_dir, const SourceState& source, const ImportedMesh& mesh) {
  std::string out = header(source);
  put_array(out, mesh.mesh.positions);
  put_array(out, mesh.mesh.normals);
  put_array(out, mesh.mesh.uvs);
  put_array(out, mesh.mesh.indices);
  put(out, uint32_t(mesh.notes.size()));
  for (const std::string& note : mesh.notes) put_string(out, note);
  put(out, crc_of(out.data(), out.size()));
  std::error_code ec;
  fs::create_directories(cache_dir, ec);
  const std::string target = mesh_cache_path(cache_dir, source.path);
  // A temporary file renamed over the target: a reader never sees half a cache file.
  const std::string tmp =
      target + fmt::format(".tmp{}", uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()));
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) return false;
    f.write(out.data(), std::streamsize(out.size()));
    if (!f) {
      f.close();
      fs::remove(tmp, ec);
      return false;
    }
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return false;
  }
  prune(cache_dir, target);
  return true;
}

}  // namespace

std::optional<ImportedMesh> load_cached_mesh(const std::string& cache_dir, const std::string& path) {
  if (cache_dir.empty()) return std::nullopt;
  const std::optional<SourceState> source = source_stat(path);
  return source ? load(cache_dir, *source, nullptr, false) : std::nullopt;
}

bool save_cached_mesh(const std::string& cache_dir, const std::string& path, const ImportedMesh& mesh) {
  if (cache_dir.empty()) return false;
  const std::optional<SourceState> source = source_state(path);
  return source && save(cache_dir, *source, mesh);
}

ImportedMesh import_mesh_cached(const std::string& path, const LoadMonitor* monitor, const std::string& cache_dir,
                                double min_import_seconds) {
  const std::optional<SourceState> stat = cache_dir.empty() ? std::nullopt : source_stat(path);
  if (stat)
    if (std::optional<ImportedMesh> cached = load(cache_dir, *stat, monitor, true)) return std::move(*cached);
  const std::optional<SourceState> before = stat ? source_state(path) : std::nullopt;
  const auto start = std::chrono::steady_clock::now();
  ImportedMesh m = import_mesh_assimp(path, monitor);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Cached if the import was slow enough to be worth a file, and the file is still what
  // it was before the import began.
  if (before && seconds >= min_import_seconds) {
    const std::optional<SourceState> after = source_state(path);
    if (after && header(*after) == header(*before)) save(cache_dir, *before, m);
  }
  return m;
}

}  // namespace dermis
