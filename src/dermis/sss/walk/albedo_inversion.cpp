#include "dermis/sss/walk/albedo_inversion.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "dermis/core/cache_dir.h"
#include "dermis/core/microfacet.h"
#include "dermis/source_hashes.h"  // generated (cmake/source_hashes.cmake)
#include "dermis/sss/halfspace/halfspace.h"

namespace dermis::sss {

namespace {

// 2: tables of rough boundaries (their alphas in the file name) exist.
constexpr int kCacheVersion = 2;

// Weighted pool-adjacent-violators: the non-increasing sequence closest to y in the
// weighted least-squares sense (Barlow et al. 1972, Statistical Inference under Order
// Restrictions). Removes the Monte Carlo noise that could make A(t) non-monotone.
std::vector<double> non_increasing_fit(const std::vector<double>& y, const std::vector<double>& w) {
  struct Block {
    double sum_wy, sum_w;
    size_t count;
  };
  std::vector<Block> blocks;
  for (size_t i = 0; i < y.size(); ++i) {
    blocks.push_back({w[i] * y[i], w[i], 1});
    while (blocks.size() > 1) {
      const Block& b = blocks.back();
      const Block& a = blocks[blocks.size() - 2];
      if (a.sum_wy / a.sum_w >= b.sum_wy / b.sum_w) break;  // in order
      Block merged{a.sum_wy + b.sum_wy, a.sum_w + b.sum_w, a.count + b.count};
      blocks.pop_back();
      blocks.back() = merged;
    }
  }
  std::vector<double> out;
  for (const Block& b : blocks) out.insert(out.end(), b.count, b.sum_wy / b.sum_w);
  return out;
}

// A rough dielectric boundary whose exits lose energy (the single-scattering microfacet
// model's loss at each hit from inside): then A < 1 at alpha = 1.
bool exits_lose_energy(const AlbedoTableConfig& config) {
  return !config.exit_matched && config.eta != 1.0 && std::max(config.alpha_x, config.alpha_y) >= double(kSmoothAlpha);
}

}  // namespace

AlbedoInversion::AlbedoInversion(const AlbedoTableConfig& config) : config_(config) {
  init_nodes();
  if (!cache_path_.empty() && load()) {
    from_cache_ = true;
  } else {
    const auto start = std::chrono::steady_clock::now();
    build();
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!cache_path_.empty() && build_seconds_ >= config.cache_min_seconds) save();
  }
  init_slopes();
}

AlbedoInversion::AlbedoInversion(const AlbedoTableConfig& config, const std::vector<AlbedoNode>& nodes, bool fitted)
    : config_(config) {
  init_nodes();
  if (int(nodes.size()) != config.size)
    throw std::invalid_argument(
        fmt::format("albedo inversion: {} nodes given for a table of {}", nodes.size(), config.size));
  if (fitted) {
    albedo_.clear(), stderr_.clear();
    for (const AlbedoNode& node : nodes) albedo_.push_back(node.albedo), stderr_.push_back(node.error);
  } else {
    fit(nodes);
  }
  init_slopes();
}

AlbedoInversion::AlbedoInversion(const AlbedoTableConfig& config, CacheOnly) : config_(config) {
  init_nodes();
  from_cache_ = !cache_path_.empty() && load();
  if (from_cache_) init_slopes();
}

std::unique_ptr<AlbedoInversion> AlbedoInversion::from_cache(const AlbedoTableConfig& config) {
  std::unique_ptr<AlbedoInversion> t(new AlbedoInversion(config, CacheOnly{}));
  if (!t->from_cache_) return nullptr;
  return t;
}

void AlbedoInversion::save_to_cache() const {
  if (!cache_path_.empty()) save();
}

