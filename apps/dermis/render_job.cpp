#include "render_job.h"

#include <fmt/format.h>
#include <oneapi/tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <thread>

#include "cli_checks.h"
#include "dermis/preview/live_image.h"
#include "dermis/preview/preview_server.h"
#include "dermis/render/checkpoint.h"
#include "dermis/render/film.h"
#include "dermis/render/image.h"
#include "dermis/render/progress.h"
#include "dermis/render/scene_assembly.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/scene/gzip_file.h"
#include "dermis/scene/parser.h"
#include "scene_watcher.h"

namespace dermis::app {

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_stop_signal(int signal) {
  g_interrupted = true;
  std::signal(signal, SIG_DFL);  // a second one ends the program at once
}

// A step's error on this process, if any. With a group every process learns whether
// any failed, and the message is printed once: by rank 0 if it failed, else by each
// process that did. Returns true when the job must stop (exit status 2).
bool failed_somewhere(ProcessGroup& group, const std::optional<std::string>& error) {
  int64_t state[2] = {error ? 1 : 0, error && group.is_root() ? 1 : 0};
  group.sum_all(state);
  if (error && (group.is_root() || state[1] == 0)) fmt::print(stderr, "{}\n", *error);
  return state[0] > 0;
}

// Loading's progress: a stage (a large mesh read, a BVH built) that is still running after half
// a second gets a progress bar or line; quick stages show nothing.
class LoadProgressDisplay {
 public:
  explicit LoadProgressDisplay(Progress::Style style) : style_(style) {}

  void operator()(const std::string& stage, double fraction) {
    const auto now = std::chrono::steady_clock::now();
    if (stage != stage_) {
      end_bar();
      stage_ = stage;
      started_ = now;
      bar_ = std::make_unique<Progress>(stage_, kSteps, style_);  // draws nothing until advanced
    }
    if (!shown_ && fraction < 1 && now - started_ > std::chrono::milliseconds(500)) shown_ = true;
    if (shown_) bar_->advance(int64_t(fraction * kSteps) - bar_->done());
    if (fraction >= 1) end_bar();
  }

 private:
  static constexpr int64_t kSteps = 1000;
  void end_bar() {
    if (bar_ && shown_) bar_->finish();
    bar_.reset();
    shown_ = false;
    stage_.clear();  // the same name again (another shape's file) is a new stage
  }

  Progress::Style style_;
  std::string stage_;
  std::chrono::steady_clock::time_point started_;
  std::unique_ptr<Progress> bar_;
  bool shown_ = false;
};

}  // namespace

