// Helpers shared by the scene parser tests (header only; not part of the library).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "dermis/core/transform.h"
#include "dermis/scene/parser.h"

namespace dermis::test {

// A fresh directory under the system temp dir, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("dermis_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string path() const { return path_.string(); }
  std::string write(const std::string& name, const std::string& contents) const {
    std::filesystem::path p = path_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << contents;
    return p.string();
  }

 private:
  std::filesystem::path path_;
};

// `data` as one gzip member (RFC 1952), compressed with zlib at `level`.
inline std::string gzip(const std::string& data, int level = Z_BEST_COMPRESSION) {
  z_stream zs{};
  // 16 + MAX_WBITS: write a gzip header and trailer rather than zlib's own.
  if (deflateInit2(&zs, level, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    ADD_FAILURE() << "deflateInit2 failed";
    return {};
  }
  std::string out(deflateBound(&zs, uLong(data.size())) + 64, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = uInt(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = uInt(out.size());
  int rc = deflate(&zs, Z_FINISH);
  EXPECT_EQ(rc, Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

inline SceneDesc parse_world(const std::string& body, const std::string& dir = ".") {
  return parse_scene_string("WorldBegin\n" + body, "test.pbrt", dir);
}

inline SceneDesc parse_text(const std::string& text) { return parse_scene_string(text, "test.pbrt"); }

inline void expect_matrix_near(const Mat4& a, const Mat4& b, double tol = 1e-12) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(a.m[i][j], b.m[i][j], tol) << "entry [" << i << "][" << j << "]";
}

inline Mat4 rows(std::initializer_list<double> v) {
  Mat4 m;
  int k = 0;
  for (double x : v) {
    m.m[k / 4][k % 4] = x;
    ++k;
  }
  return m;
}

inline bool has_warning(const SceneDesc& s, const std::string& needle) {
  for (const std::string& w : s.diagnostics.warnings)
    if (w.find(needle) != std::string::npos) return true;
  for (const std::string& w : s.diagnostics.warnings) std::cerr << "  (warning present: " << w << ")\n";
  return false;
}

}  // namespace dermis::test
