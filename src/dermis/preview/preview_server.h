// The live preview's web server (`dermis render --preview`, dermis.render(preview=True)):
// a page that shows a LiveImage as it converges, on the loopback address unless told
// otherwise. It serves exactly these paths, GET only, and nothing from disk:
//   /             the page (page.html, embedded at build time)
//   /image.png    the image, tone-mapped (?exposure=EV, stops; default 0), sRGB
//   /samples.png  the samples taken per pixel, over the most any pixel took
//   /error.png    the estimated error per pixel (adaptive_sampling.h), over its 99th percentile
//   /status.json  the progress facts (LiveImage::Status)
// Anything else is 404. The PNGs are encoded on the server's threads, only when asked,
// at most every kPreviewEncodeInterval for a changing image, and less often where encoding
// would take more than kPreviewEncodeShare of a core: the render's threads only copy their
// tiles (LiveImage::copy_tile). cpp-httplib (Debian's libcpp-httplib-dev).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "dermis/preview/live_image.h"

namespace dermis {

inline constexpr double kPreviewEncodeInterval = 0.25;  // seconds
// At most this share of one core's time goes to encoding a view, however large the image.
inline constexpr double kPreviewEncodeShare = 0.02;
// zlib's level for the PNGs: 0, stored (loopback needs no small files; Huffman coding
// alone took twice the time of the rest of the encoding at 1280 x 720).
inline constexpr int kPreviewZlibLevel = 0;

class PreviewServer {
 public:
  // Binds to `address`:`port` (0: a free port) and serves from a thread of its own.
  // Throws std::runtime_error (naming the address and port) when it cannot bind.
  PreviewServer(LiveImage& image, const std::string& address, int port);
  ~PreviewServer();  // stops serving and joins
  PreviewServer(const PreviewServer&) = delete;
  PreviewServer& operator=(const PreviewServer&) = delete;

  int port() const;
  // http://ADDRESS:PORT/ (IPv6 addresses in brackets).
  std::string url() const;
  // What serving has cost so far: the requests answered, and the CPU seconds of the
  // server's threads (the one listening and those that answered, encoding and sending included).
  struct Cost {
    int64_t requests = 0;
    double cpu_seconds = 0;
  };
  Cost cost() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The pieces the server sends, for tests.
enum class PreviewView { Image, Samples, Error };
// The frame as an sRGB PNG: the image at 2^exposure_ev, or a map.
std::string preview_png(const LiveImage::Frame& frame, PreviewView view, float exposure_ev);
// status.json's text.
std::string preview_status_json(const LiveImage::Status& status);

}  // namespace dermis
