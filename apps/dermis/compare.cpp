// dermis compare A.exr B.exr [--diff OUT.exr]: error statistics of A (test)
// against B (reference), and optionally a false-colour difference image.
#include <fmt/format.h>

#include <cstdio>
#include <exception>
#include <string>

#include "commands.h"
#include "dermis/render/image.h"
#include "dermis/render/image_compare.h"

namespace dermis::app {

namespace {

struct CompareOptions {
  std::string test, reference, diff;
};

void print_row(const char* name, RGB v, double all) {
  fmt::print("{:<12}{:>13.6g}{:>13.6g}{:>13.6g}{:>13.6g}\n", name, v[0], v[1], v[2], all);
}

void print_table(const CompareOptions& opt, const ImageComparison& r) {
  fmt::print("A = {} (test)\nB = {} (reference)\n{}x{} pixels\n\n", opt.test, opt.reference, r.width, r.height);
  fmt::print("{:<12}{:>13}{:>13}{:>13}{:>13}\n", "", "R", "G", "B", "all");
  print_row("mean A", r.mean_a, r.mean_a.average());
  print_row("mean B", r.mean_b, r.mean_b.average());
  print_row("RMSE", r.rmse, r.rmse_all);
  print_row("relMSE", r.relative_mse, r.relative_mse_all);
  print_row("max |A-B|", r.max_abs_diff, r.max_abs_diff_all);
  fmt::print("\nrelMSE = mean of (A-B)^2 / (B^2 + {:g})\n", kRelativeMseEpsilon);
}

int run_compare(const CompareOptions& opt) {
  try {
    const Image a = read_image(opt.test);
    const Image b = read_image(opt.reference);
    const ImageComparison r = compare_images(a, b);
    print_table(opt, r);
    if (!opt.diff.empty()) {
      double scale = 0;
      write_image(opt.diff, difference_image(a, b, &scale));
      fmt::print("difference image: {} (luminance of |A-B|; top of the colour ramp = {:.6g})\n", opt.diff, scale);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fflush(stdout);
    fmt::print(stderr, "dermis compare: {}\n", e.what());
    return 2;
  }
}

}  // namespace

void register_compare(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<CompareOptions>();
  auto* cmd = app.add_subcommand("compare", "Compare two images: per-channel mean, RMSE, relative MSE");
  cmd->add_option("A", opt->test, "Test image (any format OpenImageIO reads)")->required();
  cmd->add_option("B", opt->reference, "Reference image")->required();
  cmd->add_option("--diff", opt->diff,
                  "Write a false-colour image of |A-B| (luminance, scaled to its 99th percentile); "
                  "format by extension: .exr .hdr .tif .png .jpg");
  cmd->callback([opt, &exit_code] { exit_code = run_compare(*opt); });
}

}  // namespace dermis::app
