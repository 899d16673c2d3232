// dermis.render: the scene made renderable (assembly and preparation, kept between
// renders), the render loop without the GIL, progress and Ctrl-C.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <time.h>

#include <optional>

#include "bindings.h"
#include "dermis/preview/live_image.h"
#include "dermis/preview/preview_server.h"
#include "dermis/render/film.h"
#include "dermis/render/point_cloud_prepass.h"
#include "dermis/render/renderer.h"
#include "dermis/render/scene_assembly.h"
#include "dermis/render/scene_preparation.h"
#include "interruptible.h"
#include "scene.h"

namespace py = pybind11;

namespace dermis::python {

namespace {

py::handle g_render_interrupted;  // the exception class, created once by bind_render

double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Marks the scene busy for the duration of a render (changes from other threads are refused).
class BusyGuard {
 public:
  explicit BusyGuard(Scene& s) : s_(s) {
    if (s_.busy.exchange(true)) throw std::runtime_error("the scene is already being rendered (by another thread)");
  }
  ~BusyGuard() { s_.busy = false; }

 private:
  Scene& s_;
};

bool has_point_clouds(const SceneDesc& desc) {
  for (const MaterialDesc& m : desc.materials)
    if (m.type == MaterialDesc::Type::Subsurface && m.subsurface.method == SubsurfaceParams::Method::PointCloud)
      return true;
  return false;
}

// The render scene for these seed and sampler: the one kept, or a new one (assembly and
// preparation on a worker thread; Ctrl-C raises KeyboardInterrupt).
std::shared_ptr<RenderScene> prepared_scene(Scene& s, uint64_t seed, SamplerKind sampler) {
  // Only point clouds depend on the seed and sampler (their irradiance pre-pass).
  const bool depends = has_point_clouds(s.desc);
  if (s.prepared && (!depends || (s.prepared_seed == seed && s.prepared_sampler == sampler))) return s.prepared;
  s.prepared.reset();
  std::shared_ptr<RenderScene> built;
  Diagnostics diag;
  std::atomic<bool> cancel{false};
  LoadMonitor monitor;  // Ctrl-C stops the BVH build too
  monitor.cancel = &cancel;
  auto error = run_interruptible(
      [&] {
        built = assemble_scene(s.desc, diag, &monitor);
        PreparationOptions prep;
        prep.point_clouds.seed = seed;
        prep.point_clouds.sampler = sampler;
        prep.cancel = &cancel;
        const PreparationReport report = prepare_scene(*built, prep);
        diag.warnings.insert(diag.warnings.end(), report.point_clouds.warnings.begin(),
                             report.point_clouds.warnings.end());
      },
      cancel, nullptr);
  if (error) throw *error;
  for (const std::string& w : diag.warnings)
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 2) != 0) throw py::error_already_set();
  s.prepared = built;
  s.prepared_seed = seed;
  s.prepared_sampler = sampler;
  return built;
}

// preview=: False or None (none), True (a free port) or a port number.
std::optional<int> preview_port(const py::object& preview) {
  if (preview.is_none()) return std::nullopt;
  if (py::isinstance<py::bool_>(preview)) return preview.cast<bool>() ? std::optional<int>(0) : std::nullopt;
  const int port = preview.cast<int>();
  if (port < 0 || port > 65535) throw py::value_error(fmt::format("preview: a port is 0 to 65535, got {}", port));
  return port;
}

