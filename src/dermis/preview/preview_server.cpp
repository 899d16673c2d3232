#include "dermis/preview/preview_server.h"

#include <fmt/format.h>
#include <httplib.h>
#include <sys/socket.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "dermis/preview/page_html.h"  // generated from page.html (CMakeLists.txt)
#include "dermis/preview/thread_cpu_time.h"
#include "dermis/render/image.h"

namespace dermis {

namespace {

// Linear values to 8-bit sRGB codes: lround(255 linear_to_srgb(v)) without a power per
// channel. A code's lower edge is the linear value of code - 1/2 (sRGB's curve inverted); a
// table over 4096 bins of [0, 1] gives the code at a bin's start, and at most one edge
// lies inside a bin (sRGB's steepest slope, 12.92, is 0.8 codes per bin).
class Srgb8 {
 public:
  Srgb8() {
    for (int i = 0; i < 255; ++i) edges_[i] = srgb_to_linear((float(i) + 0.5f) / 255.0f);
    edges_[255] = INFINITY;
    for (int b = 0; b <= kBins; ++b)
      start_[b] = uint8_t(std::upper_bound(edges_.begin(), edges_.end() - 1, float(b) / kBins) - edges_.begin());
  }
  uint8_t operator()(float linear) const {
    if (!(linear > 0)) return 0;  // and NaN
    if (linear >= 1) return 255;
    uint8_t code = start_[int(linear * kBins)];
    if (linear >= edges_[code]) ++code;
    return code;
  }

 private:
  static constexpr int kBins = 4096;
  std::array<float, 256> edges_{};
  std::array<uint8_t, kBins + 1> start_{};
};

}  // namespace

std::string preview_png(const LiveImage::Frame& frame, PreviewView view, float exposure_ev) {
  const std::size_t n = std::size_t(frame.width) * std::size_t(frame.height);
  if (n == 0) return encode_png(1, 1, {0, 0, 0}, kPreviewZlibLevel);
  static const Srgb8 srgb8;
  std::vector<uint8_t> encoded(3 * n);
  if (view == PreviewView::Image) {
    const float scale = std::exp2(std::clamp(exposure_ev, -20.0f, 20.0f));
    for (std::size_t i = 0; i < 3 * n; ++i) encoded[i] = srgb8(frame.rgb[i] * scale);
  } else {
    // A map as grey, 0 to its scale: the most samples, or the error's 99th percentile
    // (one firefly pixel would turn the rest black). Unknown error (fewer than 2 samples): black.
    std::vector<float> value(n);
    for (std::size_t i = 0; i < n; ++i)
      value[i] = view == PreviewView::Samples ? float(frame.samples[i]) : std::max(frame.error[i], 0.0f);
    float top = 0;
    if (view == PreviewView::Samples) {
      for (float v : value) top = std::max(top, v);
    } else {
      std::vector<float> sorted = value;
      auto at = sorted.begin() + std::ptrdiff_t(std::min(n - 1, std::size_t(0.99 * double(n))));
      std::nth_element(sorted.begin(), at, sorted.end());
      top = *at;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const uint8_t g = top > 0 ? srgb8(std::min(value[i] / top, 1.0f)) : 0;
      encoded[3 * i] = encoded[3 * i + 1] = encoded[3 * i + 2] = g;
    }
  }
  return encode_png(frame.width, frame.height, encoded, kPreviewZlibLevel);
}

namespace {

// A JSON string's text: quotes, backslashes and control characters escaped.
std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\')
      out += '\\', out += char(c);
    else if (c < 0x20)
      out += fmt::format("\\u{:04x}", unsigned(c));
    else
      out += char(c);
  }
  return out + "\"";
}

std::string json_number(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : "null"; }
std::string json_number(const std::optional<double>& v) { return v ? json_number(*v) : "null"; }

}  // namespace

std::string preview_status_json(const LiveImage::Status& s) {
  return fmt::format(
      "{{\"scene\": {}, \"render\": {}, \"state\": \"{}\", \"frame\": {}, \"width\": {}, \"height\": {}, \"spp\": {}, "
      "\"samples_per_pixel\": {}, \"progress\": {}, \"converged\": {}, \"elapsed\": {}, \"eta\": {}, \"error\": {}}}",
      json_string(s.scene), s.render, live_image_state_name(s.state), s.frame, s.width, s.height, s.spp,
      json_number(s.samples_per_pixel), json_number(s.progress), json_number(s.converged), json_number(s.elapsed),
      json_number(s.eta), s.error.empty() ? "null" : json_string(s.error));
}

struct PreviewServer::Impl {
  LiveImage& image;
  std::string address;
  httplib::Server server;
  std::thread thread;
  std::atomic<bool> listen_ended{false};
  int port = 0;

  // The CPU clocks of the threads that have served (PreviewServer::cost).
  mutable std::mutex cost_mutex;
  std::vector<clockid_t> serving_clocks;
  std::atomic<int64_t> requests{0};

  void count_this_thread() {
    thread_local const Impl* counted = nullptr;  // a pool thread serves one server
    if (counted == this) return;
    counted = this;
    if (const auto clock = this_thread_cpu_clock()) {
      std::lock_guard lock(cost_mutex);
      serving_clocks.push_back(*clock);
    }
  }

  // The last PNG sent of each view, kept while the image changes faster than
  // kPreviewEncodeInterval: one encoding at a time, whatever the number of clients.
  struct Encoded {
    std::string png;
    uint64_t frame = ~uint64_t(0);
    float exposure = 0;
    std::chrono::steady_clock::time_point at{};
    double seconds = 0;  // the encoding took
  };
  std::mutex encode_mutex;
  LiveImage::Frame frame;
  Encoded encoded[3];

