#include "dermis/preview/preview_server.h"

#include <gtest/gtest.h>
#include <httplib.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <thread>

#include "dermis/render/image.h"
#include "dermis/scene/scene_test_util.h"

namespace dermis {
namespace {

// A film of w x h pixels, each of `samples` samples of radiance v (grey).
Film uniform_film(int w, int h, uint32_t samples, double v) {
  Film film(w, h);
  for (std::size_t p = 0; p < film.pixel_count(); ++p) {
    film.samples[p] = samples;
    for (int c = 0; c < 3; ++c) film.sum[3 * p + c] = v * samples, film.sum_sq[3 * p + c] = v * v * samples;
  }
  return film;
}

// The PNG's pixels, through a file (read_image reads PNGs with libpng, as sRGB).
Image decode(const std::string& png, const test::TempDir& dir) {
  const std::string path = dir.path() + "/decoded.png";
  std::ofstream(path, std::ios::binary) << png;
  return read_image(path);
}

TEST(PreviewPng, TheImageIsToneMappedAtItsExposureAndTheMapsOverTheirScale) {
  test::TempDir dir;
  LiveImage::Frame f;
  f.width = 2, f.height = 1;
  f.rgb = {0.25f, 0.25f, 0.25f, 2.0f, 0.5f, 0.0f};
  f.samples = {8, 32};
  f.error = {0.1f, -1.0f};  // unknown in the second pixel
  // 0.25 at +1 stop is 0.5 (linear, after the sRGB round trip: within one 8-bit step); 2.0 clips.
  const Image img = decode(preview_png(f, PreviewView::Image, 1.0f), dir);
  ASSERT_EQ(img.width, 2);
  EXPECT_NEAR(img.at(0, 0)[0], 0.5f, 0.01f);
  EXPECT_NEAR(img.at(1, 0)[0], 1.0f, 1e-6f);
  EXPECT_NEAR(img.at(1, 0)[1], 1.0f, 1e-6f);
  EXPECT_NEAR(img.at(1, 0)[2], 0.0f, 1e-6f);
  const Image samples = decode(preview_png(f, PreviewView::Samples, 0), dir);
  EXPECT_NEAR(samples.at(0, 0)[0], 0.25f, 0.01f);  // 8 of 32
  EXPECT_NEAR(samples.at(1, 0)[0], 1.0f, 1e-6f);
  const Image error = decode(preview_png(f, PreviewView::Error, 0), dir);
  EXPECT_NEAR(error.at(0, 0)[0], 1.0f, 1e-6f);  // the largest known error
  EXPECT_NEAR(error.at(1, 0)[0], 0.0f, 1e-6f);  // unknown: black
}

// The image's 8-bit codes (a table, not a power per channel) are sRGB's curve rounded, at
// every value from 0 to beyond 1 (4000 of them, denser near 0 where the codes are closest).
TEST(PreviewPng, TheCodesAreTheSrgbCurveRounded) {
  test::TempDir dir;
  LiveImage::Frame f;
  f.width = 4000, f.height = 1;
  for (int i = 0; i < f.width; ++i) {
    const float v = 1.1f * std::pow(float(i) / float(f.width - 1), 2.5f);
    f.rgb.insert(f.rgb.end(), {v, v, v});
  }
  f.samples.assign(f.width, 1), f.error.assign(f.width, 0.0f);
  const Image img = decode(preview_png(f, PreviewView::Image, 0), dir);
  int wrong = 0;
  for (int i = 0; i < f.width; ++i) {
    const float v = f.rgb[3 * i];
    const long code = std::lround(255 * linear_to_srgb(std::min(v, 1.0f)));
    const long read = std::lround(255 * linear_to_srgb(img.at(i, 0)[1]));  // the decoder linearizes
    if (read != code && wrong++ < 5) ADD_FAILURE() << "value " << v << ": code " << read << ", not " << code;
  }
  EXPECT_EQ(wrong, 0);
}

TEST(PreviewStatus, IsJsonWithTheErrorEscaped) {
  LiveImage::Status s;
  s.scene = "a \"b\".pbrt";
  s.state = LiveImage::State::Error;
  s.error = "x.pbrt:3:5: bad\nline";
  const std::string json = preview_status_json(s);
  EXPECT_NE(json.find("\"scene\": \"a \\\"b\\\".pbrt\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"state\": \"error\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"error\": \"x.pbrt:3:5: bad\\u000aline\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"converged\": null"), std::string::npos) << json;
}

// The server on loopback: the page, the status, the image as tiles arrive (a new PNG once
// the last is older than kPreviewEncodeInterval), and 404 for every other path.
TEST(PreviewServer, ServesThePageTheStatusAndTheImageAsItChanges) {
  LiveImage live("scene.pbrt");
  PreviewServer server(live, "127.0.0.1", 0);
  ASSERT_GT(server.port(), 0);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.port()) + "/");
  httplib::Client client("127.0.0.1", server.port());

  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_NE(page->body.find("id=\"view\""), std::string::npos);
  auto status = client.Get("/status.json");
  ASSERT_TRUE(status);
  EXPECT_NE(status->body.find("\"state\": \"loading\""), std::string::npos) << status->body;