py::object render(Scene& s, std::optional<int> spp, std::optional<int64_t> seed, int threads, double time_limit,
                  std::optional<std::string> sampler, const py::object& progress, bool stats,
                  std::optional<double> noise_threshold, std::optional<int> min_spp, const py::object& preview,
                  std::optional<bool> spectral) {
  BusyGuard busy(s);
  RenderOptions opt;
  opt.spp = spp.value_or(s.desc.settings.spp);
  if (opt.spp <= 0) throw py::value_error(fmt::format("spp must be positive, got {}", opt.spp));
  if (seed && *seed < 0) throw py::value_error(fmt::format("seed must be >= 0, got {}", *seed));
  opt.seed = seed ? uint64_t(*seed) : uint64_t(s.desc.settings.seed);
  if (threads < 0) throw py::value_error(fmt::format("threads must be >= 0 (0: all cores), got {}", threads));
  opt.threads = threads;
  if (!(time_limit >= 0)) throw py::value_error(fmt::format("time_limit must be >= 0 seconds, got {}", time_limit));
  opt.time_limit = time_limit;
  opt.sampler = s.desc.settings.sampler;
  if (sampler && !parse_sampler_kind(*sampler, opt.sampler))
    throw py::value_error(fmt::format("sampler must be 'sobol' or 'independent', got '{}'", *sampler));
  opt.adaptive.noise_threshold = noise_threshold.value_or(s.desc.settings.noise_threshold);
  if (!(opt.adaptive.noise_threshold >= 0) || !std::isfinite(opt.adaptive.noise_threshold))
    throw py::value_error(fmt::format("noise_threshold must be >= 0 (0: off), got {}", opt.adaptive.noise_threshold));
  opt.adaptive.min_spp = min_spp.value_or(s.desc.settings.min_spp);
  if (opt.adaptive.min_spp < 0 || (min_spp && *min_spp <= 0))
    throw py::value_error(fmt::format("min_spp must be positive, got {}", opt.adaptive.min_spp));

  std::shared_ptr<RenderScene> scene = prepared_scene(s, opt.seed, opt.sampler);
  opt.spectral = spectral.value_or(s.desc.settings.spectral);
  std::string spectral_note;
  if (opt.spectral) {
    spectral_note = spectral_limitations(*scene);
    if (!spectral_note.empty() &&
        PyErr_WarnEx(PyExc_UserWarning, fmt::format("spectral: {}", spectral_note).c_str(), 1) < 0)
      throw py::error_already_set();
  }

  const PixelBounds px = film_pixel_bounds(scene->film);
  const int64_t total = int64_t(px.width()) * px.height() * opt.spp;
  std::atomic<int64_t> done{0};
  int64_t reported = -1;
  opt.progress = [&done](int64_t n) { done += n; };
  // The live preview (preview/preview_server.h) while this render runs, on loopback.
  std::optional<LiveImage> live;
  std::unique_ptr<PreviewServer> server;
  if (const std::optional<int> port = preview_port(preview)) {
    live.emplace("dermis.render");
    server = std::make_unique<PreviewServer>(*live, "127.0.0.1", *port);
    py::module_::import("sys").attr("stderr").attr("write")(fmt::format("preview: {}\n", server->url()));
    live->begin_render(px.width(), px.height(), opt.spp, total, scene->film.exposure_scale);
    opt.tile_rendered = [&live](const Film& film, int x0, int y0, int x1, int y1) {
      live->copy_tile(film, x0, y0, x1, y1);
    };
    opt.progress = [&done, &live](int64_t n) {
      done += n;
      live->add_samples(n);
    };
    if (opt.adaptive.enabled())
      opt.adaptive_progress = [&live](int64_t converged, int64_t pixels) {
        live->set_converged(double(converged) / double(pixels));
      };
  }
  std::atomic<bool> cancel{false};
  opt.cancel = &cancel;
  RenderResult r;
  const double cpu0 = process_cpu_seconds();
  auto poll = [&] {
    const int64_t d = std::min(done.load(), total);  // adaptive sampling may count a little over
    if (!progress.is_none() && d != reported) {
      reported = d;
      progress(d, total);
    }
  };
  auto error = run_interruptible([&] { r = render_image(*scene, opt); }, cancel, poll);
  const double cpu_seconds = process_cpu_seconds() - cpu0;
  if (live) live->finish(bool(error) || r.interrupted);
  if (!error && !progress.is_none() && reported != std::min(done.load(), total))
    progress(std::min(done.load(), total), total);

  py::array_t<float> image({py::ssize_t(r.height), py::ssize_t(r.width), py::ssize_t(3)});
  std::copy(r.rgb.begin(), r.rgb.end(), image.mutable_data());
  py::dict st;
  st["seconds"] = r.seconds;
  st["cpu_seconds"] = cpu_seconds;
  st["spp"] = opt.spp;
  st["seed"] = opt.seed;
  st["samples"] = r.samples;
  st["min_spp"] = r.min_spp;
  st["max_spp"] = r.max_spp;
  st["rays"] = r.rays;
  st["spectral"] = opt.spectral;
  st["nonfinite"] = r.nonfinite;
  st["truncated"] = r.truncated;
  st["interrupted"] = r.interrupted;
  st["time_limited"] = r.time_limited;
  st["noise_threshold"] = opt.adaptive.noise_threshold;
  py::array_t<uint32_t> counts({py::ssize_t(r.height), py::ssize_t(r.width)});
  std::copy(r.sample_counts.begin(), r.sample_counts.end(), counts.mutable_data());
  st["sample_counts"] = counts;
  py::array_t<float> rel_error({py::ssize_t(r.height), py::ssize_t(r.width)});
  std::copy(r.noise_error.begin(), r.noise_error.end(), rel_error.mutable_data());
  st["noise_error"] = rel_error;
  st["converged_pixels"] = r.converged_pixels;
  py::array_t<uint64_t> pixel_rays({py::ssize_t(r.height), py::ssize_t(r.width)});
  std::copy(r.pixel_rays.begin(), r.pixel_rays.end(), pixel_rays.mutable_data());
  st["pixel_rays"] = pixel_rays;
  py::list choices;
  for (const SubsurfaceChoice& c : r.subsurface_choices) {
    py::dict d;
    d["material"] = c.material;
    d["strategy"] = c.strategy;
    d["gain"] = c.gain;
    d["gain_se"] = c.gain_se;
    d["first_stage_only"] = c.first_stage_only;
    d["pixels"] = c.pixels;
    d["description"] = c.description;
    choices.append(d);
  }
  st["subsurface_choices"] = choices;
  if (server) st["preview_url"] = server->url();
  if (error) {
    if (!error->matches(PyExc_KeyboardInterrupt)) throw *error;
    py::object e = py::reinterpret_borrow<py::object>(g_render_interrupted)(
        fmt::format("render interrupted: the image holds the samples finished so far ({}..{} per pixel of {})",
                    r.min_spp, r.max_spp, opt.spp));
    e.attr("image") = image;
    e.attr("stats") = st;
    PyErr_SetObject(g_render_interrupted.ptr(), e.ptr());
    throw py::error_already_set();
  }
  if (stats) return py::make_tuple(image, st);
  return image;
}

}  // namespace

