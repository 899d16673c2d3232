// dermis profile: the Christensen-Burley study (docs/profile-study.md). Brute-force
// reference profiles against Burley's, the Christensen-Burley fit, the dipole and a
// tabulated profile: CSVs and plots (--plot DIR) and a table of errors (--fit-error).
#include <fmt/format.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "commands.h"
#include "dermis/sss/study/profile_study.h"
#include "dermis/sss/study/study_models.h"

namespace dermis::app {

namespace {

struct ProfileCommandOptions {
  sss::ProfileStudyOptions study;
  std::string plot_dir;
  bool fit_error = false;
  long long paths = 400000, seed = 1;
  int threads = 0;
  std::string python = "/usr/bin/python3";
};

// " 12.34%" right-aligned in `width` characters, or "n/a" for NaN (an undefined measure).
std::string percent(double v, int width = 18) {
  return std::isnan(v) ? fmt::format(" {:>{}}", "n/a", width) : fmt::format(" {:>{}.2f}%", 100 * v, width - 1);
}

void print_error_table(const std::vector<sss::AlbedoStudy>& studies, std::ostream& out) {
  if (studies.empty()) return;
  const auto& labels = studies[0].model_labels;
  for (int k = 0; k < sss::kErrorMeasures; ++k) {
    const sss::ErrorMeasure m = sss::kStudyMeasures[k];
    out << fmt::format("\nrelative error, {} ({})\n", sss::error_measure_name(m),
                       m == sss::ErrorMeasure::Energy ? "all bins" : "r in [r_a, r_b]");
    out << fmt::format("{:>6} {:>14} {:>7} {:>7}", "A", "alpha", "r_a", "r_b");
    for (const auto& l : labels) out << fmt::format(" {:>18}", l);
    out << fmt::format(" {:>12}\n", "ref. noise");
    std::vector<double> sum(labels.size(), 0.0);
    double noise_sum = 0;
    for (const auto& s : studies) {
      out << fmt::format("{:>6.3g} {:>14.10f} {:>7.3g} {:>7.4g}", s.surface_albedo, s.single_scattering_albedo, s.r_a,
                         s.r_b);
      for (size_t j = 0; j < labels.size(); ++j) {
        out << percent(s.errors[j][k]);
        sum[j] += s.errors[j][k];
      }
      out << percent(s.noise[k], 12) << '\n';
      noise_sum += s.noise[k];
    }
    out << fmt::format("{:>38}", "mean over albedos");
    for (double v : sum) out << percent(v / studies.size());
    out << percent(noise_sum / studies.size(), 12) << '\n';
  }
}

int run_profile(ProfileCommandOptions& o) {
  if (o.plot_dir.empty() && !o.fit_error) throw std::invalid_argument("give --plot OUTDIR and/or --fit-error");
  if (o.paths < 0) throw std::invalid_argument("--paths must be positive");
  if (o.seed < 0) throw std::invalid_argument("--seed must be >= 0");
  if (o.threads < 0) throw std::invalid_argument("--threads must be >= 0 (0: all cores)");
  o.study.paths = uint64_t(o.paths);
  o.study.seed = uint64_t(o.seed);
  sss::validate(o.study);
  namespace fs = std::filesystem;
  if (!o.plot_dir.empty()) {
    std::error_code ec;
    fs::create_directories(o.plot_dir, ec);
    if (ec || !fs::is_directory(o.plot_dir))
      throw std::invalid_argument("--plot: cannot create the directory '" + o.plot_dir + "'");
  }

  std::unique_ptr<tbb::global_control> limit;
  if (o.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
  const auto start = std::chrono::steady_clock::now();
  const auto table = sss::study_profile_table(o.study.eta);
  std::vector<sss::AlbedoStudy> studies;
  for (double a : o.study.albedos) {
    studies.push_back(sss::study_albedo(a, o.study, table));
    const auto& s = studies.back();
    std::cerr << fmt::format(
        "A = {:.3g}: alpha = {:.10f}, simulated A = {:.5f} +- {:.5f} ({:.2g} beyond r_max), "
        "{} paths, {:.1f} s\n",
        a, s.single_scattering_albedo, s.simulated_albedo, s.simulated_albedo_stderr, s.beyond_rmax, s.paths,
        s.seconds);
    if (!o.plot_dir.empty()) {
      const fs::path file = fs::path(o.plot_dir) / fmt::format("profile_A{:.2f}.csv", a);
      std::ofstream out(file);
      if (!out) throw std::invalid_argument("cannot write '" + file.string() + "'");
      sss::write_profile_csv(s, out);
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cerr << fmt::format("study: {} albedos, {} paths each, eta {}, seed {}: {:.1f} s\n", studies.size(),
                           o.study.paths, o.study.eta, o.study.seed, seconds);
  if (o.fit_error) print_error_table(studies, std::cout);

  if (!o.plot_dir.empty()) {
    const fs::path errors = fs::path(o.plot_dir) / "errors.csv";
    std::ofstream out(errors);
    if (!out) throw std::invalid_argument("cannot write '" + errors.string() + "'");
    sss::write_error_csv(studies, out);
    out.close();
    const fs::path script = fs::path(DERMIS_SOURCE_DIR) / "scripts" / "plot_profiles.py";
    if (!fs::exists(o.python) || !fs::exists(script)) {
      std::cerr << "plots skipped: " << (fs::exists(o.python) ? script.string() : o.python)
                << " not found; the CSVs are in " << o.plot_dir << "\n";
      return 0;
    }
    const std::string cmd = fmt::format("'{}' '{}' '{}'", o.python, script.string(), o.plot_dir);
    const int rc = std::system(cmd.c_str());
    if (rc != 0)
      std::cerr << "plots skipped (the plotting script failed, e.g. matplotlib is missing: run "
                   "scripts/install-deps.sh); the CSVs are in "
                << o.plot_dir << "\n";
  }
  return 0;
}

}  // namespace

void register_profile(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ProfileCommandOptions>();
  auto* cmd = app.add_subcommand("profile",
                                 "Christensen-Burley study: brute-force reference profiles vs Burley, the C-B fit, "
                                 "the dipole and a tabulated profile (docs/profile-study.md)");
  cmd->add_option("--plot", o->plot_dir, "Write one CSV per albedo, errors.csv and PNG plots into this directory");
  cmd->add_flag("--fit-error", o->fit_error, "Print the relative errors of each model per albedo and on average");
  cmd->add_option("--paths", o->paths, "Reference paths per albedo (default 400000)");
  cmd->add_option("--seed", o->seed, "Random seed");
  cmd->add_option("--albedos", o->study.albedos, "Surface albedos in (0, 1), comma-separated")->delimiter(',');
  cmd->add_option("--eta", o->study.eta, "Relative index n_medium/n_outside (1: index-matched, the seed's set-up)");
  cmd->add_option("--bins", o->study.bins, "Log-spaced radial bins per albedo");
  cmd->add_option("--threads", o->threads, "Worker threads (0: all cores; results do not depend on it)");
  cmd->add_option("--python", o->python, "Python interpreter for the plots");
  cmd->callback([o, &exit_code] {
    try {
      exit_code = run_profile(*o);
    } catch (const std::exception& e) {
      std::cerr << "dermis profile: " << e.what() << "\n";
      exit_code = 2;
    }
  });
}

}  // namespace dermis::app
