// read_file_contents: plain files as they are, gzip (by its magic) inflated; corrupt,
// truncated and oversized gzip data reported with the file's name.
#include "dermis/scene/gzip_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <string>

#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

using test::gzip;

// Text that compresses, but not to nothing: lines with varying numbers.
std::string sample_text(int lines = 400) {
  std::string s;
  uint32_t x = 12345;
  for (int i = 0; i < lines; ++i) {
    x = x * 1664525u + 1013904223u;
    s += "Shape \"sphere\" \"float radius\" " + std::to_string(x % 1000) + "\n";
  }
  return s;
}

// The FileReadError read_file_contents throws for `path`, or a failure.
std::string read_error(const std::string& path, uint64_t limit = kMaxDecompressedBytes) {
  try {
    read_file_contents(path, limit);
  } catch (const FileReadError& e) {
    EXPECT_EQ(e.path(), path);
    EXPECT_EQ(std::string(e.what()), path + ": " + e.reason());
    return e.what();
  }
  ADD_FAILURE() << "no FileReadError for " << path;
  return {};
}

TEST(GzipFile, MagicIsTheRfc1952Id) {
  EXPECT_TRUE(has_gzip_magic("\x1f\x8b"));
  EXPECT_TRUE(has_gzip_magic(gzip("x")));
  EXPECT_FALSE(has_gzip_magic("\x1f"));
  EXPECT_FALSE(has_gzip_magic("\x8b\x1f"));
  EXPECT_FALSE(has_gzip_magic("ply\n"));
  EXPECT_FALSE(has_gzip_magic(""));
}

TEST(GzipFile, PlainFilesAreReadAsTheyAre) {
  test::TempDir dir;
  const std::string text = sample_text();
  EXPECT_EQ(read_file_contents(dir.write("a.pbrt", text)), text);
  EXPECT_EQ(read_file_contents(dir.write("empty.pbrt", "")), "");
  EXPECT_EQ(read_file_contents(dir.write("one.pbrt", "\x1f")), "\x1f");
  // The name does not matter: a plain file called .gz is plain.
  EXPECT_EQ(read_file_contents(dir.write("plain.pbrt.gz", text)), text);
}

TEST(GzipFile, GzipIsDetectedByItsMagicWhateverTheName) {
  test::TempDir dir;
  const std::string text = sample_text();
  EXPECT_EQ(read_file_contents(dir.write("a.pbrt.gz", gzip(text))), text);
  EXPECT_EQ(read_file_contents(dir.write("a.pbrt", gzip(text))), text);
  EXPECT_EQ(read_file_contents(dir.write("stored.gz", gzip(text, Z_NO_COMPRESSION))), text);
  EXPECT_EQ(read_file_contents(dir.write("empty.gz", gzip(""))), "");
  // Larger than the reader's input and output chunks.
  std::string big;
  while (big.size() < (size_t(5) << 20)) big += sample_text();
  EXPECT_EQ(read_file_contents(dir.write("big.gz", gzip(big, 1))), big);
}

TEST(GzipFile, ConcatenatedMembersAndZeroPadding) {
  test::TempDir dir;
  EXPECT_EQ(read_file_contents(dir.write("two.gz", gzip("first\n") + gzip("second\n"))), "first\nsecond\n");
  EXPECT_EQ(read_file_contents(dir.write("padded.gz", gzip("text\n") + std::string(100, '\0'))), "text\n");
  std::string garbage = dir.write("garbage.gz", gzip("text\n") + "trailing");
  EXPECT_NE(read_error(garbage).find("gzip data is corrupt/truncated (zlib: "), std::string::npos);
}

TEST(GzipFile, TruncatedDataIsAnErrorNamingTheFile) {
  test::TempDir dir;
  const std::string z = gzip(sample_text());
  ASSERT_GT(z.size(), 100u);
  for (size_t keep :
       {size_t(2), size_t(5), size_t(10), size_t(11), z.size() / 2, z.size() - 8, z.size() - 4, z.size() - 1}) {
    std::string path = dir.write("cut.pbrt.gz", z.substr(0, keep));
    std::string what = read_error(path);
    EXPECT_EQ(what, path + ": gzip data is corrupt/truncated (zlib: unexpected end of file)") << keep << " bytes kept";
  }
}

