// dermis render SCENE [--spp N] [--threads N] [--seed S] [--sampler sobol|independent] [-o OUT] [--res WxH] [--time-limit SEC]
#include <fmt/format.h>

#include <atomic>
#include <csignal>
#include <filesystem>

#include "commands.h"
#include "dermis/render/film.h"
#include "dermis/render/image.h"
#include "dermis/render/progress.h"
#include "dermis/render/scene_assembly.h"
#include "dermis/render/scene_preparation.h"
#include "dermis/render/renderer.h"
#include "dermis/scene/parser.h"

namespace dermis::app {

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_sigint(int) {
  g_interrupted = true;
  std::signal(SIGINT, SIG_DFL);  // a second Ctrl-C ends the program at once
}

struct RenderArgs {
  std::string scene;
  int spp = 0, threads = 0;
  int64_t seed = -1;
  std::string sampler;  // empty: the scene's Sampler
  std::string output, res;
  double time_limit = 0;
  bool quiet = false, no_png = false;
  int64_t points = 0;
  std::string save_pointcloud, load_pointcloud;
};

int run_render(const RenderArgs& a) {
  // One Ctrl-C handler from the start: preparation stops between stages, rendering
  // between tiles; a second Ctrl-C ends the program at once.
  g_interrupted = false;
  std::signal(SIGINT, on_sigint);
  SceneDesc desc;
  std::unique_ptr<RenderScene> scene;
  PreparationReport preparation;
  try {
    desc = parse_scene_file(a.scene);
    if (!a.res.empty()) {
      int w = 0, h = 0, consumed = 0;
      char x = 0;
      if (std::sscanf(a.res.c_str(), "%d%c%d%n", &w, &x, &h, &consumed) != 3 || consumed != int(a.res.size()) ||
          (x != 'x' && x != 'X') || w <= 0 || h <= 0 || w > 65536 || h > 65536)
        throw std::invalid_argument(fmt::format("--res {}: expected WIDTHxHEIGHT with positive integers, e.g. 640x480", a.res));
      desc.film.xres = w;
      desc.film.yres = h;
    }
    {
      // The film holds 3 doubles and a count per pixel: refuse what cannot be allocated.
      const PixelBounds px = film_pixel_bounds(desc.film);
      const double pixels = double(px.width()) * px.height(), gib = pixels * 28 / double(1ull << 30);
      if (pixels > double(1ull << 28))
        throw std::invalid_argument(fmt::format("{}: a film of {}x{} pixels is too large (it would need {:.0f} GiB); "
                                                "lower the Film's xresolution/yresolution or use --res",
                                                a.scene, px.width(), px.height(), gib));
    }
    if (a.spp > 0) desc.settings.spp = a.spp;
    if (!a.sampler.empty()) parse_sampler_kind(a.sampler, desc.settings.sampler);  // checked by CLI11
    for (const auto& w : desc.diagnostics.warnings) fmt::print(stderr, "{}\n", w);
    Diagnostics build_diag;
    PointCloudOptions pco;
    pco.points = std::size_t(a.points);
    pco.save_path = a.save_pointcloud;
    pco.load_path = a.load_pointcloud;
    pco.seed = a.seed >= 0 ? uint64_t(a.seed) : uint64_t(desc.settings.seed);
    pco.sampler = desc.settings.sampler;
    scene = assemble_scene(desc, build_diag);
    for (const auto& w : build_diag.warnings) fmt::print(stderr, "{}\n", w);
    PreparationOptions prep;
    prep.point_clouds = pco;
    prep.progress = a.quiet ? Progress::Style::kQuiet : Progress::Style::kAuto;
    prep.cancel = &g_interrupted;
    preparation = prepare_scene(*scene, prep);
  } catch (const Interrupted&) {
    fmt::print(stderr, "dermis render: interrupted while preparing the scene; nothing written\n");
    return 130;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "dermis render: {}: out of memory while loading or preparing the scene\n", a.scene);
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "dermis render: {}\n", e.what());
    return 2;
  }

  std::string out = a.output.empty() ? desc.film.filename : a.output;
  std::filesystem::path out_path(out);
  std::string ext = out_path.extension().string();
  for (char& c : ext) c = char(std::tolower(c));
  if (ext != ".exr" && ext != ".png" && ext != ".hdr" && ext != ".tif" && ext != ".tiff" && ext != ".jpg") {
    fmt::print(stderr, "dermis render: {}: unsupported output format '{}' (use .exr, .png, .hdr, .tif or .jpg)\n", out, ext);
    return 2;
  }
  if (out_path.has_parent_path() && !std::filesystem::is_directory(out_path.parent_path())) {
    fmt::print(stderr, "dermis render: {}: output directory '{}' does not exist\n", out, out_path.parent_path().string());
    return 2;
  }

  RenderOptions opt;
  opt.spp = desc.settings.spp;
  opt.threads = a.threads;
  opt.seed = a.seed >= 0 ? uint64_t(a.seed) : uint64_t(desc.settings.seed);
  opt.sampler = desc.settings.sampler;
  opt.time_limit = a.time_limit;
  opt.cancel = &g_interrupted;
  const PixelBounds pixels = film_pixel_bounds(scene->film);
  const int64_t total = int64_t(pixels.width()) * pixels.height() * opt.spp;
  Progress progress("Rendering", total, a.quiet ? Progress::Style::kQuiet : Progress::Style::kAuto);
  opt.progress = [&progress](int64_t n) { progress.advance(n); };

  if (!a.quiet)
    fmt::print(stderr, "dermis: {} — {}x{}, {} spp, {} shapes, {} lights\n", a.scene, scene->film.xres, scene->film.yres,
               opt.spp, scene->shapes.size(), scene->lights.size());
  RenderResult r = render_image(*scene, opt);  // stops at once if Ctrl-C came during preparation
  std::signal(SIGINT, SIG_DFL);
  progress.finish();

  Image img;
  img.width = r.width;
  img.height = r.height;
  img.pixels = std::move(r.rgb);
  try {
    write_image(out, img);
    if (ext == ".exr" && !a.no_png) write_image(out_path.replace_extension(".png").string(), img);
  } catch (const std::exception& e) {
    fmt::print(stderr, "dermis render: {}\n", e.what());
    return 2;
  }

  double mrays = r.seconds > 0 ? double(r.rays) / r.seconds * 1e-6 : 0;
  fmt::print(stderr, "dermis: wrote {}{} in {:.1f} s ({:.2f} Mrays/s, {} samples)\n", out,
             ext == ".exr" && !a.no_png ? " and its .png" : "", r.seconds, mrays, r.samples);
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
    fmt::print(stderr,
               "dermis: warning: {} paths were truncated (random-walk step cap or interface-crossing guard); their "
               "energy is missing from the image\n",
               r.truncated);
  if (r.interrupted) {
    fmt::print(stderr, "dermis: interrupted: the image holds the samples finished so far ({}..{} per pixel of {})\n",
               r.min_spp, r.max_spp, opt.spp);
    return 130;
  }
  if (r.time_limited)
    fmt::print(stderr, "dermis: time limit reached: {}..{} samples per pixel of {}\n", r.min_spp, r.max_spp, opt.spp);
  return 0;
}

}  // namespace