void add_render_options(CLI::App& cmd, RenderArgs& args) {
  cmd.add_option("scene", args.scene, "pbrt-v4 scene file")->required();
  cmd.add_option("--spp", args.spp, "samples per pixel (default: the scene's Sampler pixelsamples)")->check(kPositive);
  cmd.add_option("--threads", args.threads, "worker threads (default: all cores)")->check(kNonNegative);
  cmd.add_option("--seed", args.seed, "random seed (default: the scene's, else 0)")->check(kNonNegative);
  cmd.add_option("--sampler", args.sampler,
                 "sobol (Owen-scrambled Sobol', the default) or independent (default: the scene's Sampler)")
      ->check(CLI::IsMember({"sobol", "independent"}));
  cmd.add_option("-o,--output", args.output, "output image (.exr, .png, ...; default: the Film's filename)");
  cmd.add_option("--res", args.res, "resolution WIDTHxHEIGHT, overriding the Film's");
  cmd.add_option("--time-limit", args.time_limit,
                 "stop after this many seconds (never before every pixel has a sample), keeping the samples taken")
      ->check(kNonNegative);
  cmd.add_option("--noise-threshold", args.noise_threshold,
                 "adaptive sampling: pixels stop once the estimated error of their value (the standard error over the "
                 "square root of the value, as Cycles: 0.01 is 1% of white), and of their neighbours', is below this "
                 "(e.g. 0.01; 0: off); --spp is then the most a pixel takes "
                 "(default: the scene's Sampler noisethreshold, else off)")
      ->check(kNonNegative);
  cmd.add_option("--min-spp", args.min_spp,
                 "with --noise-threshold, samples every pixel takes before any stops (default: the scene's Sampler "
                 "minpixelsamples, else max(16, sqrt(spp)) rounded up to a multiple of 16)")
      ->check(kPositive);
  cmd.add_option("--subsurface", args.subsurface,
                 "parameters for every subsurface material, as pbrt-v4 parameter text (e.g. '\"string method\" "
                 "\"disk\"'), or pbrt-v4: its photon-beam-diffusion profile, sampled by disk probes, the picture "
                 "pbrt-v4 gives the same file (docs/materials.md)");
  cmd.add_flag("--error-map", args.error_map,
               "write each pixel's sample count, estimated error and rays traced as the .exr's 'samples', 'error' and "
               "'rays' channels "
               "(or STEM-maps.exr beside another format), as --noise-threshold does");
  cmd.add_flag("-q,--quiet", args.quiet, "no progress bar or summary");
  cmd.add_option("--points", args.points,
                 "points per `pointcloud` subsurface object (default: chosen from the illumination, or its "
                 "pointdensity; up to its maxpoints)")
      ->check(kPositive);
  cmd.add_option("--save-pointcloud", args.save_pointcloud, "save the point cloud(s) of the pre-pass to this file");
  cmd.add_option("--load-pointcloud", args.load_pointcloud, "load the point cloud(s) instead of computing them")
      ->excludes("--save-pointcloud");
  cmd.add_flag("--no-png", args.no_png, "with an .exr output, do not also write a .png preview");
  cmd.add_flag("--spectral", args.spectral,
               "spectral transport: each sample carries three wavelengths and the RGB inputs are read as spectra, "
               "as pbrt-v4 does (also Option \"bool spectral\" true in the scene; docs/rendering.md)");
  cmd.add_option("--checkpoint", args.checkpoint,
                 "save the film state to this file every --checkpoint-interval seconds (between passes), on Ctrl-C "
                 "and at the end, for --resume");
  cmd.add_option("--checkpoint-interval", args.checkpoint_interval, "seconds between checkpoints (default 60)")
      ->check(CLI::PositiveNumber);
  cmd.add_option("--resume", args.resume,
                 "continue from a checkpoint of the same scene, seed, sampler and resolution (--spp may be larger): "
                 "the image is bit-identical to a render never stopped");
  cmd.add_flag("--confine", args.file_access.confined,
               "the scene may name only files inside its own directory (and --allow-path ones), after '..' and "
               "symbolic links: Include/Import, meshes, images, spectrum files, its Film filename "
               "(docs/robustness.md)");
  cmd.add_option("--allow-path", args.file_access.allowed_dirs,
                 "with --confine (implied), also allow files under this directory (repeatable)")
      ->allow_extra_args(false)
      ->check(CLI::ExistingDirectory);
  cmd.add_option("--preview", args.preview_port,
                 "serve a live preview of the render at http://127.0.0.1:PORT/ (no PORT or 0: a free port, printed "
                 "as 'preview: URL'); after the render it shows the image until Ctrl-C (docs/preview.md)")
      ->expected(0, 1)
      ->default_str("0")
      ->check(CLI::Range(0, 65535));
  cmd.add_option("--preview-bind", args.preview_bind,
                 "the address the preview listens on (default 127.0.0.1, this machine only; another address lets "
                 "other machines see the picture, with a warning)");
  cmd.add_flag("--watch", args.watch,
               "render again when the scene file, a file it includes or a mesh or image it names changes "
               "(until Ctrl-C); a scene that no longer loads keeps the last image");
}