void bind_render(py::module_& m) {
  g_render_interrupted = PyErr_NewExceptionWithDoc(
      "dermis.RenderInterrupted",
      "Ctrl-C (KeyboardInterrupt) during render(): .image holds the partial image (every pixel with the samples "
      "finished so far) and .stats the render statistics.",
      PyExc_KeyboardInterrupt, nullptr);
  m.attr("RenderInterrupted") = py::reinterpret_borrow<py::object>(g_render_interrupted);
  m.def("render", &render, py::arg("scene"), py::kw_only(), py::arg("spp") = py::none(), py::arg("seed") = py::none(),
        py::arg("threads") = 0, py::arg("time_limit") = 0.0, py::arg("sampler") = py::none(),
        py::arg("progress") = py::none(), py::arg("stats") = false, py::arg("noise_threshold") = py::none(),
        py::arg("min_spp") = py::none(), py::arg("preview") = py::none(), py::arg("spectral") = py::none(),
        R"(Renders a scene; returns a float32 NumPy array (height, width, 3) of linear RGB.

spp: samples per pixel (default: scene.spp, the scene's Sampler).
seed: the random seed (default: scene.seed). The same seed gives the same image, whatever
  the number of threads.
threads: worker threads (0: all cores).
time_limit: stop after this many seconds (0: none), keeping the samples finished; the
  render takes samples in passes of 1, 1, 2, 4, ... 16 per pixel, so every pixel then has
  about the same number, and never stops before every pixel has one.
sampler: 'sobol' (Owen-scrambled Sobol') or 'independent' (default: the scene's).
progress: a callable progress(done, total) of pixel samples, called on this thread
  about every 50 ms and once at the end.
stats: also return a dict (image, stats): seconds (wall), cpu_seconds (this process),
  spp, seed, samples, min_spp, max_spp, rays, nonfinite (NaN/inf samples, dropped),
  truncated (paths cut short), interrupted, time_limited, noise_threshold,
  sample_counts (uint32 array (height, width)), noise_error (float32 array: each
  pixel's estimated error, the standard error over the square root of the value; inf
  with fewer than 2 samples), converged_pixels, pixel_rays (uint64 array: the rays each
  pixel traced), subsurface_choices (the render's subsurface pilot, one dict per
  random-walk material it measured: material, strategy, gain, gain_se, first_stage_only, pixels,
  description; docs/rendering.md "The subsurface pilot").
noise_threshold: adaptive sampling (default: the scene's Sampler "noisethreshold"; 0: off):
  pixels stop once their estimated error (the standard error over the square root of the
  value, as Cycles: 0.01 is 1% of white), and their neighbours', is below it;
  spp is then the most a pixel takes.
min_spp: with noise_threshold, the samples every pixel takes first (default: the
  scene's "minpixelsamples", else max(16, sqrt(spp)) rounded up to a multiple of 16).
preview: True (a free port) or a port number: while the render runs, a page at
  http://127.0.0.1:PORT/ shows the image as it converges (the URL is written to
  sys.stderr as "preview: URL", and given in stats as preview_url); it stops when render()
  returns. From a notebook: open the URL, or call render() in a thread (docs/preview.md).
spectral: spectral transport (default: the scene's Option "bool spectral"): each sample
  carries three wavelengths, the RGB inputs are read as spectra as pbrt-v4 reads them, and
  the image is the colour of the result (CIE 1931 to linear sRGB). A scene with subsurface
  materials or media has no spectral form yet: a UserWarning says so and it renders in RGB
  (stats["spectral"] says which; docs/rendering.md).
The GIL is released while rendering. Ctrl-C raises dermis.RenderInterrupted (a
KeyboardInterrupt) whose .image is the partial image. The scene's assembly and
preparation (BVH, albedo tables, point clouds) are kept for the next render until the
scene changes. Raises dermis.SceneError for materials a method cannot use.)");
}

}  // namespace dermis::python