void register_render(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RenderArgs>();
  auto* cmd = app.add_subcommand("render", "Render a pbrt-v4 scene to EXR (and a PNG preview)");
  cmd->add_option("scene", args->scene, "pbrt-v4 scene file")->required();
  cmd->add_option("--spp", args->spp, "samples per pixel (default: the scene's Sampler pixelsamples)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--threads", args->threads, "worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--seed", args->seed, "random seed (default: the scene's, else 0)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--sampler", args->sampler,
                  "sobol (Owen-scrambled Sobol', the default) or independent (default: the scene's Sampler)")
      ->check(CLI::IsMember({"sobol", "independent"}));
  cmd->add_option("-o,--output", args->output, "output image (.exr, .png, ...; default: the Film's filename)");
  cmd->add_option("--res", args->res, "resolution WIDTHxHEIGHT, overriding the Film's");
  cmd->add_option("--time-limit", args->time_limit, "stop after this many seconds, keeping the samples taken")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("-q,--quiet", args->quiet, "no progress bar or summary");
  cmd->add_option("--points", args->points, "points per `pointcloud` subsurface object (default: from its pointdensity)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--save-pointcloud", args->save_pointcloud, "save the point cloud(s) of the pre-pass to this file");
  cmd->add_option("--load-pointcloud", args->load_pointcloud, "load the point cloud(s) instead of computing them")
      ->excludes("--save-pointcloud");
  cmd->add_flag("--no-png", args->no_png, "with an .exr output, do not also write a .png preview");
  cmd->callback([args, &exit_code] { exit_code = run_render(*args); });
}

}  // namespace dermis::app
