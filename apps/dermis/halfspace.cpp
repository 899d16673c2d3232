// dermis halfspace: brute-force random walk in a semi-infinite medium (the ground
// truth of the diffusion profiles). Total albedo on stderr, R(r) as CSV.
#include "dermis/sss/halfspace/halfspace.h"

#include <fmt/format.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "commands.h"

namespace dermis::app {

namespace {

struct HalfspaceOptions {
  std::optional<double> albedo, sigma_a, sigma_s;
  double sigma_t = 1.0, g = 0.0, eta = 1.0, r_max = 16.0, r_min = 0.0, alpha = 0.0;
  std::string incidence = "normal", output, walk_sampling = "classical";
  double p_guided = 0.5;
  long long paths = 1000000, seed = 1, max_collisions = 10'000'000;
  int threads = 0, bins = 64;
  bool log_bins = false, per_entering = false;
};

int run_halfspace(const HalfspaceOptions& o) {
  sss::HalfspaceConfig c;
  if (o.albedo) {
    if (o.sigma_a || o.sigma_s)
      throw std::invalid_argument("give either --albedo (with --sigma-t) or --sigma-a and --sigma-s");
    c.albedo = *o.albedo;
    c.sigma_t = o.sigma_t;
  } else if (o.sigma_a && o.sigma_s) {
    if (!(*o.sigma_a >= 0 && *o.sigma_s >= 0)) throw std::invalid_argument("--sigma-a and --sigma-s must be >= 0");
    c.sigma_t = *o.sigma_a + *o.sigma_s;
    if (!(c.sigma_t > 0)) throw std::invalid_argument("--sigma-a + --sigma-s must be positive");
    c.albedo = *o.sigma_s / c.sigma_t;
  } else {
    throw std::invalid_argument("give --albedo A, or both --sigma-a and --sigma-s");
  }
  if (o.paths < 1) throw std::invalid_argument("--paths must be at least 1");
  if (o.seed < 0) throw std::invalid_argument("--seed must be >= 0");
  if (o.max_collisions < 1) throw std::invalid_argument("--max-collisions must be at least 1");
  if (o.threads < 0) throw std::invalid_argument("--threads must be >= 0 (0: all cores)");
  c.g = o.g;
  c.eta = o.eta;
  c.alpha_x = c.alpha_y = o.alpha;
  c.paths = uint64_t(o.paths);
  c.seed = uint64_t(o.seed);
  c.max_collisions = uint64_t(o.max_collisions);
  sss::parse_incidence(o.incidence, c.incidence, c.incidence_angle);
  c.sampling = sss::parse_walk_sampling(o.walk_sampling);
  c.p_guided = o.p_guided;
  c.bins = o.log_bins ? sss::RadialBins::logarithmic(o.r_min > 0 ? o.r_min : o.r_max * 1e-3, o.r_max, o.bins)
                      : sss::RadialBins::linear(o.r_max, o.bins);
  sss::validate(c);

  std::unique_ptr<tbb::global_control> limit;
  if (o.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
  const sss::HalfspaceResult r = sss::simulate_halfspace(c);

  const double scale = o.per_entering ? 1 / r.entered : 1.0;
  std::cerr << fmt::format("albedo {:.6f} +- {:.6f} (per unit incident power)\n", r.albedo, r.albedo_stderr);
  if (c.eta != 1.0)
    std::cerr << fmt::format("albedo per entering power {:.6f} +- {:.6f}; entry specular {:.6f}\n",
                             r.albedo_per_entering(), r.albedo_per_entering_stderr(), r.specular);
  if (r.lost > 0 || r.entered_stderr > 0)
    std::cerr << fmt::format("rough boundary: entered {:.6f} +- {:.6f}; specular +- {:.6f}; lost {:.6f} +- {:.6f}\n",
                             r.entered, r.entered_stderr, r.specular_stderr, r.lost, r.lost_stderr);
  std::cerr << fmt::format("absorbed {:.6f} +- {:.6f}; beyond r_max {:.6f}; truncated paths {} (weight {:.3g})\n",
                           r.absorbed, r.absorbed_stderr, r.beyond_rmax, r.truncated, r.truncated_weight);
  std::cerr << fmt::format("{} paths ({} sampling), {:.1f} collisions/path, {:.3f} s, {:.3g} paths/s\n", r.paths,
                           sss::walk_sampling_name(c.sampling), r.mean_collisions, r.seconds,
                           double(r.paths) / r.seconds);

  std::ofstream file;
  if (!o.output.empty()) {
    file.open(o.output);
    if (!file) throw std::invalid_argument("cannot write '" + o.output + "'");
  }
  std::ostream& out = o.output.empty() ? std::cout : file;
  out << "r_lo,r_hi,r_mid,R,R_stderr\n";
  for (size_t i = 0; i < r.R.size(); ++i)
    out << fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", r.r_lo[i], r.r_hi[i], 0.5 * (r.r_lo[i] + r.r_hi[i]),
                       r.R[i] * scale, r.R_stderr[i] * scale);
  return 0;
}

}  // namespace

void register_halfspace(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<HalfspaceOptions>();
  auto* cmd = app.add_subcommand(
      "halfspace", "Brute-force random walk in a semi-infinite medium: total albedo and radial profile R(r)");
  cmd->add_option("--albedo", opts->albedo, "Single-scattering albedo sigma_s/sigma_t in [0, 1]");
  cmd->add_option("--sigma-t", opts->sigma_t,
                  "Extinction coefficient with --albedo (default 1: lengths in mean free paths)");
  cmd->add_option("--sigma-a", opts->sigma_a, "Absorption coefficient (with --sigma-s, instead of --albedo)");
  cmd->add_option("--sigma-s", opts->sigma_s, "Scattering coefficient (with --sigma-a)");
  cmd->add_option("--g", opts->g, "Henyey-Greenstein anisotropy in (-1, 1)");
  cmd->add_option("--eta", opts->eta, "Relative index of refraction n_medium/n_outside (1: index-matched)");
  cmd->add_option("--alpha", opts->alpha,
                  "Trowbridge-Reitz alpha of a rough dielectric boundary (pbrt-v4: sqrt(roughness); 0: smooth)");
  cmd->add_option("--incidence", opts->incidence, "normal | diffuse | angle:DEG");
  cmd->add_option("--paths", opts->paths, "Number of paths");
  cmd->add_option("--seed", opts->seed, "Random seed");
  cmd->add_option("--threads", opts->threads, "Worker threads (0: all cores; the result does not depend on it)");
  cmd->add_option("--rmax", opts->r_max, "Outer radius of the profile bins");
  cmd->add_option("--rmin", opts->r_min, "First edge of log-spaced bins (default rmax/1000)");
  cmd->add_option("--bins", opts->bins, "Number of radial bins");
  cmd->add_flag("--log-bins", opts->log_bins, "Log-spaced bins");
  cmd->add_option("--walksampling", opts->walk_sampling,
                  "classical | dwivedi (zero-variance guiding) | mis (one-sample MIS of both)");
  cmd->add_option("--p-guided", opts->p_guided,
                  "Probability of the guided strategy with --walksampling mis, in [0, 1]");
  cmd->add_option("--max-collisions", opts->max_collisions, "Truncate (and report) paths after this many collisions");
  cmd->add_flag("--per-entering", opts->per_entering,
                "Normalise R(r) per unit power that entered (1 - specular when smooth)");
  cmd->add_option("-o,--output", opts->output, "CSV file for R(r) (default: stdout)");
  cmd->callback([opts, &exit_code] {
    try {
      exit_code = run_halfspace(*opts);
    } catch (const std::exception& e) {
      std::cerr << "dermis halfspace: " << e.what() << "\n";
      exit_code = 2;
    }
  });
}

}  // namespace dermis::app