void check_albedo_table_config(const AlbedoTableConfig& config) {
  auto fail = [](const std::string& m) { throw std::invalid_argument("albedo inversion: " + m); };
  if (!(config.eta > 0 && std::isfinite(config.eta)))
    fail("relative index of refraction eta must be positive and finite, got " + std::to_string(config.eta));
  if (!(config.g > -1 && config.g < 1)) fail("HG anisotropy g must be in (-1, 1), got " + std::to_string(config.g));
  if (config.size < 3) fail("table size must be at least 3, got " + std::to_string(config.size));
  if (exits_lose_energy(config) && config.size < 5)
    fail("a table for a rough boundary needs at least 5 nodes, got " + std::to_string(config.size));
  if (config.paths_per_node < 100) fail("need at least 100 paths per table node");
  if (!(config.alpha_x >= 0 && config.alpha_y >= 0 && std::isfinite(config.alpha_x) && std::isfinite(config.alpha_y)))
    fail("roughness alphas must be non-negative and finite");
}

void AlbedoInversion::init_nodes() {
  const AlbedoTableConfig& config = config_;
  check_albedo_table_config(config);

  const int n = config.size;
  t_.resize(n), alpha_.resize(n);
  for (int i = 0; i < n; ++i) {
    t_[i] = double(i) / (n - 1);
    alpha_[i] = 1 - t_[i] * t_[i];
  }
  if (config.use_cache) {
    const std::string dir = config.cache_dir.empty() ? default_cache_dir() : config.cache_dir;
    // The file names every parameter of the table and the code that made it (its sources' hash).
    if (!dir.empty())
      cache_path_ = fmt::format(
          "{}/albedo-v{}-{}-eta{:.9g}{}{}{}-g{:.9g}-n{}-p{}-s{}-{}.txt", dir, kCacheVersion, source_hash::kAlbedoTable,
          config.eta, config.exit_matched ? "-exitmatched" : "", config.entry_lambertian ? "-lambertianentry" : "",
          config.alpha_x > 0 || config.alpha_y > 0 ? fmt::format("-ax{:.9g}-ay{:.9g}", config.alpha_x, config.alpha_y)
                                                   : "",
          config.g, n, config.paths_per_node, config.seed, walk_sampling_name(config.sampling));
  }
}

void AlbedoInversion::init_slopes() {
  const int n = config_.size;
  // Fritsch-Carlson monotone cubic Hermite slopes with the harmonic mean of the
  // neighbouring secants (Fritsch & Butland 1984): monotone data give a monotone curve.
  slope_.assign(n, 0.0);
  std::vector<double> secant(n - 1);
  for (int i = 0; i + 1 < n; ++i) secant[i] = (albedo_[i + 1] - albedo_[i]) / (t_[i + 1] - t_[i]);
  slope_[0] = secant[0], slope_[n - 1] = secant[n - 2];
  for (int i = 1; i + 1 < n; ++i) {
    const double a = secant[i - 1], b = secant[i];
    slope_[i] = a * b > 0 ? 2 * a * b / (a + b) : 0.0;
  }
}

AlbedoNode simulate_albedo_node(const AlbedoTableConfig& config, int i) {
  const int n = config.size;
  // alpha = 1: nothing is absorbed, all entering light returns (A = 1), unless the exits
  // lose energy: then fit() extrapolates the node (a conservative walk has a return time
  // of infinite mean, too long to simulate); alpha = 0: nothing scatters back (A = 0).
  if (i == 0) return {1.0, 0.0};
  if (i == n - 1) return {0.0, 0.0};
  const double t = double(i) / (n - 1);  // as init_nodes() places the nodes
  HalfspaceConfig c;
  c.albedo = 1 - t * t;
  c.g = config.g;
  c.eta = config.eta;
  c.exit_matched = config.exit_matched;
  c.entry_lambertian = config.entry_lambertian;
  c.alpha_x = config.alpha_x;
  c.alpha_y = config.alpha_y;
  c.incidence = Incidence::Diffuse;
  c.paths = config.paths_per_node;
  c.seed = config.seed;
  c.sampling = config.sampling;
  c.bins = RadialBins::linear(1.0, 1);
  const HalfspaceResult r = simulate_halfspace(c);
  return {r.albedo_per_entering(), r.albedo_per_entering_stderr()};
}