  Impl(LiveImage& img, std::string addr) : image(img), address(std::move(addr)) {}

  std::string png(PreviewView view, float exposure) {
    std::lock_guard lock(encode_mutex);
    Encoded& e = encoded[int(view)];
    const auto now = std::chrono::steady_clock::now();
    const bool same_request = !e.png.empty() && e.exposure == exposure;
    // Asked again soon: the last PNG, though the image may have changed since (encoding
    // at every request of every client would take the render's time). Soon: within
    // kPreviewEncodeInterval, or as long as it takes for the last encoding to be
    // kPreviewEncodeShare of the time (a large image is refreshed less often).
    const double interval = std::max(kPreviewEncodeInterval, e.seconds / kPreviewEncodeShare);
    if (same_request && std::chrono::duration<double>(now - e.at).count() < interval) return e.png;
    image.frame_since(frame.frame, frame);
    if (same_request && e.frame == frame.frame) return e.png;  // nothing new
    e.png = preview_png(frame, view, exposure);
    e.frame = frame.frame;
    e.exposure = exposure;
    e.at = now;
    e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - now).count();  // the frame's copy too
    return e.png;
  }

  void routes() {
    server.Get("/", [](const httplib::Request&, httplib::Response& res) {
      res.set_content(kPreviewPageHtml, "text/html; charset=utf-8");
    });
    server.Get("/status.json", [this](const httplib::Request&, httplib::Response& res) {
      res.set_header("Cache-Control", "no-store");
      res.set_content(preview_status_json(image.status()), "application/json");
    });
    auto serve_png = [this](PreviewView view) {
      return [this, view](const httplib::Request& req, httplib::Response& res) {
        float exposure = 0;
        if (view == PreviewView::Image && req.has_param("exposure")) {
          // A number of stops; anything else is the client's mistake.
          const std::string text = req.get_param_value("exposure");
          char* end = nullptr;
          exposure = std::strtof(text.c_str(), &end);
          if (text.empty() || text.size() > 32 || end != text.c_str() + text.size() || !std::isfinite(exposure)) {
            res.status = 400;
            res.set_content("exposure: expected a number of stops, e.g. -1.5\n", "text/plain");
            return;
          }
          exposure = std::clamp(std::round(exposure * 100.0f) / 100.0f, -20.0f, 20.0f);
        }
        res.set_header("Cache-Control", "no-store");
        res.set_content(png(view, exposure), "image/png");
      };
    };
    server.Get(R"(/image\.png)", serve_png(PreviewView::Image));
    server.Get(R"(/samples\.png)", serve_png(PreviewView::Samples));
    server.Get(R"(/error\.png)", serve_png(PreviewView::Error));
    server.set_pre_routing_handler([this](const httplib::Request&, httplib::Response&) {
      ++requests;
      count_this_thread();
      return httplib::Server::HandlerResponse::Unhandled;
    });
    server.set_error_handler([](const httplib::Request&, httplib::Response& res) {
      if (res.status == 404)
        res.set_content(
            "not found: the preview serves /, /image.png, /samples.png, "
            "/error.png and /status.json\n",
            "text/plain");
    });
    server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
      res.status = 500;
      res.set_content("the preview could not answer\n", "text/plain");
    });
    // Bounded: a few threads (they compete with the render's), short timeouts, small requests.
    server.new_task_queue = [] { return new httplib::ThreadPool(8); };
    server.set_read_timeout(1, 0);
    server.set_write_timeout(5, 0);
    server.set_keep_alive_timeout(1);
    server.set_keep_alive_max_count(100);
    server.set_payload_max_length(4096);
    // SO_REUSEADDR alone: cpp-httplib's default adds SO_REUSEPORT, which would let a second
    // program bind the same port and take some of the connections (a port in use is an error).
    server.set_socket_options([](int sock) {
      int yes = 1;
      setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });
  }
};

PreviewServer::PreviewServer(LiveImage& image, const std::string& address, int port)
    : impl_(std::make_unique<Impl>(image, address)) {
  impl_->routes();
  if (port < 0 || port > 65535) throw std::runtime_error(fmt::format("--preview {}: not a port (0 to 65535)", port));
  const bool bound = port == 0 ? (impl_->port = impl_->server.bind_to_any_port(address)) > 0
                               : impl_->server.bind_to_port(address, port) && (impl_->port = port) > 0;
  if (!bound)
    throw std::runtime_error(
        fmt::format("the preview cannot listen on {}:{} ({}): another program may use the port, "
                    "or the address is not this machine's",
                    address, port, port == 0 ? "any free port" : "this port"));
  impl_->thread = std::thread([this] {
    impl_->count_this_thread();
    impl_->server.listen_after_bind();
    impl_->listen_ended = true;
  });
  // Serving before the constructor returns: Server::stop() does nothing to a server not yet
  // running, and the destructor would then wait for ever.
  while (!impl_->server.is_running() && !impl_->listen_ended) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

PreviewServer::~PreviewServer() {
  impl_->server.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

int PreviewServer::port() const { return impl_->port; }

PreviewServer::Cost PreviewServer::cost() const {
  Cost cost{impl_->requests.load(), 0};
  std::lock_guard lock(impl_->cost_mutex);
  for (clockid_t clock : impl_->serving_clocks)
    if (const int64_t ns = cpu_clock_ns(clock); ns > 0) cost.cpu_seconds += double(ns) * 1e-9;
  return cost;
}

std::string PreviewServer::url() const {
  const bool v6 = impl_->address.find(':') != std::string::npos;
  return fmt::format("http://{}{}{}:{}/", v6 ? "[" : "", impl_->address, v6 ? "]" : "", impl_->port);
}

}  // namespace dermis
