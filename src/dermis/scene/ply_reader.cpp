#include "dermis/scene/ply_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <sstream>
#include <vector>

#include "dermis/scene/diagnostics.h"
#include "dermis/scene/gzip_file.h"

namespace dermis {

namespace {

enum class Format { Ascii, BinaryLE, BinaryBE };

enum class ScalarType { I8, U8, I16, U16, I32, U32, F32, F64 };

bool parse_scalar_type(const std::string& s, ScalarType& t) {
  if (s == "char" || s == "int8")
    t = ScalarType::I8;
  else if (s == "uchar" || s == "uint8")
    t = ScalarType::U8;
  else if (s == "short" || s == "int16")
    t = ScalarType::I16;
  else if (s == "ushort" || s == "uint16")
    t = ScalarType::U16;
  else if (s == "int" || s == "int32")
    t = ScalarType::I32;
  else if (s == "uint" || s == "uint32")
    t = ScalarType::U32;
  else if (s == "float" || s == "float32")
    t = ScalarType::F32;
  else if (s == "double" || s == "float64")
    t = ScalarType::F64;
  else
    return false;
  return true;
}

size_t type_size(ScalarType t) {
  switch (t) {
    case ScalarType::I8:
    case ScalarType::U8:
      return 1;
    case ScalarType::I16:
    case ScalarType::U16:
      return 2;
    case ScalarType::I32:
    case ScalarType::U32:
    case ScalarType::F32:
      return 4;
    case ScalarType::F64:
      return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  bool is_list = false;
  ScalarType count_type = ScalarType::U8;
  ScalarType type = ScalarType::F32;
};

struct Element {
  std::string name;
  size_t count = 0;
  std::vector<Property> props;
};

// Reads values one at a time from the body of the file, whatever its format.
class BodyReader {
 public:
  // The body is `data` from `start` on.
  BodyReader(std::string data, size_t start, Format format) : data_(std::move(data)), format_(format), pos_(start) {}

  // Bytes of the body not read yet.
  size_t remaining() const { return data_.size() - pos_; }
  double fraction_read() const { return data_.empty() ? 1.0 : double(pos_) / double(data_.size()); }

  // The fewest bytes one value of type `t` takes: its size in binary; in ASCII a digit and
  // a separator (the last value may lack its separator: see fits()).
  size_t min_bytes(ScalarType t) const { return format_ == Format::Ascii ? 2 : type_size(t); }

  // Whether `count` records of `record_bytes` (min_bytes sums) can fit in the bytes left:
  // checked before anything is allocated or looped over, so that a header or a list
  // count cannot claim more than the file holds.
  bool fits(size_t count, size_t record_bytes) const {
    if (count == 0 || record_bytes == 0) return true;
    const size_t room = remaining() + (format_ == Format::Ascii ? 1 : 0);
    return count <= room / record_bytes;
  }

  // A list's length: a non-negative integer whose values fit in the rest of the file.
  size_t read_count(const Property& p, const char* what, size_t which) {
    const double v = read(p.count_type);
    if (!(v >= 0) || v != std::floor(v) || !fits(size_t(std::min(v, 1e18)), min_bytes(p.type)))
      throw std::runtime_error(fmt::format("{} {}: list '{}' claims {} values, more than the {} bytes left in the file",
                                           what, which, p.name, v, remaining()));
    return size_t(v);
  }

  double read(ScalarType t) {
    if (format_ == Format::Ascii) return read_ascii();
    size_t n = type_size(t);
    if (pos_ + n > data_.size()) throw std::runtime_error("the file ends before all elements were read");
    unsigned char b[8];
    std::memcpy(b, data_.data() + pos_, n);
    pos_ += n;
    bool swap = (format_ == Format::BinaryBE) == (std::endian::native == std::endian::little);
    if (swap)
      for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    switch (t) {
      case ScalarType::I8: {
        int8_t v;
        std::memcpy(&v, b, 1);
        return v;
      }
      case ScalarType::U8: {
        uint8_t v;
        std::memcpy(&v, b, 1);
        return v;
      }
      case ScalarType::I16: {
        int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case ScalarType::U16: {
        uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case ScalarType::I32: {
        int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case ScalarType::U32: {
        uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case ScalarType::F32: {
        float v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case ScalarType::F64: {
        double v;
        std::memcpy(&v, b, 8);
        return v;
      }
    }
    return 0;
  }

 private:
  double read_ascii() {
    while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
    if (pos_ >= data_.size()) throw std::runtime_error("the file ends before all elements were read");
    const char* begin = data_.c_str() + pos_;
    char* end = nullptr;
    double v = std::strtod(begin, &end);
    if (end == begin) {
      std::string word;
      for (const char* c = begin; *c && !std::isspace(static_cast<unsigned char>(*c)) && word.size() < 20; ++c)
        word += *c;
      throw std::runtime_error(fmt::format("invalid number '{}' in the body", word));
    }
    pos_ += size_t(end - begin);
    return v;
  }

  std::string data_;
  Format format_;
  size_t pos_;
};

// Refuses an element whose count cannot be backed by the bytes left in the file (every
// record takes at least the minimal size of its properties), before any allocation.
void check_element_fits(const Element& e, const BodyReader& reader) {
  size_t record = 0;
  for (const Property& p : e.props) record += reader.min_bytes(p.is_list ? p.count_type : p.type);
  if (!reader.fits(e.count, record))
    throw std::runtime_error(
        fmt::format("the header declares {} '{}' elements of at least {} bytes each, but only {} "
                    "bytes follow the header: a corrupt or truncated file",
                    e.count, excerpt(e.name), record, reader.remaining()));
}

// The line of `data` that starts at `pos` (without its '\n'); `pos` moves past it. False at the end.
bool next_line(const std::string& data, size_t& pos, std::string& line) {
  if (pos >= data.size()) return false;
  size_t nl = data.find('\n', pos);
  if (nl == std::string::npos) nl = data.size();
  line.assign(data, pos, nl - pos);
  pos = std::min(nl + 1, data.size());
  return true;
}

// Reads the header of `data`; returns where the body starts.
size_t read_header(const std::string& data, Format& format, std::vector<Element>& elements) {
  std::string line;
  size_t pos = 0;
  if (!next_line(data, pos, line) || line.substr(0, 3) != "ply")
    throw std::runtime_error("not a PLY file (no 'ply' magic)");
  bool have_format = false;
  while (next_line(data, pos, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::string kw;
    ls >> kw;
    if (kw == "end_header") {
      if (!have_format) throw std::runtime_error("header has no 'format' line");
      return pos;
    }
    if (kw == "format") {
      std::string f;
      ls >> f;
      if (f == "ascii")
        format = Format::Ascii;
      else if (f == "binary_little_endian")
        format = Format::BinaryLE;
      else if (f == "binary_big_endian")
        format = Format::BinaryBE;
      else
        throw std::runtime_error(fmt::format("unknown PLY format '{}'", excerpt(f)));
      have_format = true;
    } else if (kw == "element") {
      Element e;
      long long count = -1;
      ls >> e.name >> count;
      if (!ls || e.name.empty() || count < 0)
        throw std::runtime_error(fmt::format("malformed header line '{}'", excerpt(line)));
      e.count = size_t(count);
      elements.push_back(e);
    } else if (kw == "property") {
      if (elements.empty()) throw std::runtime_error("'property' before any 'element' in the header");
      Property p;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> p.name;
        p.is_list = true;
        if (!parse_scalar_type(ct, p.count_type) || !parse_scalar_type(it, p.type))
          throw std::runtime_error(fmt::format("unsupported property types in '{}'", excerpt(line)));
      } else {
        ls >> p.name;
        if (!parse_scalar_type(t, p.type))
          throw std::runtime_error(fmt::format("unsupported property type '{}'", excerpt(t)));
      }
      elements.back().props.push_back(p);
    }
    // comment, obj_info and unknown lines are ignored
  }
  throw std::runtime_error("header has no 'end_header'");
}

uint32_t checked_index(double v, size_t nverts, const char* what, size_t which) {
  if (v < 0 || v >= double(nverts) || v != std::floor(v))
    throw std::runtime_error(
        fmt::format("{} {} references vertex {} but the file has {} vertices", what, which, v, nverts));
  return uint32_t(v);
}

}  // namespace

TriangleMeshDesc read_ply(const std::string& path, const LoadMonitor* monitor) {
  const std::string name = std::filesystem::path(path).filename().string();
  std::string data;
  {
    LoadStage loading(monitor, "loading " + name);
    data = read_file_contents(path, kMaxDecompressedBytes, &loading);
    loading.finish();
  }
  LoadStage reading(monitor, "reading " + name);
  // Progress and the cancel flag every this many vertices or faces.
  constexpr size_t kCheckEvery = size_t(1) << 14;
  Format format = Format::Ascii;
  std::vector<Element> elements;
  size_t body = read_header(data, format, elements);
  BodyReader reader(std::move(data), body, format);

  TriangleMeshDesc mesh;
  size_t nverts = 0;
  bool have_vertices = false;
  for (const Element& e : elements) {
    check_element_fits(e, reader);
    // An element with no properties takes no bytes: nothing to read, however many it claims.
    if (e.props.empty() && e.name != "vertex") continue;
    if (e.name == "vertex") {
      if (have_vertices) throw std::runtime_error("the header declares two 'vertex' elements");
      if (e.count > std::numeric_limits<uint32_t>::max())
        throw std::runtime_error(fmt::format("{} vertices: more than 32-bit indices can address", e.count));
      have_vertices = true;
      nverts = e.count;
      int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, iu = -1, iv = -1;
      for (int i = 0; i < int(e.props.size()); ++i) {
        const std::string& n = e.props[i].name;
        if (e.props[i].is_list) continue;
        if (n == "x")
          ix = i;
        else if (n == "y")
          iy = i;
        else if (n == "z")
          iz = i;
        else if (n == "nx")
          inx = i;
        else if (n == "ny")
          iny = i;
        else if (n == "nz")
          inz = i;
        else if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s")
          iu = i;
        else if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t")
          iv = i;
      }
      if (ix < 0 || iy < 0 || iz < 0) throw std::runtime_error("vertex element lacks x, y or z");
      bool normals = inx >= 0 && iny >= 0 && inz >= 0, uvs = iu >= 0 && iv >= 0;
      mesh.positions.resize(e.count);
      if (normals) mesh.normals.resize(e.count);
      if (uvs) mesh.uvs.resize(e.count);
      std::vector<double> vals(e.props.size());
      for (size_t k = 0; k < e.count; ++k) {
        if (k % kCheckEvery == 0) reading.update(reader.fraction_read());
        for (size_t i = 0; i < e.props.size(); ++i) {
          const Property& p = e.props[i];
          if (p.is_list) {
            size_t n = reader.read_count(p, "vertex", k);
            for (size_t j = 0; j < n; ++j) reader.read(p.type);
          } else {
            vals[i] = reader.read(p.type);
          }
        }
        const Vec3 pos{float(vals[ix]), float(vals[iy]), float(vals[iz])};  // braces: not a vexing parse
        if (!std::isfinite(pos.x) || !std::isfinite(pos.y) || !std::isfinite(pos.z))
          throw std::runtime_error(fmt::format("vertex {} has a non-finite coordinate", k));
        mesh.positions[k] = pos;
        if (normals) mesh.normals[k] = Vec3(float(vals[inx]), float(vals[iny]), float(vals[inz]));
        if (uvs) mesh.uvs[k] = Vec2(float(vals[iu]), float(vals[iv]));
      }
    } else if (e.name == "face" || e.name == "tristrips") {
      if (!have_vertices) throw std::runtime_error(fmt::format("element '{}' comes before the vertices", e.name));
      bool strips = e.name == "tristrips";
      std::vector<uint32_t> poly;
      for (size_t k = 0; k < e.count; ++k) {
        if (k % kCheckEvery == 0) reading.update(reader.fraction_read());
        for (const Property& p : e.props) {
          if (!p.is_list) {
            reader.read(p.type);
            continue;
          }
          size_t n = reader.read_count(p, e.name.c_str(), k);
          bool wanted = p.name == "vertex_indices" || p.name == "vertex_index";
          poly.clear();
          if (!wanted) {
            for (size_t j = 0; j < n; ++j) reader.read(p.type);
            continue;
          }
          if (!strips) {
            for (size_t j = 0; j < n; ++j) poly.push_back(checked_index(reader.read(p.type), nverts, "face", k));
            if (n < 3) throw std::runtime_error(fmt::format("face {} has only {} vertices", k, n));
            for (size_t j = 1; j + 1 < n; ++j) mesh.indices.insert(mesh.indices.end(), {poly[0], poly[j], poly[j + 1]});
            continue;
          }
          // Triangle strip with -1 restarts.
          auto flush = [&mesh](const std::vector<uint32_t>& s) {
            for (size_t j = 0; j + 2 < s.size(); ++j) {
              uint32_t a = s[j], b = s[j + 1], c = s[j + 2];
              if (a == b || b == c || a == c) continue;
              if (j % 2 == 1) std::swap(a, b);
              mesh.indices.insert(mesh.indices.end(), {a, b, c});
            }
          };
          for (size_t j = 0; j < n; ++j) {
            double v = reader.read(p.type);
            if (v == -1) {
              flush(poly);
              poly.clear();
            } else {
              poly.push_back(checked_index(v, nverts, "triangle strip", k));
            }
          }
          flush(poly);
        }
      }
    } else {
      for (size_t k = 0; k < e.count; ++k)
        for (const Property& p : e.props) {
          size_t n = p.is_list ? reader.read_count(p, "element", k) : 1;
          for (size_t j = 0; j < n; ++j) reader.read(p.type);
        }
    }
  }
  if (!have_vertices) throw std::runtime_error("the file has no vertex element");
  if (mesh.indices.empty()) throw std::runtime_error("the file has no faces or triangle strips");
  reading.finish();
  return mesh;
}

}  // namespace dermis