namespace {

// After rendering: rank 0 writes the image and the summary; returns the exit status.
int write_and_report(const RenderArgs& a, const RenderJob& job, ProcessGroup& group, const std::string& out,
                     const std::string& ext, RenderResult& r, const PreparationReport& preparation,
                     const RenderOptions& opt);

// The command line's settings over the scene's: resolution, samples, sampler, the
// subsurface materials' parameters.
void apply_render_args(const RenderArgs& a, SceneDesc& desc) {
  if (!a.res.empty()) {
    int w = 0, h = 0, consumed = 0;
    char x = 0;
    if (std::sscanf(a.res.c_str(), "%d%c%d%n", &w, &x, &h, &consumed) != 3 || consumed != int(a.res.size()) ||
        (x != 'x' && x != 'X') || w <= 0 || h <= 0 || w > 65536 || h > 65536)
      throw std::invalid_argument(
          fmt::format("--res {}: expected WIDTHxHEIGHT with positive integers, e.g. 640x480", a.res));
    desc.film.xres = w;
    desc.film.yres = h;
  }
  {
    // The film's sums, squares and counts: refuse what cannot be allocated.
    const PixelBounds px = film_pixel_bounds(desc.film);
    const double pixels = double(px.width()) * px.height(),
                 gib = pixels * double(Film::kBytesPerPixel) / double(1ull << 30);
    if (pixels > double(1ull << 28))
      throw std::invalid_argument(
          fmt::format("{}: a film of {}x{} pixels is too large (it would need {:.0f} GiB); "
                      "lower the Film's xresolution/yresolution or use --res",
                      a.scene, px.width(), px.height(), gib));
  }
  if (a.spp > 0) desc.settings.spp = a.spp;
  if (a.noise_threshold >= 0) desc.settings.noise_threshold = a.noise_threshold;
  if (a.min_spp > 0) desc.settings.min_spp = a.min_spp;
  if (!a.sampler.empty()) parse_sampler_kind(a.sampler, desc.settings.sampler);  // checked by CLI11
  if (!a.subsurface.empty()) {
    const std::string text = a.subsurface == "pbrt-v4" ? kPbrtV4Subsurface : a.subsurface;
    for (std::size_t i = 0; i < desc.materials.size(); ++i)
      if (desc.materials[i].type == MaterialDesc::Type::Subsurface)
        for (auto& w : set_material_parameters(desc, i, text, "--subsurface"))
          desc.diagnostics.warnings.push_back(std::move(w));
  }
}

uint64_t render_seed(const RenderArgs& a, const SceneDesc& desc) {
  return a.seed >= 0 ? uint64_t(a.seed) : uint64_t(desc.settings.seed);
}

// Reading and assembling (each process alone); the warnings printed by rank 0. Returns
// the error, if any.
std::optional<std::string> load_scene(const RenderArgs& a, const std::string& program, bool root, LoadMonitor& load,
                                      SceneDesc& desc, std::unique_ptr<RenderScene>& scene) {
  try {
    desc = parse_scene_file(a.scene, a.file_access, &load);
    apply_render_args(a, desc);
    if (root)
      for (const auto& w : desc.diagnostics.warnings) fmt::print(stderr, "{}\n", w);
    Diagnostics build_diag;
    scene = assemble_scene(desc, build_diag, &load);
    if (root)
      for (const auto& w : build_diag.warnings) fmt::print(stderr, "{}\n", w);
  } catch (const Interrupted&) {
    return fmt::format("{}: interrupted while loading the scene; nothing written", program);
  } catch (const std::bad_alloc&) {
    return fmt::format("{}: {}: out of memory while loading or preparing the scene", program, a.scene);
  } catch (const std::exception& e) {
    return fmt::format("{}: {}", program, e.what());
  }
  return std::nullopt;
}

// The output's format and place, checked before rendering (rank 0): failing at the write
// would waste the render, or leave an .exr without its preview.
std::optional<std::string> check_output(const RenderArgs& a, const std::string& program, const std::string& out,
                                        const std::string& ext) {
  const std::filesystem::path out_path(out);
  if (ext != ".exr" && ext != ".png" && ext != ".hdr" && ext != ".tif" && ext != ".tiff" && ext != ".jpg")
    return fmt::format("{}: {}: unsupported output format '{}' (use .exr, .png, .hdr, .tif or .jpg)", program, out,
                       ext);
  if (out_path.has_parent_path() && !std::filesystem::is_directory(out_path.parent_path()))
    return fmt::format("{}: {}: output directory '{}' does not exist", program, out, out_path.parent_path().string());
  if (const auto png = std::filesystem::path(out).replace_extension(".png");
      std::filesystem::is_directory(out_path) || (ext == ".exr" && !a.no_png && std::filesystem::is_directory(png)))
    return fmt::format("{}: {}: the output {} is a directory", program, out,
                       std::filesystem::is_directory(out_path) ? "path" : fmt::format("preview '{}'", png.string()));
  return std::nullopt;
}

// Checkpoints: the film state, with what it must match to be resumed; the film of
// --resume read. Returns the error, if any.
std::optional<std::string> open_checkpoints(const RenderArgs& a, const std::string& program, const ProcessGroup& group,
                                            const SceneDesc& desc, const RenderScene& scene, CheckpointKey& key,
                                            std::optional<Film>& resumed) {
  if (a.checkpoint.empty() && a.resume.empty()) return std::nullopt;
  try {
    if (group.size() > 1)
      throw std::invalid_argument("--checkpoint and --resume work with one process only (not with dermis-mpi yet)");
    key.scene_hash = kFingerprintOfNothing;  // the scene's text, hashed a chunk at a time (never held whole)
    FileChunks scene_text(a.scene);
    for (std::string_view c = scene_text.next(); !c.empty(); c = scene_text.next())
      key.scene_hash = fingerprint(c, key.scene_hash);
    key.seed = render_seed(a, desc);
    key.sampler = desc.settings.sampler;
    key.full_width = scene.film.xres;
    key.full_height = scene.film.yres;
    key.pixels = film_pixel_bounds(scene.film);
    if (!a.resume.empty()) resumed = read_checkpoint(a.resume, key);
  } catch (const std::exception& e) {
    return fmt::format("{}: {}", program, e.what());
  }
  return std::nullopt;
}

RenderOptions render_options(const RenderArgs& a, const RenderJob& job, const SceneDesc& desc, ProcessGroup& group) {
  RenderOptions opt;
  opt.spp = desc.settings.spp;
  opt.threads = a.threads;
  opt.seed = render_seed(a, desc);
  opt.sampler = desc.settings.sampler;
  opt.spectral = a.spectral || desc.settings.spectral;
  opt.time_limit = a.time_limit;
  opt.adaptive.noise_threshold = desc.settings.noise_threshold;
  opt.adaptive.min_spp = desc.settings.min_spp;
  opt.cancel = &g_interrupted;
  opt.group = &group;
  opt.tile_assignment = job.tile_assignment;
  return opt;
}

// The line that opens a render: the scene, its size, the samples, what it holds.
void print_render_header(const RenderArgs& a, const RenderScene& scene, const RenderOptions& opt,
                         const ProcessGroup& group) {
  fmt::print(
      stderr, "dermis: {} — {}x{}, {}{} spp{}, {} shapes, {} lights{}\n", a.scene, scene.film.xres, scene.film.yres,
      opt.adaptive.enabled() ? "at most " : "", opt.spp,
      opt.adaptive.enabled()
          ? fmt::format(" (noise threshold {:g}, at least {})", opt.adaptive.noise_threshold,
                        opt.adaptive.min_spp > 0 ? std::min(opt.adaptive.min_spp, opt.spp) : default_min_spp(opt.spp))
          : "",
      scene.shapes.size(), scene.lights.size(), group.size() > 1 ? fmt::format(", {} processes", group.size()) : "");
}

// --spectral: a warning for what the scene does in RGB inside it (spectral_limitations);
// false (refused) with checkpoints, which hold RGB films.
bool settle_spectral(const RenderArgs& a, const RenderScene& scene, const std::string& program, bool root,
                     const RenderOptions& opt) {
  if (!opt.spectral) return true;
  if (!a.checkpoint.empty() || !a.resume.empty()) {
    if (root) fmt::print(stderr, "{}: --spectral does not work with --checkpoint or --resume yet\n", program);
    return false;
  }
  if (const std::string what = spectral_limitations(scene); !what.empty() && root)
    fmt::print(stderr, "{}: warning: --spectral: {}\n", program, what);
  return true;
}

// What a live render (--preview, --watch) adds to one render of the scene.
struct LiveRender {
  LiveImage* image = nullptr;                 // the preview's picture, if any
  const std::atomic<bool>* cancel = nullptr;  // stops the render (else the stop signals do)
  // Told the files the scene read (the main file first), whether or not it loaded.
  std::function<void(const std::vector<std::string>&)> scene_read;
  // The render was stopped to begin again: nothing is written.
  std::function<bool()> restarting;
};
// render_once's status when it was stopped to begin again.
constexpr int kRestarting = -1;

// Loads, prepares, renders and writes the scene once; returns the exit status (or kRestarting).
int render_once(const RenderArgs& args, const RenderJob& job, const LiveRender& live) {
  RenderArgs a = args;
  std::vector<std::string> named_files;
  if (live.scene_read) {
    named_files.push_back(std::filesystem::absolute(a.scene).string());
    a.file_access.named_files = &named_files;
  }
  ProcessGroup& group = job.group ? *job.group : single_process();
  const bool root = group.is_root();
  const bool quiet = a.quiet || !root;  // one progress bar and summary: rank 0's
  const Progress::Style progress_style = quiet ? Progress::Style::kQuiet : Progress::Style::kAuto;
  const std::string& program = job.program;
  // One stop handler from the start: preparation stops between stages, rendering
  // between tiles; a second signal ends the program at once.
  const std::vector<int> stop_signals = job.stop_signals.empty() ? std::vector<int>{SIGINT} : job.stop_signals;
  g_interrupted = false;
  for (int s : stop_signals) std::signal(s, on_stop_signal);
  // --threads bounds every stage, not only the render: the BVH build (Embree), the albedo
  // tables and the point-cloud pre-pass all run on TBB's pool.
  std::optional<tbb::global_control> thread_limit;
  if (a.threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(a.threads));

  SceneDesc desc;
  std::unique_ptr<RenderScene> scene;
  LoadMonitor load;
  load.cancel = &g_interrupted;
  if (progress_style != Progress::Style::kQuiet)
    load.progress = [display = std::make_shared<LoadProgressDisplay>(progress_style)](
                        const std::string& stage, double fraction) { (*display)(stage, fraction); };
  std::optional<std::string> error = load_scene(a, program, root, load, desc, scene);
  load.progress = nullptr;  // its display is not drawn to after this point
  if (live.scene_read) live.scene_read(named_files);
  // A step's failure: shown on the preview's page too.
  auto failed = [&](const std::optional<std::string>& e) {
    if (e && live.image) live.image->fail(*e);
    return failed_somewhere(group, e);
  };
  if (failed(error)) return g_interrupted ? 130 : 2;

  // Preparing: together (the group shares the tables and the point clouds).
  PreparationReport preparation;
  try {
    PreparationOptions prep;
    prep.point_clouds.points = std::size_t(a.points);
    prep.point_clouds.save_path = a.save_pointcloud;
    prep.point_clouds.load_path = a.load_pointcloud;
    prep.point_clouds.seed = render_seed(a, desc);
    prep.point_clouds.sampler = desc.settings.sampler;
    prep.progress = progress_style;
    prep.cancel = &g_interrupted;
    prep.group = &group;
    preparation = prepare_scene(*scene, prep);
    if (root)
      for (const std::string& w : preparation.point_clouds.warnings) fmt::print(stderr, "{}\n", w);
    if (root && progress_style != Progress::Style::kQuiet)
      for (const std::string& n : preparation.point_clouds.notes) fmt::print(stderr, "{}\n", n);
  } catch (const Interrupted&) {
    if (root) fmt::print(stderr, "{}: interrupted while preparing the scene; nothing written\n", program);
    return 130;
  } catch (const std::bad_alloc&) {
    error = fmt::format("{}: {}: out of memory while loading or preparing the scene", program, a.scene);
  } catch (const std::exception& e) {
    error = fmt::format("{}: {}", program, e.what());
  }
  // A process that failed while preparing cannot rejoin the others: they may be waiting in
  // one of the preparation's exchanges (table or point-cloud shares), not in the agreement
  // below, and would wait for ever. With more than one process the job stops here.
  if (error && group.size() > 1) throw RankCannotContinue(*error);
  if (failed(error)) return 2;

  // The output: rank 0 writes it.
  const std::string out = a.output.empty() ? desc.film.filename : a.output;
  std::string ext = std::filesystem::path(out).extension().string();
  for (char& c : ext) c = char(std::tolower(c));
  if (root) error = check_output(a, program, out, ext);
  if (failed(error)) return 2;

  std::optional<Film> resumed;
  CheckpointKey key;
  error = open_checkpoints(a, program, group, desc, *scene, key, resumed);
  if (failed(error)) return 2;

  RenderOptions opt = render_options(a, job, desc, group);
  if (!settle_spectral(a, *scene, program, root, opt)) return 2;
  const PixelBounds pixels = film_pixel_bounds(scene->film);
  const int64_t total = int64_t(pixels.width()) * pixels.height() * opt.spp;
  Progress progress("Rendering", total, progress_style);
  opt.progress = [&progress](int64_t n) { progress.advance(n); };
  if (opt.adaptive.enabled())
    opt.adaptive_progress = [&progress](int64_t converged, int64_t pixels) {
      progress.set_note(fmt::format("{:.1f}% of pixels converged", 100.0 * double(converged) / double(pixels)));
    };
  if (resumed) {
    opt.resume = &*resumed;
    int64_t had = 0;
    for (uint32_t s : resumed->samples) had += std::min<int64_t>(s, opt.spp);
    progress.advance(had);
  }
  bool checkpoint_failed = false;
  if (!a.checkpoint.empty()) {
    opt.checkpoint_interval = a.checkpoint_interval;
    opt.checkpoint = [&](const Film& film) {
      try {
        write_checkpoint(a.checkpoint, key, film);
      } catch (const std::exception& e) {
        if (!checkpoint_failed) fmt::print(stderr, "\n{}: warning: {}\n", program, e.what());
        checkpoint_failed = true;  // said once; rendering goes on
      }
    };
  }

  if (live.image) {
    live.image->begin_render(pixels.width(), pixels.height(), opt.spp, total, scene->film.exposure_scale);
    opt.tile_rendered = [&live](const Film& film, int x0, int y0, int x1, int y1) {
      live.image->copy_tile(film, x0, y0, x1, y1);
    };
    opt.progress = [&progress, &live](int64_t n) {
      progress.advance(n);
      live.image->add_samples(n);
    };
    if (opt.adaptive.enabled())
      opt.adaptive_progress = [&progress, &live](int64_t converged, int64_t pixels) {
        progress.set_note(fmt::format("{:.1f}% of pixels converged", 100.0 * double(converged) / double(pixels)));
        live.image->set_converged(double(converged) / double(pixels));
      };
  }
  if (live.cancel) opt.cancel = live.cancel;

  if (!quiet) print_render_header(a, *scene, opt, group);
  RenderResult r = render_image(*scene, opt);  // stops at once if a stop signal came during preparation
  // A live render keeps its stop handler: Ctrl-C right after the render (the page showing
  // it done) ends the preview, not the program in the middle of writing (run_render).
  if (!live.image && !live.cancel)
    for (int s : stop_signals) std::signal(s, SIG_DFL);
  progress.finish();
  if (live.image) live.image->finish(r.interrupted);
  if (live.restarting && live.restarting()) return kRestarting;
  // Rank 0 holds the image. The others wait until it is written (mpirun ends the job
  // as soon as one rank exits with a non-zero status) and exit with its status.
  int64_t status = root ? write_and_report(a, job, group, out, ext, r, preparation, opt) : 0;
  group.sum_all(std::span<int64_t>(&status, 1));
  return int(status);
}

bool is_loopback(const std::string& address) {
  return address == "localhost" || address == "::1" || address.rfind("127.", 0) == 0;
}

// Until a stop signal, or the watcher saw a change.
void wait_for_stop_or_change(const std::vector<int>& stop_signals, const SceneWatcher* watcher) {
  for (int s : stop_signals) std::signal(s, on_stop_signal);
  while (!g_interrupted && !(watcher && watcher->changed())) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  for (int s : stop_signals) std::signal(s, SIG_DFL);
}

}  // namespace

