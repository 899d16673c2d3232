// End-to-end tests of the `dermis` command line: the real binary, real files.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "dermis/render/image.h"
#include "dermis/scene/scene_test_util.h"

namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int status = -1;
  std::string output;  // stdout and stderr
};

// `env`: variable assignments put before the command ("NAME=value ").
CommandResult run_dermis(const std::string& args, const std::string& env = "") {
  CommandResult r;
  std::string cmd = env + std::string(DERMIS_BINARY) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dermis_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

const char* kSmallScene = R"(
LookAt 0 0 -4  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 24 "integer yresolution" 16 "string filename" "x.exr"
Sampler "independent" "integer pixelsamples" 4
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5]
MakeNamedMedium "milk" "string type" "homogeneous" "string preset" "Wholemilk" "float scale" 0.5
AttributeBegin
  MediumInterface "milk" ""
  Material "dielectric" "float eta" 1.33
  Shape "sphere" "float radius" 1
AttributeEnd
)";

TEST_F(Cli, VersionAndHelp) {
  CommandResult v = run_dermis("--version");
  EXPECT_EQ(v.status, 0);
  EXPECT_NE(v.output.find("dermis"), std::string::npos);
  CommandResult h = run_dermis("render --help");
  EXPECT_EQ(h.status, 0);
  EXPECT_NE(h.output.find("--time-limit"), std::string::npos);
}

TEST_F(Cli, RendersAScene) {
  std::string scene = write("s.pbrt", kSmallScene);
  CommandResult r = run_dermis("render " + scene + " -q -o " + path("out.exr"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(path("out.exr")));
  EXPECT_TRUE(fs::exists(path("out.png")));
  dermis::Image img = dermis::read_image(path("out.exr"));
  EXPECT_EQ(img.width, 24);
  EXPECT_EQ(img.height, 16);
}

// OpenImageIO is a plugin loaded on the first image read (render/image_plugin.h): a render
// that reads no image writes its .exr and .png without it; one that reads a texture says
// that the plugin is missing, with status 2 and no output.
TEST_F(Cli, RendersWithoutTheImagePluginUnlessItReadsAnImage) {
  const std::string no_plugin = "DERMIS_OIIO_PLUGIN=" + path("missing.so") + " ";
  auto run_without = [&](const std::string& args) { return run_dermis(args, no_plugin); };
  CommandResult ok = run_without("render " + write("s.pbrt", kSmallScene) + " -q -o " + path("out.exr"));
  ASSERT_EQ(ok.status, 0) << ok.output;
  EXPECT_TRUE(fs::exists(path("out.png")));
  EXPECT_EQ(dermis::read_image(path("out.exr")).width, 24);  // this process has the plugin

  dermis::write_image(path("tex.png"), dermis::Image(4, 4, dermis::RGB(0.5f)));
  const std::string textured = R"(
LookAt 0 0 -4  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5]
Texture "t" "spectrum" "imagemap" "string filename" ")" +
                               path("tex.png") + R"("
Material "diffuse" "texture reflectance" "t"
Shape "sphere" "float radius" 1
)";
  CommandResult bad = run_without("render " + write("t.pbrt", textured) + " -q -o " + path("t.exr"));
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("libdermis_oiio.so"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(path("t.exr")));
  CommandResult good = run_dermis("render " + path("t.pbrt") + " -q -o " + path("t.exr"));
  EXPECT_EQ(good.status, 0) << good.output;
}

TEST_F(Cli, SameSeedSameImageWithOneAndTwoThreads) {
  std::string scene = write("s.pbrt", kSmallScene);
  ASSERT_EQ(run_dermis("render " + scene + " -q --threads 1 --seed 9 -o " + path("a.exr")).status, 0);
  ASSERT_EQ(run_dermis("render " + scene + " -q --threads 2 --seed 9 -o " + path("b.exr")).status, 0);
  dermis::Image a = dermis::read_image(path("a.exr")), b = dermis::read_image(path("b.exr"));
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)));
}