void AlbedoInversion::fit(const std::vector<AlbedoNode>& nodes) {
  const int n = config_.size;
  std::vector<double> raw(n), weight(n);
  stderr_.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    raw[i] = nodes[i].albedo;
    stderr_[i] = nodes[i].error;
    weight[i] = i == 0 || i == n - 1 ? 1e30 : 1 / std::max(stderr_[i] * stderr_[i], 1e-30);
  }
  if (exits_lose_energy(config_) && n >= 4) {
    // A(alpha = 1) < 1: the quadratic in t through nodes 1, 2, 3 (equally spaced), at
    // t = 0: 3 A1 - 3 A2 + A3 (Newton's forward differences), its error propagated as
    // if the nodes were independent. Checked against a truncated simulation in
    // docs/materials.md.
    raw[0] = std::clamp(3 * raw[1] - 3 * raw[2] + raw[3], raw[1], 1.0);
    stderr_[0] = std::sqrt(9 * sqr(stderr_[1]) + 9 * sqr(stderr_[2]) + sqr(stderr_[3]));
    weight[0] = 1 / std::max(sqr(stderr_[0]), 1e-30);
  }
  albedo_ = non_increasing_fit(raw, weight);
}

void AlbedoInversion::build() {
  std::vector<AlbedoNode> nodes;
  for (int i = 0; i < config_.size; ++i) nodes.push_back(simulate_albedo_node(config_, i));
  fit(nodes);
}

bool AlbedoInversion::load() {
  std::ifstream in(cache_path_);
  if (!in) return false;
  std::string header;
  std::getline(in, header);
  if (header != fmt::format("dermis albedo table v{} {}", kCacheVersion, config_.size)) return false;
  const int n = config_.size;
  std::vector<double> albedo(n), err(n);
  for (int i = 0; i < n; ++i) {
    double t;
    if (!(in >> t >> albedo[i] >> err[i]) || std::abs(t - t_[i]) > 1e-12 || !(albedo[i] >= 0 && albedo[i] <= 1))
      return false;
  }
  albedo_ = albedo, stderr_ = err;
  return true;
}

void AlbedoInversion::save() const {
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(cache_path_).parent_path(), ec);
  // Write a temporary file and rename it: a reader never sees half a table.
  const std::string tmp =
      cache_path_ + fmt::format(".tmp{}", uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()));
  {
    std::ofstream out(tmp);
    if (!out) return;  // the cache is optional
    out << fmt::format("dermis albedo table v{} {}\n", kCacheVersion, config_.size);
    for (size_t i = 0; i < t_.size(); ++i)
      out << fmt::format("{:.17g} {:.17g} {:.17g}\n", t_[i], albedo_[i], stderr_[i]);
    if (!out) return;
  }
  std::filesystem::rename(tmp, cache_path_, ec);
  if (ec) std::filesystem::remove(tmp, ec);
}

HermiteNode AlbedoInversion::node(int k) const {
  return {t_[std::size_t(k)], albedo_[std::size_t(k)], slope_[std::size_t(k)]};
}

double AlbedoInversion::albedo_at_t(double t) const {
  const int n = int(t_.size());
  t = std::clamp(t, 0.0, 1.0);
  const int k = std::min(n - 2, int(t * (n - 1)));
  return hermite_between(node(k), node(k + 1), t);
}

double AlbedoInversion::surface_albedo(double alpha) const {
  if (!(alpha >= 0 && alpha <= 1))
    throw std::invalid_argument("albedo inversion: single-scattering albedo must be in [0, 1], got " +
                                std::to_string(alpha));
  return albedo_at_t(std::sqrt(1 - alpha));
}

double AlbedoInversion::single_scattering_albedo(double a) const {
  if (!(a >= 0 && a <= 1))
    throw std::invalid_argument("albedo inversion: surface albedo must be in [0, 1], got " + std::to_string(a));
  // A(t) is non-increasing in t (a textured material inverts per walk, in each channel).
  const double t = crossing_of_non_increasing(
      int(t_.size()), [this](int k) { return node(k); }, a);
  return 1 - t * t;
}

double van_de_hulst_single_scattering_albedo(double a) {
  if (!(a >= 0 && a <= 1))
    throw std::invalid_argument("van de Hulst fit: surface albedo must be in [0, 1], got " + std::to_string(a));
  // van de Hulst fit (METHODS.md section 4).
  const double s = 4.09712 + 4.20863 * a - std::sqrt(9.59217 + 41.6808 * a + 17.7126 * a * a);
  return 1 - s * s;
}

}  // namespace dermis::sss