int run_render(const RenderArgs& a, const RenderJob& job) {
  if (a.preview_port < 0 && !a.watch) return render_once(a, job, {});
  const std::string& program = job.program;
  if (job.group && job.group->size() > 1) {
    if (job.group->is_root()) fmt::print(stderr, "{}: --preview and --watch work with one process only\n", program);
    return 2;
  }
  const std::vector<int> stop_signals = job.stop_signals.empty() ? std::vector<int>{SIGINT} : job.stop_signals;
  std::optional<LiveImage> image;
  std::unique_ptr<PreviewServer> server;
  if (a.preview_port >= 0) {
    image.emplace(a.scene);
    try {
      server = std::make_unique<PreviewServer>(*image, a.preview_bind, a.preview_port);
    } catch (const std::exception& e) {
      fmt::print(stderr, "{}: {}\n", program, e.what());
      return 2;
    }
    std::signal(SIGPIPE, SIG_IGN);  // a client gone mid-answer is the server's error to handle, not the end
    if (!is_loopback(a.preview_bind))
      fmt::print(stderr,
                 "{}: warning: the preview listens on {}: anyone who can reach this machine there can see the "
                 "picture (the default, 127.0.0.1, is this machine only)\n",
                 program, a.preview_bind);
    fmt::print(stderr, "preview: {}\n", server->url());
    std::fflush(stderr);
  }
  std::atomic<bool> cancel{false};
  std::optional<SceneWatcher> watcher;
  if (a.watch) watcher.emplace(g_interrupted, cancel);
  LiveRender live;
  live.image = image ? &*image : nullptr;
  if (watcher) {
    live.cancel = &cancel;
    live.scene_read = [&watcher](const std::vector<std::string>& files) { watcher->watch(files); };
    live.restarting = [&watcher] { return watcher->changed(); };
  }
  for (;;) {
    if (image) image->begin_loading();
    const int status = render_once(a, job, live);
    if (status == kRestarting || (watcher && watcher->changed() && !g_interrupted)) {
      if (!a.quiet) fmt::print(stderr, "dermis: {} changed: rendering it again\n", a.scene);
      continue;
    }
    if (status == 0 && server && !a.quiet) {
      // Measured on the threads that pay it (bench/preview_overhead.py divides it by the render's).
      const PreviewServer::Cost cost = server->cost();
      fmt::print(stderr,
                 "dermis: the preview so far: {} requests answered in {:.3f} CPU s; {:.3f} CPU s copying tiles\n",
                 cost.requests, cost.cpu_seconds, image->copy_cpu_seconds());
    }
    if (status == 130 || g_interrupted) return status;
    // The last picture stays on the page: without --watch until a stop signal (a scene that
    // did not load ends at once), with it until a stop signal or a change.
    if (!watcher && (status != 0 || !server)) return status;
    if (!a.quiet)
      fmt::print(
          stderr, "dermis: {}; Ctrl-C ends{}\n",
          watcher ? "watching the scene's files" : fmt::format("the preview shows the image at {}", server->url()),
          server && watcher ? " (the preview follows)" : "");
    wait_for_stop_or_change(stop_signals, watcher ? &*watcher : nullptr);
    if (g_interrupted) return status;
    if (!a.quiet) fmt::print(stderr, "dermis: {} changed: rendering it again\n", a.scene);
  }
}

