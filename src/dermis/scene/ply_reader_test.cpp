// The PLY reader on hostile files: headers that claim more than the file holds, elements
// with no properties, lying list counts, truncated binary data in both endiannesses.
#include "dermis/scene/ply_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <ctime>
#include <string>

#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

using test::TempDir;

// The message of the runtime_error read_ply throws for `contents` ("" when it succeeds).
std::string ply_error(const TempDir& dir, const std::string& contents) {
  try {
    read_ply(dir.write("m.ply", contents));
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

template <class T>
std::string bytes_of(T v, bool big_endian) {
  std::string b(sizeof(T), '\0');
  std::memcpy(b.data(), &v, sizeof(T));
  if (big_endian) std::reverse(b.begin(), b.end());
  return b;
}

const char* kTriangleAscii =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

TEST(PlyReaderHostile, AValidTriangleStillReads) {
  TempDir dir;
  TriangleMeshDesc m = read_ply(dir.write("m.ply", kTriangleAscii));
  EXPECT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.indices.size(), 3u);
}

TEST(PlyReaderHostile, VertexCountBeyondTheFileIsRefusedBeforeAllocating) {
  TempDir dir;
  // 200 million vertices of 12 bytes in a file of about 100 bytes (used to take 2.4 GB).
  std::string err = ply_error(dir,
                              "ply\nformat binary_little_endian 1.0\nelement vertex 200000000\nproperty float x\n"
                              "property float y\nproperty float z\nend_header\n" +
                                  std::string(12, '\0'));
  EXPECT_NE(err.find("200000000 'vertex' elements of at least 12 bytes"), std::string::npos) << err;
  err = ply_error(dir,
                  "ply\nformat ascii 1.0\nelement vertex 9223372036854775807\nproperty float x\nproperty float y\n"
                  "property float z\nend_header\n0 0 0\n");
  EXPECT_NE(err.find("bytes follow the header"), std::string::npos) << err;
}

TEST(PlyReaderHostile, ElementsWithNoPropertiesDoNotSpin) {
  TempDir dir;
  // 2^63 - 1 faces with no properties: nothing to read (used to loop forever).
  // Bounded in this process's CPU time, not wall time: a loaded machine does not fail it, a spin does.
  const std::clock_t start = std::clock();
  std::string err = ply_error(dir,
                              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                              "property float z\nelement face 9223372036854775807\nelement junk 9223372036854775807\n"
                              "end_header\n0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_LT(double(std::clock() - start) / CLOCKS_PER_SEC, 2.0);
  EXPECT_NE(err.find("no faces"), std::string::npos) << err;
}

TEST(PlyReaderHostile, ListCountsAreCheckedAgainstTheFile) {
  TempDir dir;
  const std::string head =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list int int vertex_indices\nend_header\n";
  const std::string verts(36, '\0');
  std::string err = ply_error(dir, head + verts + bytes_of<int32_t>(1000000000, false) + bytes_of<int32_t>(0, false));
  EXPECT_NE(err.find("claims 1000000000 values"), std::string::npos) << err;
  // A negative count (int8 -1) is an error, not a conversion of -1.0 to size_t.
  err = ply_error(dir,
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\nelement face 1\nproperty list char int vertex_indices\nend_header\n"
                  "0 0 0\n1 0 0\n0 1 0\n-1 0 1 2\n");
  EXPECT_NE(err.find("claims -1 values"), std::string::npos) << err;
  err = ply_error(dir,
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\nelement face 1\nproperty list float int vertex_indices\nend_header\n"
                  "0 0 0\n1 0 0\n0 1 0\nnan 0 1 2\n");
  EXPECT_NE(err.find("claims nan values"), std::string::npos) << err;
}

TEST(PlyReaderHostile, TruncatedBinaryDataInBothEndiannesses) {
  TempDir dir;
  for (bool big : {false, true}) {
    const std::string head = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                             " 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    std::string body;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) body += bytes_of(v, big);
    std::string face =
        std::string(1, '\3') + bytes_of<int32_t>(0, big) + bytes_of<int32_t>(1, big) + bytes_of<int32_t>(2, big);
    TriangleMeshDesc m = read_ply(dir.write("m.ply", head + body + face));
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.positions[1], Vec3(1, 0, 0)) << (big ? "big" : "little") << " endian";
    // Cut inside the face's indices: the list claims more than is left; cut inside a value: the file ends.
    std::string err = ply_error(dir, head + body + face.substr(0, face.size() - 2));
    EXPECT_NE(err.find("claims 3 values, more than the 10 bytes left"), std::string::npos) << err;
    err = ply_error(dir, head + body.substr(0, body.size() - 2));
    EXPECT_NE(err.find("bytes follow the header"), std::string::npos) << err;
  }
}

TEST(PlyReaderHostile, MalformedHeaders) {
  TempDir dir;
  EXPECT_NE(ply_error(dir, "ply\nformat ascii 1.0\nelement vertex many\nend_header\n").find("malformed header"),
            std::string::npos);
  EXPECT_NE(ply_error(dir,
                      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                      "property float z\nelement vertex 1\nproperty float x\nproperty float y\n"
                      "property float z\nend_header\n0 0 0\n0 0 0\n")
                .find("two 'vertex' elements"),
            std::string::npos);
  EXPECT_NE(ply_error(dir, "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n")
                .find("unsupported property type 'quad'"),
            std::string::npos);
  // 2^63 vertices with no properties: refused at once, not allocated.
  EXPECT_NE(
      ply_error(dir, "ply\nformat ascii 1.0\nelement vertex 9223372036854775807\nend_header\n").find("32-bit indices"),
      std::string::npos);
}

}  // namespace
}  // namespace dermis