// One float channel of an OpenEXR file (empty if it has no such channel).
std::vector<float> exr_channel(const std::string& path, const char* name) {
  Imf::InputFile file(path.c_str());
  if (!file.header().channels().findChannel(name)) return {};
  const Imath::Box2i box = file.header().dataWindow();
  const int w = box.max.x - box.min.x + 1, h = box.max.y - box.min.y + 1;
  std::vector<float> values(std::size_t(w) * h);
  Imf::FrameBuffer fb;
  fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float), sizeof(float) * w));
  file.setFrameBuffer(fb);
  file.readPixels(box.min.y, box.max.y);
  return values;
}

// --noise-threshold: the .exr gains the per-pixel sample counts and error estimates, the
// summary says how many pixels converged; another format gets them in STEM-maps.exr;
// the scene's Sampler can ask for it; bad values are refused with the place.
TEST_F(Cli, AdaptiveSamplingWritesTheCountAndErrorChannels) {
  std::string scene = write("s.pbrt", kSmallScene);
  CommandResult r = run_dermis("render " + scene + " --no-png --spp 64 --noise-threshold 0.05 -o " + path("a.exr"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("at most 64 spp (noise threshold 0.05, at least 16)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("adaptive sampling: "), std::string::npos) << r.output;
  const std::vector<float> samples = exr_channel(path("a.exr"), "samples"), error = exr_channel(path("a.exr"), "error");
  ASSERT_EQ(samples.size(), 24u * 16u);
  ASSERT_EQ(error.size(), samples.size());
  const auto [fewest, most] = std::minmax_element(samples.begin(), samples.end());
  EXPECT_EQ(*fewest, 16.0f);  // the background converges at once
  EXPECT_EQ(*most, 64.0f);    // the milk does not at 0.05
  for (std::size_t p = 0; p < samples.size(); ++p)
    if (samples[p] < 64) {
      EXPECT_LE(error[p], 0.05f) << p;
    }
  CommandResult uniform = run_dermis("render " + scene + " -q --no-png --spp 4 -o " + path("u.exr"));
  ASSERT_EQ(uniform.status, 0) << uniform.output;
  EXPECT_TRUE(exr_channel(path("u.exr"), "samples").empty());
  ASSERT_EQ(run_dermis("render " + scene + " -q --no-png --spp 4 --error-map -o " + path("m.exr")).status, 0);
  const std::vector<float> uniform_counts = exr_channel(path("m.exr"), "samples");
  ASSERT_EQ(uniform_counts.size(), 24u * 16u);
  EXPECT_EQ(*std::min_element(uniform_counts.begin(), uniform_counts.end()), 4.0f);
  EXPECT_EQ(exr_channel(path("m.exr"), "error").size(), 24u * 16u);
  const std::vector<float> rays = exr_channel(path("m.exr"), "rays");
  ASSERT_EQ(rays.size(), 24u * 16u);
  for (float n : rays) EXPECT_GE(n, 4.0f);  // at least the camera ray of each sample

  CommandResult png = run_dermis("render " + scene + " -q --spp 32 --noise-threshold 0.1 -o " + path("p.png"));
  ASSERT_EQ(png.status, 0) << png.output;
  EXPECT_EQ(exr_channel(path("p-maps.exr"), "samples").size(), 24u * 16u);

  std::string text = kSmallScene;
  const std::string asked = "\"integer pixelsamples\" 4";
  text.replace(text.find(asked), asked.size(),
               "\"integer pixelsamples\" 32 \"float noisethreshold\" 0.1 \"integer minpixelsamples\" 8");
  CommandResult from_scene = run_dermis("render " + write("t.pbrt", text) + " --no-png -o " + path("t.exr"));
  ASSERT_EQ(from_scene.status, 0) << from_scene.output;
  EXPECT_NE(from_scene.output.find("at most 32 spp (noise threshold 0.1, at least 8)"), std::string::npos)
      << from_scene.output;
  const std::vector<float> counts = exr_channel(path("t.exr"), "samples");
  ASSERT_FALSE(counts.empty());
  EXPECT_EQ(*std::min_element(counts.begin(), counts.end()), 8.0f);

  EXPECT_EQ(run_dermis("render " + scene + " --noise-threshold -0.1 -o " + path("o.exr")).status, 2);
  EXPECT_EQ(run_dermis("render " + scene + " --noise-threshold 0.1 --min-spp 0 -o " + path("o.exr")).status, 2);
  text.replace(text.find("0.1"), 3, "-1.");
  CommandResult bad = run_dermis("render " + write("b.pbrt", text) + " -o " + path("o.exr"));
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("b.pbrt:5:"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("noisethreshold must be 0 (off) or a positive"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(path("o.exr")));
}

// --checkpoint then --resume with more samples: the same pixels as one render of that
// many samples. A checkpoint of another seed or scene is refused with the reason.
TEST_F(Cli, ResumeFromACheckpointIsBitIdentical) {
  std::string scene = write("s.pbrt", kSmallScene);
  const std::string common = " -q --no-png --seed 3 --threads 2 ";
  ASSERT_EQ(run_dermis("render " + scene + common + "--spp 6 -o " + path("whole.exr")).status, 0);
  CommandResult first =
      run_dermis("render " + scene + common + "--spp 2 --checkpoint " + path("c.ckpt") + " -o " + path("part.exr"));
  ASSERT_EQ(first.status, 0) << first.output;
  ASSERT_TRUE(fs::exists(path("c.ckpt")));
  CommandResult rest =
      run_dermis("render " + scene + common + "--spp 6 --resume " + path("c.ckpt") + " -o " + path("resumed.exr"));
  ASSERT_EQ(rest.status, 0) << rest.output;
  dermis::Image a = dermis::read_image(path("whole.exr")), b = dermis::read_image(path("resumed.exr"));
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)));

  CommandResult other_seed =
      run_dermis("render " + scene + " -q --seed 4 --resume " + path("c.ckpt") + " -o " + path("o.exr"));
  EXPECT_EQ(other_seed.status, 2);
  EXPECT_NE(other_seed.output.find("written with --seed 3, not 4"), std::string::npos) << other_seed.output;
  EXPECT_FALSE(fs::exists(path("o.exr")));
  write("s.pbrt", std::string(kSmallScene) + "# changed\n");
  CommandResult changed =
      run_dermis("render " + scene + " -q --seed 3 --resume " + path("c.ckpt") + " -o " + path("o.exr"));
  EXPECT_EQ(changed.status, 2);
  EXPECT_NE(changed.output.find("another scene"), std::string::npos) << changed.output;
  CommandResult garbage =
      run_dermis("render " + scene + " -q --resume " + write("g.ckpt", "not a checkpoint") + " -o " + path("o.exr"));
  EXPECT_EQ(garbage.status, 2);
  EXPECT_NE(garbage.output.find("not a Dermis checkpoint"), std::string::npos) << garbage.output;
}

// --subsurface gives every subsurface material the parameters: `pbrt-v4` renders the
// scene as if its material named the photon-beam profile and the disk probes (the same
// image bit for bit); text that does not parse is refused at its column, status 2, no image.
TEST_F(Cli, SubsurfaceOptionSetsEveryMaterialsMethod) {
  const std::string head = R"(
LookAt 0 0 -4  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 16 "integer yresolution" 16
Sampler "independent" "integer pixelsamples" 2
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5]
)";
  const std::string plain =
      write("plain.pbrt", head + R"(Material "subsurface" "rgb reflectance" [0.8 0.5 0.3] "rgb mfp" [0.2 0.1 0.05]
Shape "sphere" "float radius" 1
)");
  const std::string named = write(
      "named.pbrt",
      head +
          R"(Material "subsurface" "rgb reflectance" [0.8 0.5 0.3] "rgb mfp" [0.2 0.1 0.05] "string method" "disk" "string profile" "photonbeam"
Shape "sphere" "float radius" 1
)");
  ASSERT_EQ(run_dermis("render " + plain + " -q --seed 3 --subsurface pbrt-v4 -o " + path("a.exr")).status, 0);
  ASSERT_EQ(run_dermis("render " + named + " -q --seed 3 -o " + path("b.exr")).status, 0);
  ASSERT_EQ(run_dermis("render " + plain + " -q --seed 3 -o " + path("c.exr")).status, 0);
  const dermis::Image a = dermis::read_image(path("a.exr")), b = dermis::read_image(path("b.exr")),
                      c = dermis::read_image(path("c.exr"));
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)));
  EXPECT_NE(0, std::memcmp(a.pixels.data(), c.pixels.data(), a.pixels.size() * sizeof(float)));  // the walk's

  const CommandResult bad =
      run_dermis("render " + plain + " -q --subsurface '\"string method\" \"nope\"' -o " + path("d.exr"));
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--subsurface:1:"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(path("d.exr")));
}

