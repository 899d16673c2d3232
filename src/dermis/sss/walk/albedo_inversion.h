// From a user's surface albedo A to the single-scattering albedo alpha of the medium
// under it (METHODS.md section 4), exact for the boundary: A(alpha) is tabulated with
// the half-space simulator for the given relative index eta and HG g, and inverted
// through a monotone interpolant.
//
// Surface albedo A = the total diffuse reflectance per unit power that ENTERED the
// medium (HalfspaceResult::albedo_per_entering), under diffuse incidence: the energy
// that leaves after entering, internal Fresnel reflections included, with the entry
// specular part excluded. That is the A of the separable BSSRDF (METHODS.md section 0),
// which multiplies the entry transmission 1 - Fr separately: including the specular
// part would count it twice. Behind a rough boundary the entering power is the part the
// sampled rough dielectric transmits (a single-scattering microfacet model also loses
// some: neither reflected nor transmitted), and A is what leaves per unit of it.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dermis/sss/walk/monotone_hermite.h"
#include "dermis/sss/walk/walk_step.h"

namespace dermis::sss {

struct AlbedoTableConfig {
  double eta = 1.0;               // n_medium / n_outside
  bool exit_matched = false;      // entry refracts by eta, exit at the first crossing (HalfspaceConfig)
  bool entry_lambertian = false;  // entry along a cosine lobe (HalfspaceConfig)
  double g = 0.0;                 // HG anisotropy
  // The boundary's Trowbridge-Reitz alphas (HalfspaceConfig::alpha_x, alpha_y): rough at
  // the entry, and at every exit unless exit_matched. Below kSmoothAlpha: smooth.
  double alpha_x = 0.0, alpha_y = 0.0;
  // Nodes uniform in t = sqrt(1 - alpha) on [0, 1] (A is close to linear in t near
  // alpha = 1); the end nodes alpha = 1 (A = 1) and alpha = 0 (A = 0) are exact, but for
  // a rough `dielectric` boundary, whose exits lose energy: its A(alpha = 1) < 1 is
  // extrapolated from the next three nodes, and no A above it can be asked for (the
  // inversion returns alpha = 1).
  int size = 32;
  uint64_t paths_per_node = 100000;
  uint64_t seed = 1;  // the same seed at every node: correlated noise, a smoother table
  // The flat half-space is where Dwivedi guiding is at its best (docs/random-walk.md).
  WalkSampling sampling = WalkSampling::Dwivedi;
  bool use_cache = true;
  std::string cache_dir;           // empty: $XDG_CACHE_HOME/dermis, else $HOME/.cache/dermis
  double cache_min_seconds = 1.0;  // write the cache only when building took longer
};

// One node of a table as simulated, before the monotone fit.
struct AlbedoNode {
  double albedo = 0, error = 0;  // A at the node's alpha, its standard error
};

// Node i of the table of `config` (i = 0: alpha = 1 and i = size - 1: alpha = 0 are
// exact). The nodes are independent: a caller may compute them anywhere, in parts
// (the distributed renderer does), and build the table from them.
AlbedoNode simulate_albedo_node(const AlbedoTableConfig& config, int i);

// Throws std::invalid_argument, as the constructors do, when `config` cannot make a table.
void check_albedo_table_config(const AlbedoTableConfig& config);

class AlbedoInversion {
 public:
  // Loads the table from the cache, or builds it (each node's simulation runs in
  // parallel on the oneTBB arena) and caches it. Throws std::invalid_argument for bad
  // parameters. A cache that cannot be read or written is ignored (rebuilt).
  explicit AlbedoInversion(const AlbedoTableConfig& config);
  // From `size` nodes the caller computed: as simulated (simulate_albedo_node; the
  // monotone fit is applied), or `fitted` (another table's node_albedos() and
  // node_stderrs()). Neither reads nor writes the cache.
  AlbedoInversion(const AlbedoTableConfig& config, const std::vector<AlbedoNode>& nodes, bool fitted);
  // The table from the cache alone: null when the cache has none (or is off).
  static std::unique_ptr<AlbedoInversion> from_cache(const AlbedoTableConfig& config);
  // Writes the table to the cache, as the first constructor does after building.
  void save_to_cache() const;

  // A(alpha) for alpha in [0, 1] (monotone cubic interpolation in t; Fritsch & Carlson 1980).
  double surface_albedo(double single_scattering_albedo) const;
  // alpha(A) for A in [0, 1]: the inverse of surface_albedo (Newton on the interpolant's
  // cubic, bracketed; where A is flat, the end of the flat part nearest alpha = 1).
  double single_scattering_albedo(double surface_albedo) const;

  const std::vector<double>& node_alphas() const { return alpha_; }
  const std::vector<double>& node_albedos() const { return albedo_; }  // after the monotone fix
  const std::vector<double>& node_stderrs() const { return stderr_; }
  // Node k of the interpolant in t = sqrt(1 - alpha): t, A and dA/dt.
  HermiteNode node(int k) const;
  int size() const { return int(t_.size()); }
  bool from_cache() const { return from_cache_; }
  double build_seconds() const { return build_seconds_; }
  const std::string& cache_path() const { return cache_path_; }

 private:
  struct CacheOnly {};
  AlbedoInversion(const AlbedoTableConfig& config, CacheOnly);
  void init_nodes();                               // checks the config; t_, alpha_, cache_path_
  void fit(const std::vector<AlbedoNode>& nodes);  // albedo_, stderr_ from raw nodes
  void init_slopes();
  double albedo_at_t(double t) const;
  void build();
  bool load();
  void save() const;

  AlbedoTableConfig config_;
  std::vector<double> t_, alpha_, albedo_, stderr_, slope_;
  bool from_cache_ = false;
  double build_seconds_ = 0;
  std::string cache_path_;
};

// The van de Hulst fit (g = 0; METHODS.md section 4), for comparison only:
// s = 4.09712 + 4.20863 A - sqrt(9.59217 + 41.6808 A + 17.7126 A^2), alpha = 1 - s^2.
double van_de_hulst_single_scattering_albedo(double surface_albedo);

}  // namespace dermis::sss