namespace {

int write_and_report(const RenderArgs& a, const RenderJob& job, ProcessGroup& group, const std::string& out,
                     const std::string& ext, RenderResult& r, const PreparationReport& preparation,
                     const RenderOptions& opt) {
  const std::string& program = job.program;
  const int spp = opt.spp;
  std::filesystem::path out_path(out);
  Image img;
  img.width = r.width;
  img.height = r.height;
  img.pixels = std::move(r.rgb);
  // Adaptive sampling's maps: channels of the .exr, or beside another format in STEM-maps.exr.
  std::string maps_path;
  if (opt.adaptive.enabled() || a.error_map) {
    img.extra_channels.push_back({"samples", std::vector<float>(r.sample_counts.begin(), r.sample_counts.end())});
    std::vector<float> error = r.noise_error;
    for (float& e : error)
      if (!std::isfinite(e)) e = -1;  // unknown: fewer than 2 samples
    img.extra_channels.push_back({"error", std::move(error)});
    img.extra_channels.push_back({"rays", std::vector<float>(r.pixel_rays.begin(), r.pixel_rays.end())});
    if (ext != ".exr") maps_path = (out_path.parent_path() / (out_path.stem().string() + "-maps.exr")).string();
  }
  try {
    write_image(out, img);
    if (!maps_path.empty()) write_image(maps_path, img);
    img.extra_channels.clear();
    if (ext == ".exr" && !a.no_png) write_image(std::filesystem::path(out).replace_extension(".png").string(), img);
  } catch (const std::exception& e) {
    fmt::print(stderr, "{}: {}\n", program, e.what());
    return 2;
  }

  double mrays = r.seconds > 0 ? double(r.rays) / r.seconds * 1e-6 : 0;
  if (!(a.quiet && a.preview_port >= 0))  // with the preview, -q leaves the URL and the errors alone
    fmt::print(stderr, "dermis: wrote {}{}{} in {:.3f} s ({:.2f} Mrays/s, {} samples)\n", out,
               ext == ".exr" && !a.no_png ? " and its .png" : "", maps_path.empty() ? "" : " and " + maps_path,
               r.seconds, mrays, r.samples);
  if (!r.subsurface_choices.empty() && !a.quiet) {
    fmt::print(
        stderr,
        "dermis: subsurface pilot ({:.3f} s of the render; Integrator \"bool subsurfacepilot\" false turns it off):\n",
        r.pilot_seconds);
    for (const SubsurfaceChoice& c : r.subsurface_choices) fmt::print(stderr, "  {}\n", c.description);
  }
  if (opt.adaptive.enabled() && !a.quiet) {
    const double pixels = double(r.sample_counts.size());
    fmt::print(stderr,
               "dermis: adaptive sampling: {:.1f}% of pixels converged (with their neighbours, at or below the noise "
               "threshold {:g}); {}..{} samples per pixel, {:.1f} on average (the .exr's 'samples', 'error' and 'rays' "
               "channels)\n",
               100.0 * double(r.converged_pixels) / pixels, opt.adaptive.noise_threshold, r.min_spp, r.max_spp,
               double(r.samples) / pixels);
  }
  if (group.size() > 1 && !a.quiet) {
    // The load balance: each process's time rendering its tiles, waits excluded.
    std::string times;
    double longest = 0, sum = 0;
    for (double s : r.process_seconds) {
      times += fmt::format("{}{:.2f}", times.empty() ? "" : " ", s);
      longest = std::max(longest, s), sum += s;
    }
    fmt::print(stderr, "dermis: {} processes rendered for {} s (imbalance max/mean {:.2f})\n", group.size(), times,
               sum > 0 ? longest * double(r.process_seconds.size()) / sum : 1.0);
  }
  if (const PointCloudReport& pc = preparation.point_clouds; pc.clouds > 0 && !a.quiet)
    fmt::print(stderr,
               "dermis: point clouds: {} points in {} object(s), {:.1f} MiB in memory{}, pre-pass {:.1f} s, octree "
               "build {:.2f} s, render {:.1f} s\n",
               pc.points, pc.clouds, double(pc.memory_bytes) / (1 << 20),
               pc.file_bytes ? fmt::format(", {:.1f} MiB on disk", double(pc.file_bytes) / (1 << 20)) : "",
               pc.prepass_seconds, pc.build_seconds, r.seconds);
  if (r.nonfinite > 0)
    fmt::print(stderr, "dermis: warning: {} samples were NaN or infinite; they were dropped (counted as zero)\n",
               r.nonfinite);
  if (r.truncated > 0)
    fmt::print(
        stderr,
        "dermis: warning: {} paths were truncated (random-walk step cap, interface-crossing guard or a grid medium's "
        "tracking cap); their "
        "energy is missing from the image\n",
        r.truncated);
  if (!a.checkpoint.empty() && !a.quiet)
    fmt::print(stderr, "dermis: checkpoint {} holds {}..{} samples per pixel (continue with --resume {})\n",
               a.checkpoint, r.min_spp, r.max_spp, a.checkpoint);
  if (r.interrupted) {
    fmt::print(stderr, "dermis: interrupted: the image holds the samples finished so far ({}..{} per pixel of {})\n",
               r.min_spp, r.max_spp, spp);
    return 130;
  }
  if (r.time_limited)
    fmt::print(stderr, "dermis: time limit reached: {}..{} samples per pixel of {}\n", r.min_spp, r.max_spp, spp);
  return 0;
}

}  // namespace

}  // namespace dermis::app