TEST_F(Cli, MissingSceneIsAnErrorWithStatus2) {
  CommandResult r = run_dermis("render " + path("nope.pbrt") + " -o " + path("o.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("nope.pbrt"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("o.exr")));
}

TEST_F(Cli, GzipSceneRendersAndCorruptGzipExitsWithStatus2) {
  const std::string z = dermis::test::gzip(kSmallScene);
  CommandResult ok = run_dermis("render " + write("s.pbrt.gz", z) + " -q --no-png -o " + path("ok.exr"));
  EXPECT_EQ(ok.status, 0) << ok.output;
  EXPECT_TRUE(fs::exists(path("ok.exr")));
  std::string cut = write("cut.pbrt.gz", z.substr(0, z.size() / 2));
  CommandResult r = run_dermis("render " + cut + " -q -o " + path("o.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find(cut + "': gzip data is corrupt/truncated (zlib: unexpected end of file)"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(path("o.exr")));
}

TEST_F(Cli, MalformedSceneReportsLineAndColumnAndWritesNothing) {
  std::string scene = write("bad.pbrt", "WorldBegin\nShape \"sphere\" \"float radius\" [ 1\n");
  CommandResult r = run_dermis("render " + scene + " -o " + path("o.exr"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("bad.pbrt:"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("o.exr")));
  EXPECT_FALSE(fs::exists(path("o.png")));
}

TEST_F(Cli, BadOptionsExitWithStatus2) {
  std::string scene = write("s.pbrt", kSmallScene);
  EXPECT_EQ(run_dermis("render " + scene + " --res 12by5 -o " + path("o.exr")).status, 2);
  EXPECT_EQ(run_dermis("render " + scene + " --res 32x32junk -o " + path("o.exr")).status, 2);
  // A film that cannot be allocated is refused before anything is read or allocated.
  std::string huge = kSmallScene;
  const std::string xres = "\"integer xresolution\" 24";
  huge.replace(huge.find(xres), xres.size(), "\"integer xresolution\" 100000000");
  CommandResult r = run_dermis("render " + write("huge.pbrt", huge) + " -o " + path("o.exr"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("too large"), std::string::npos) << r.output;
  EXPECT_EQ(run_dermis("render " + scene + " --spp -3 -o " + path("o.exr")).status, 2);
  EXPECT_EQ(run_dermis("render " + scene + " -o " + path("o.bmpx")).status, 2);
  EXPECT_EQ(run_dermis("render " + scene + " -o " + path("missing_dir/o.exr")).status, 2);
  EXPECT_EQ(run_dermis("frobnicate").status, 2);
  EXPECT_FALSE(fs::exists(path("o.exr")));
  EXPECT_EQ(run_dermis("halfspace --albedo 0.5 --paths 10 --walksampling guided").status, 2);
  EXPECT_EQ(run_dermis("halfspace --albedo 0.5 --paths 10 --walksampling mis --p-guided 1.5").status, 2);
}

TEST_F(Cli, HalfspaceWalkSampling) {
  CommandResult r = run_dermis("halfspace --albedo 0.9 --paths 2000 --bins 2 --walksampling mis -o " + path("r.csv"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("mis sampling"), std::string::npos) << r.output;
}

TEST_F(Cli, TimeLimitKeepsTheSamplesTaken) {
  std::string scene = write("s.pbrt", kSmallScene);
  CommandResult r = run_dermis("render " + scene + " -q --spp 100000 --time-limit 0.5 -o " + path("t.exr"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(path("t.exr")));
}

TEST_F(Cli, PointCloudSaveLoadAndBadFile) {
  std::string scene = write("pc.pbrt", R"(LookAt 0 0 -4  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 12 "integer yresolution" 8
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
Material "subsurface" "rgb reflectance" [0.7 0.5 0.3] "rgb mfp" [0.2 0.2 0.2] "string method" "pointcloud"
Shape "sphere"
)");
  CommandResult s = run_dermis("render " + scene + " --spp 2 --points 500 --save-pointcloud " + path("c.bin") + " -o " +
                               path("a.exr"));
  ASSERT_EQ(s.status, 0) << s.output;
  EXPECT_NE(s.output.find("point clouds: 500 points"), std::string::npos) << s.output;
  EXPECT_TRUE(fs::exists(path("c.bin")));
  EXPECT_EQ(
      run_dermis("render " + scene + " -q --spp 2 --load-pointcloud " + path("c.bin") + " -o " + path("b.exr")).status,
      0);
  std::ofstream(path("bad.bin")) << "not a point cloud";
  CommandResult bad = run_dermis("render " + scene + " --load-pointcloud " + path("bad.bin") + " -o " + path("x.exr"));
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("bad.bin"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(path("x.exr")));
}

TEST_F(Cli, InterruptWritesThePartialImageAndSaysSo) {
  std::string scene = write("s.pbrt", kSmallScene);
  // SIGINT to a render that would take minutes, sent once it has finished a pass: its first
  // checkpoint (written after each pass past 1 ms) exists. Whatever the machine's speed, the
  // signal then lands in the render loop with samples done (a background job of sh starts
  // with SIGINT ignored until dermis installs its handler: a signal sent before would be lost).
  const std::string log = path("render.log"), checkpoint = path("i.ckpt");
  std::string cmd = "sh -c '" + std::string(DERMIS_BINARY) + " render " + scene + " --spp 1000000 --res 64x64 -o " +
                    path("i.exr") + " --checkpoint " + checkpoint + " --checkpoint-interval 0.001 > " + log +
                    " 2>&1 & pid=$!; i=0; while [ ! -e " + checkpoint +
                    " ] && [ $i -lt 1200 ]; do sleep 0.05; i=$((i+1)); done; kill -INT $pid; wait $pid; "
                    "echo rc=$?; cat " +
                    log + "'";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  pclose(p);
  EXPECT_NE(out.find("interrupted"), std::string::npos) << out;
  EXPECT_NE(out.find("rc=130"), std::string::npos) << out;
  ASSERT_TRUE(fs::exists(path("i.exr"))) << out;
  dermis::Image img = dermis::read_image(path("i.exr"));
  float sum = 0;
  for (float v : img.pixels) sum += v;
  EXPECT_GT(sum, 0.0f);  // the samples finished before the interrupt are in the image
}

// A cache that cannot be written (its folder cannot be made, even by root: it would lie under
// a file) never fails a render: the tables are built, used and not kept. The photon-beam
// table is always written when built; the walk's albedo table when it took a second or more.
TEST_F(Cli, AnUnwritableCacheNeverFailsARender) {
  const std::string scene = write("tables.pbrt", R"(LookAt 0 0 -4  0 0 0  0 1 0
Camera "perspective" "float fov" 40
Film "rgb" "integer xresolution" 16 "integer yresolution" 8
WorldBegin
LightSource "infinite" "rgb L" [0.5 0.5 0.5]
AttributeBegin
  Translate -1.1 0 0
  Material "subsurface" "rgb reflectance" [0.8 0.5 0.3] "rgb mfp" [0.2 0.2 0.2] "float eta" 1.37
    "string method" "randomwalk"
  Shape "sphere"
AttributeEnd
AttributeBegin
  Translate 1.1 0 0
  Material "subsurface" "rgb reflectance" [0.8 0.5 0.3] "rgb mfp" [0.2 0.2 0.2] "float eta" 1.37
    "string method" "disk" "string profile" "photonbeam"
  Shape "sphere"
AttributeEnd
)");
  for (const char* env : {"XDG_CACHE_HOME=/dev/null/cache ", "XDG_CACHE_HOME= HOME=/dev/null "}) {
    SCOPED_TRACE(env);
    const CommandResult r = run_dermis("render " + scene + " -q --spp 2 --no-png -o " + path("t.exr"), env);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(fs::exists(path("t.exr")));
    fs::remove(path("t.exr"));
  }
}

TEST_F(Cli, CompareReportsDifferences) {
  std::string scene = write("s.pbrt", kSmallScene);
  ASSERT_EQ(run_dermis("render " + scene + " -q --seed 1 -o " + path("a.exr")).status, 0);
  ASSERT_EQ(run_dermis("render " + scene + " -q --seed 2 -o " + path("b.exr")).status, 0);
  CommandResult r = run_dermis("compare " + path("a.exr") + " " + path("b.exr") + " --diff " + path("d.exr"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("RMSE"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(path("d.exr")));
  EXPECT_EQ(run_dermis("compare " + path("a.exr") + " " + path("nope.exr")).status, 2);
}

// A point light of 1e37 (within float range, as the parser requires) 0.001 away from a
// wall, seen through a narrow lens: I / r^2 overflows to infinity in the path. Such samples are counted, reported, and
// never reach the image.
TEST_F(Cli, NonFiniteSamplesAreReportedAndNotWritten) {
  std::string scene = write("hot.pbrt", R"(
LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 0.5
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
LightSource "point" "point3 from" [0 0 0.001] "rgb I" [1e37 1e37 1e37]
Material "diffuse"
Shape "trianglemesh" "point3 P" [-5 -5 0 5 -5 0 5 5 0 -5 5 0] "integer indices" [0 1 2 0 2 3]
)");
  CommandResult r = run_dermis("render " + scene + " -q --spp 2 --no-png -o " + path("hot.exr"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(" samples were NaN or infinite; they were dropped"), std::string::npos) << r.output;
  dermis::Image img = dermis::read_image(path("hot.exr"));
  for (float v : img.pixels) ASSERT_TRUE(std::isfinite(v));
}

// A light whose power is beyond float's range is an error at its directive, exit 2, nothing
// written (light selection used to stop the render with "Distribution1D: value 0 of the
// function is inf", naming neither the light nor where it is).
TEST_F(Cli, ALightWhosePowerOverflowsIsRefusedAtItsDirective) {
  std::string scene = write("bright.pbrt", R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 8 "integer yresolution" 8
WorldBegin
Shape "sphere"
LightSource "point" "point3 from" [0 0 4] "rgb I" [3e37 3e37 3e37]
)");
  CommandResult r = run_dermis("render " + scene + " -q -o " + path("bright.exr"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("bright.pbrt:6:1: error: the point light's power 4π·I = 4π × 3e+37 = 3.77e+38 is beyond "
                          "the range of 32-bit floats"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("lower \"I\" or \"scale\""), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("Distribution1D"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("bright.exr")));
}

// --confine: the scene reads inside its directory and the --allow-path ones only, after
// '..' and symbolic links; outside is an error at the file name, exit 2, nothing written.
TEST_F(Cli, ConfineRefusesFilesOutsideTheSceneDirectory) {
  const std::string head =
      "Camera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" 4 "
      "\"integer yresolution\" 4\nWorldBegin\nLightSource \"point\"\n";
  fs::create_directories(dir_ / "scene");
  fs::create_directories(dir_ / "assets");
  write("assets/part.pbrt", "Shape \"sphere\"\n");
  write("scene/inside.pbrt", "Shape \"sphere\"\n");
  fs::create_symlink(dir_ / "assets", dir_ / "scene" / "link");
  const std::string up = write("scene/up.pbrt", head + "Include \"../assets/part.pbrt\"\n");
  const std::string abs = write("scene/abs.pbrt", head + "Include \"" + path("assets/part.pbrt") + "\"\n");
  const std::string sym = write("scene/sym.pbrt", head + "Include \"link/part.pbrt\"\n");
  const std::string in = write("scene/in.pbrt", head + "Include \"inside.pbrt\"\n");
  const std::string out = " -q --no-png -o " + path("o.exr");
  // pbrt-v4's default: any path.
  for (const std::string& s : {up, abs, sym}) EXPECT_EQ(run_dermis("render " + s + out).status, 0) << s;
  fs::remove(path("o.exr"));
  for (const std::string& s : {up, abs, sym}) {
    CommandResult r = run_dermis("render " + s + " --confine" + out);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(":5:9: error: Include '"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("is outside the directories this scene may read"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("o.exr")));
  }
  EXPECT_EQ(run_dermis("render " + in + " --confine" + out).status, 0);
  // An allowed directory (--allow-path implies --confine), named through a symlink or not.
  for (const std::string& s : {up, abs, sym})
    EXPECT_EQ(run_dermis("render " + s + " --allow-path " + path("assets") + out).status, 0) << s;
  EXPECT_EQ(
      run_dermis("render " + up + " --allow-path " + path("scene") + " --allow-path " + path("assets") + out).status,
      0);
  EXPECT_EQ(run_dermis("render " + up + " --allow-path " + path("missing-dir") + out).status, 2);
}

}  // namespace