  live.begin_render(32, 16, 4, 32 * 16 * 4, 1.0);
  const Film dark = uniform_film(32, 16, 2, 0.1), bright = uniform_film(32, 16, 4, 0.8);
  live.copy_tile(dark, 0, 0, 32, 16);
  live.add_samples(32 * 16 * 2);
  auto first = client.Get("/image.png");
  ASSERT_TRUE(first);
  EXPECT_EQ(first->status, 200);
  EXPECT_EQ(first->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(first->body.substr(1, 3), "PNG");
  status = client.Get("/status.json");
  EXPECT_NE(status->body.find("\"state\": \"rendering\""), std::string::npos) << status->body;
  EXPECT_NE(status->body.find("\"progress\": 0.5,"), std::string::npos) << status->body;
  EXPECT_NE(status->body.find("\"samples_per_pixel\": 2,"), std::string::npos) << status->body;

  live.copy_tile(bright, 0, 0, 16, 16);  // the left half
  std::this_thread::sleep_for(std::chrono::duration<double>(kPreviewEncodeInterval * 1.2));
  auto second = client.Get("/image.png");
  ASSERT_TRUE(second);
  EXPECT_NE(second->body, first->body);
  test::TempDir dir;
  const Image img = decode(second->body, dir);
  EXPECT_NEAR(img.at(3, 3)[0], 0.8f, 0.01f);
  EXPECT_NEAR(img.at(20, 3)[0], 0.1f, 0.01f);
  EXPECT_EQ(client.Get("/image.png?exposure=-1")->status, 200);
  EXPECT_EQ(client.Get("/image.png?exposure=bright")->status, 400);
  EXPECT_EQ(client.Get("/samples.png")->status, 200);
  EXPECT_EQ(client.Get("/error.png")->status, 200);

  live.finish(false);
  status = client.Get("/status.json");
  EXPECT_NE(status->body.find("\"state\": \"done\""), std::string::npos) << status->body;
  live.fail("scene.pbrt:2:1: unknown directive");
  status = client.Get("/status.json");
  EXPECT_NE(status->body.find("\"error\": \"scene.pbrt:2:1: unknown directive\""), std::string::npos);
  EXPECT_EQ(client.Get("/image.png")->status, 200);  // the last image stays

  for (const char* path : {"/index.html", "/etc/passwd", "/../../etc/passwd", "/image.png/x", "/imagexpng",
                           "/status.json/", "/page.html", "/%2e%2e/%2e%2e/etc/passwd"}) {
    auto r = client.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 404) << path;
    EXPECT_EQ(r->body.find("root:"), std::string::npos) << path;
  }
  auto post = client.Post("/", "x", "text/plain");
  ASSERT_TRUE(post);
  EXPECT_NE(post->status, 200);
}

TEST(PreviewServer, APortInUseIsAnErrorThatNamesIt) {
  LiveImage live("scene.pbrt");
  PreviewServer first(live, "127.0.0.1", 0);
  try {
    PreviewServer second(live, "127.0.0.1", first.port());
    FAIL() << "bound twice";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(first.port())), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dermis