TEST(GzipFile, CorruptDataIsAnErrorNamingTheFile) {
  test::TempDir dir;
  const std::string text = sample_text();
  const std::string z = gzip(text);
  auto flipped = [&z](size_t at) {
    std::string c = z;
    c[at] = char(c[at] ^ 0x55);
    return c;
  };
  std::string method = dir.write("method.gz", flipped(2));  // CM: not deflate
  EXPECT_NE(read_error(method).find(method + ": gzip data is corrupt/truncated (zlib: unknown compression method)"),
            std::string::npos);
  std::string crc = dir.write("crc.gz", flipped(z.size() - 6));  // the CRC-32 of the trailer
  EXPECT_NE(read_error(crc).find(crc + ": gzip data is corrupt/truncated (zlib: incorrect data check)"),
            std::string::npos);
  // Every single-byte change after the magic (without which the file is not gzip and is read
  // as it is) either is reported or (header fields such as MTIME and OS) leaves the contents
  // as they were: never a crash, a hang or different text.
  std::string path = dir.path() + "/flip.gz";
  int reported = 0;
  for (size_t at = 2; at < z.size(); ++at) {
    dir.write("flip.gz", flipped(at));
    try {
      EXPECT_EQ(read_file_contents(path), text) << "byte " << at;
    } catch (const FileReadError& e) {
      EXPECT_NE(std::string(e.what()).find(path + ": gzip data is corrupt/truncated (zlib: "), std::string::npos)
          << e.what();
      ++reported;
    }
  }
  EXPECT_GE(reported, int(z.size()) - 2 - 6);  // all but MTIME, XFL, OS
}

TEST(GzipFile, DecompressionBombStopsAtTheLimit) {
  EXPECT_EQ(kMaxDecompressedBytes, uint64_t(4) << 30);
  test::TempDir dir;
  const std::string zeros(size_t(8) << 20, '\0');
  const std::string z = gzip(zeros);
  ASSERT_LT(z.size(), 20000u);  // about 1000:1
  std::string path = dir.write("bomb.gz", z);
  EXPECT_EQ(read_error(path, uint64_t(1) << 20),
            path +
                ": gzip data inflates to more than 1048576 bytes, the limit for one file "
                "(a corrupt file or a decompression bomb?)");
  EXPECT_EQ(read_file_contents(path, zeros.size()).size(), zeros.size());
  EXPECT_NE(read_error(path, zeros.size() - 1).find("inflates to more than"), std::string::npos);
}

TEST(GzipFile, MissingFileAndDirectory) {
  test::TempDir dir;
  EXPECT_EQ(read_error(dir.path() + "/none.gz"), dir.path() + "/none.gz: No such file or directory");
  EXPECT_EQ(read_error(dir.path()), dir.path() + ": it is a directory");
}

// A FIFO would block the reader until a writer comes, /dev/zero never ends: neither is
// opened (the test would hang or run out of memory if they were).
TEST(GzipFile, FifosAndDevicesAreRefusedWithoutBeingOpened) {
  test::TempDir dir;
  const std::string fifo = dir.path() + "/pipe.pbrt";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string not_regular = ": it is not a regular file (a device, FIFO or socket); only files are read";
  EXPECT_EQ(read_error(fifo), fifo + not_regular);
  EXPECT_EQ(read_error("/dev/zero"), "/dev/zero" + not_regular);
  // Through the parser: the Include names the file and where it was asked for.
  const std::string main = dir.write("main.pbrt", "WorldBegin\nInclude \"pipe.pbrt\"\n");
  try {
    parse_scene_file(main);
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("main.pbrt:2:9: error: could not read included file"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
}

// FileChunks hands a file out a piece at a time (never whole: a scene's grid of millions of
// values is parsed as it inflates): the pieces make up the contents, the fraction read grows
// to 1, and corruption near the end is met only when the reading gets there.
TEST(GzipFile, FileChunksStreamPlainAndGzip) {
  test::TempDir dir;
  std::string big;
  while (big.size() < (size_t(5) << 20)) big += sample_text();
  for (const std::string& path : {dir.write("big.pbrt", big), dir.write("big.pbrt.gz", gzip(big, 1))}) {
    FileChunks chunks(path);
    std::string got;
    std::size_t pieces = 0;
    double fraction = 0;
    for (std::string_view c = chunks.next(); !c.empty(); c = chunks.next()) {
      EXPECT_LE(c.size(), std::size_t(1) << 20) << path;
      EXPECT_GE(chunks.fraction_read(), fraction) << path;
      fraction = chunks.fraction_read();
      got.append(c);
      ++pieces;
    }
    EXPECT_EQ(got, big) << path;
    EXPECT_GE(pieces, 5u) << path;
    EXPECT_EQ(chunks.fraction_read(), 1.0) << path;
  }
  std::string cut = gzip(big, 1);
  cut.resize(cut.size() - 100);
  FileChunks chunks(dir.write("cut.pbrt.gz", cut));
  EXPECT_FALSE(chunks.next().empty());
  EXPECT_THROW(while (!chunks.next().empty()){}, FileReadError);
}

}  // namespace
}  // namespace dermis
