#include "dermis/render/subsurface/coefficients.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <tuple>

#include "dermis/core/microfacet.h"
#include "dermis/spectral/spectrum_at.h"
#include "dermis/sss/study/albedo_inversion.h"
#include "dermis/sss/walk/albedo_inversion.h"

namespace dermis {

namespace {

// (eta, g, exit matched, alpha_x, alpha_y, Lambertian entry)
using TableKey = std::tuple<double, double, bool, double, double, bool>;

// One table per boundary and g, shared by every material of the process.
std::mutex g_tables_mutex;
std::map<TableKey, std::unique_ptr<sss::AlbedoInversion>> g_tables;

sss::AlbedoTableConfig table_config(const TableKey& key) {
  sss::AlbedoTableConfig config;
  config.eta = std::get<0>(key);
  config.g = std::get<1>(key);
  config.exit_matched = std::get<2>(key);
  config.alpha_x = std::get<3>(key);
  config.alpha_y = std::get<4>(key);
  config.entry_lambertian = std::get<5>(key);
  return config;
}

// The table of the walk's own boundary: the dielectric (Fresnel at entry and at every
// exit); the diffuse boundary (refraction at entry, out at the first crossing through
// the exit lobe); matched (eta = 1). A is per entering light under diffuse incidence.
// A rough boundary (the alphas the renderer uses: subsurface_method.cpp, walk_method.cpp)
// is rough in the table too: at the entry for both, at every exit for the dielectric.
// Only the walk and the volumetric reference invert with a table.
// A textured roughness (AlbedoInversions): the table at alpha_node on both axes.
std::optional<TableKey> table_key(const SubsurfaceParams& p, std::optional<float> alpha_node = std::nullopt) {
  using Method = SubsurfaceParams::Method;
  if (!p.reflectance || p.albedo_inversion_fit) return std::nullopt;
  if (p.method != Method::RandomWalk && p.method != Method::Volumetric) return std::nullopt;
  using Boundary = SubsurfaceParams::Boundary;
  const bool matched = p.boundary == Boundary::Matched;
  float ax = 0, ay = 0;
  if (!matched) {
    ax = alpha_node ? *alpha_node : roughness_to_alpha(p.uroughness, p.remap_roughness);
    ay = alpha_node ? *alpha_node : roughness_to_alpha(p.vroughness, p.remap_roughness);
    if (std::max(ax, ay) < kSmoothAlpha) ax = ay = 0;
  }
  const bool diffuse = p.boundary == Boundary::Diffuse;
  return TableKey{matched ? 1.0 : p.eta, p.g, diffuse, ax, ay, diffuse && p.lambertian_entry};
}

bool alpha_interpolated(const SubsurfaceParams& p) {
  return p.roughness_texture >= 0 && p.boundary != SubsurfaceParams::Boundary::Matched;
}

// Nodes uniform in sqrt(alpha): A_max of a rough `dielectric` boundary falls fastest near 0.
float inversion_alpha_node(int k) {
  const float t = float(k) / (AlbedoInversions::kAlphaNodes - 1);
  return t * t;
}

// Every table a material needs.
std::vector<TableKey> table_keys(const SubsurfaceParams& p) {
  std::vector<TableKey> keys;
  if (!alpha_interpolated(p)) {
    if (auto key = table_key(p)) keys.push_back(*key);
    return keys;
  }
  for (int k = 0; k < AlbedoInversions::kAlphaNodes; ++k)
    if (auto key = table_key(p, inversion_alpha_node(k))) keys.push_back(*key);
  return keys;
}

const sss::AlbedoInversion& albedo_inversion(const TableKey& key) {
  std::lock_guard<std::mutex> lock(g_tables_mutex);
  auto& t = g_tables[key];
  if (!t) t = std::make_unique<sss::AlbedoInversion>(table_config(key));
  return *t;
}

// One table made by the group (see prepare_albedo_inversions).
std::unique_ptr<sss::AlbedoInversion> shared_table(const sss::AlbedoTableConfig& config, ProcessGroup& group) {
  std::unique_ptr<sss::AlbedoInversion> t;
  double cached = 0;
  if (group.is_root()) {
    t = sss::AlbedoInversion::from_cache(config);
    cached = t ? 1 : 0;
  }
  group.broadcast(std::span<double>(&cached, 1));
  const int n = config.size;
  std::vector<double> values(2 * std::size_t(n));  // (A, stderr) per node
  std::vector<sss::AlbedoNode> nodes(n);
  if (cached > 0) {
    if (group.size() == 1) return t;
    if (t)
      for (int i = 0; i < n; ++i) values[2 * i] = t->node_albedos()[i], values[2 * i + 1] = t->node_stderrs()[i];
    group.broadcast(values);
    if (t) return t;
    for (int i = 0; i < n; ++i) nodes[i] = {values[2 * i], values[2 * i + 1]};
    return std::make_unique<sss::AlbedoInversion>(config, nodes, true);
  }
  const auto start = std::chrono::steady_clock::now();
  const auto [begin, end] = group.share(std::size_t(n));
  for (std::size_t i = begin; i < end; ++i) {
    const sss::AlbedoNode node = sss::simulate_albedo_node(config, int(i));
    values[2 * i] = node.albedo, values[2 * i + 1] = node.error;
  }
  group.allgather(std::span<double>(values), 2);
  for (int i = 0; i < n; ++i) nodes[i] = {values[2 * i], values[2 * i + 1]};
  t = std::make_unique<sss::AlbedoInversion>(config, nodes, false);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (group.is_root() && seconds >= config.cache_min_seconds) t->save_to_cache();
  return t;
}

}  // namespace

MediumAt medium_at(const SubsurfaceParams& p, const std::vector<Texture>* textures, const TextureContext& at) {
  MediumAt m{p.sigma_a, p.sigma_s, p.reflectance, p.mfp, p.scale};
  if (!textures || !p.textured()) return m;
  // Coefficients and mfp are multiplied by scale (pbrt-v4), as for constants.
  auto texture = [&](int index, float factor, float lo, float hi) {
    RGB v = evaluate_texture(*textures, index, at) * factor;
    for (int c = 0; c < 3; ++c) v[c] = std::clamp(std::isfinite(v[c]) ? v[c] : lo, lo, hi);
    return v;
  };
  constexpr float kTiny = 1e-6f, kHuge = 1e30f;
  if (p.reflectance_texture >= 0) m.reflectance = texture(p.reflectance_texture, 1, 0, 1);
  if (p.mfp_texture >= 0) m.mfp = texture(p.mfp_texture, p.scale, kTiny, kHuge);
  if (p.sigma_a_texture >= 0) m.sigma_a = texture(p.sigma_a_texture, p.scale, 0, kHuge);
  if (p.sigma_s_texture >= 0) m.sigma_s = texture(p.sigma_s_texture, p.scale, 0, kHuge);
  if (p.scale_texture >= 0) {
    // On top of the constant scale (1 when textured): coefficients and mfp times s.
    const float s = texture(p.scale_texture, 1, kTiny, kHuge)[0];
    m.scale *= s;
    if (m.sigma_a) *m.sigma_a = *m.sigma_a * s;
    if (m.sigma_s) *m.sigma_s = *m.sigma_s * s;
    if (m.mfp) *m.mfp = *m.mfp * s;
  }
  return m;
}

MediumAt medium_at_wavelengths(const SubsurfaceParams& p, MediumAt at, const SampledWavelengths& w) {
  // Given as a spectrum and not textured: its data, times the scale at the point.
  auto data = [&](const std::shared_ptr<const std::vector<float>>& spectrum, int texture, float scale) {
    return spectrum && texture < 0 ? std::optional<RGB>(tabulated_at(*spectrum, w) * scale) : std::nullopt;
  };
  auto clamped = [](RGB v, float lo, float hi) {
    for (int c = 0; c < 3; ++c) v[c] = std::clamp(v[c], lo, hi);
    return v;
  };
  if (at.reflectance) {
    const auto d = data(p.reflectance_spectrum, p.reflectance_texture, 1);
    at.reflectance = d ? clamped(*d, 0, 1) : reflectance_at(*at.reflectance, w);
  }
  if (at.mfp) {  // a length: kept positive, as medium_at keeps a textured one
    const auto d = data(p.mfp_spectrum, p.mfp_texture, at.scale);
    at.mfp = clamped(d ? *d : unbounded_at(*at.mfp, w), 1e-6f, 1e30f);
  }
  if (at.sigma_a) {
    const auto d = data(p.sigma_a_spectrum, p.sigma_a_texture, at.scale);
    at.sigma_a = d ? *d : unbounded_at(*at.sigma_a, w);
  }
  if (at.sigma_s) {
    const auto d = data(p.sigma_s_spectrum, p.sigma_s_texture, at.scale);
    at.sigma_s = d ? *d : unbounded_at(*at.sigma_s, w);
  }
  return at;
}

const sss::AlbedoInversion* albedo_inversion_for(const SubsurfaceParams& p) {
  const std::optional<TableKey> key = table_key(p);
  return key ? &albedo_inversion(*key) : nullptr;
}

void prepare_albedo_inversions(std::span<const SubsurfaceParams> params, ProcessGroup& group) {
  // The missing tables, in the same (sorted) order on every process.
  std::set<TableKey> missing;
  {
    std::lock_guard<std::mutex> lock(g_tables_mutex);
    for (const SubsurfaceParams& p : params)
      for (const TableKey& key : table_keys(p)) {
        if (g_tables.count(key)) continue;
        try {
          sss::check_albedo_table_config(table_config(key));
        } catch (const std::invalid_argument&) {
          continue;  // the material reports it, with its place in the scene
        }
        missing.insert(key);
      }
  }
  for (const TableKey& key : missing) {
    const sss::AlbedoTableConfig config = table_config(key);
    std::unique_ptr<sss::AlbedoInversion> t = shared_table(config, group);
    std::lock_guard<std::mutex> lock(g_tables_mutex);
    g_tables[key] = std::move(t);
  }
}

AlbedoInversions::AlbedoInversions(const SubsurfaceParams& params) {
  for (const TableKey& key : table_keys(params)) tables_.push_back(&albedo_inversion(key));
}

double AlbedoInversions::single_scattering_albedo(double surface_albedo, float boundary_alpha) const {
  if (tables_.size() == 1) return tables_[0]->single_scattering_albedo(surface_albedo);
  const float x = std::sqrt(std::clamp(boundary_alpha, 0.0f, 1.0f)) * float(kAlphaNodes - 1);
  const int k = std::min(int(x), kAlphaNodes - 2);
  const double w = x - float(k);
  const sss::AlbedoInversion &a = *tables_[std::size_t(k)], &b = *tables_[std::size_t(k) + 1];
  // A(alpha) interpolated between the two tables (it is smooth in the boundary's alpha;
  // its inverse is steep near a rough dielectric's A_max): the blend of two monotone
  // cubics on the same nodes is the cubic of the blended nodes, inverted as one table
  // inverts its own; above the blend's A(1): alpha = 1.
  if (a.size() != b.size()) throw std::logic_error("albedo inversions: tables of different sizes");
  auto blended = [&](int i) {
    const sss::HermiteNode p = a.node(i), q = b.node(i);
    return sss::HermiteNode{p.t, p.y * (1 - w) + q.y * w, p.m * (1 - w) + q.m * w};
  };
  const double t = sss::crossing_of_non_increasing(a.size(), blended, surface_albedo);
  return 1 - t * t;
}

Coefficients coefficients_from(const MediumAt& m, const AlbedoInversions& inversions, float boundary_alpha) {
  if (m.sigma_a || inversions.empty()) return coefficients_from(m, nullptr);
  Coefficients k;
  for (int c = 0; c < 3; ++c) {
    const double st = 1.0 / (*m.mfp)[c];
    const double alpha = inversions.single_scattering_albedo((*m.reflectance)[c], boundary_alpha);
    k.sigma_s[c] = float(alpha * st);
    k.sigma_a[c] = float((1 - alpha) * st);
  }
  return k;
}

Coefficients coefficients_from(const MediumAt& m, const sss::AlbedoInversion* table) {
  if (m.sigma_a) return {*m.sigma_a, *m.sigma_s};
  // sigma_t = 1 / mfp; alpha from the table, or van de Hulst's fit (g = 0,
  // index-matched) for comparison ("albedoinversion" "fit").
  Coefficients k;
  for (int c = 0; c < 3; ++c) {
    const double st = 1.0 / (*m.mfp)[c];
    const double A = (*m.reflectance)[c];
    const double alpha = table ? table->single_scattering_albedo(A) : sss::van_de_hulst_single_scattering_albedo(A);
    k.sigma_s[c] = float(alpha * st);
    k.sigma_a[c] = float((1 - alpha) * st);
  }
  return k;
}

AlbedoAndMfp albedo_and_mfp(const MediumAt& m, float g) {
  if (m.reflectance) return {*m.reflectance, *m.mfp};
  AlbedoAndMfp r;
  for (int c = 0; c < 3; ++c) {
    double ss = (*m.sigma_s)[c] * (1 - g), st = (*m.sigma_a)[c] + ss;
    r.mfp[c] = float(1 / st);
    // Chandrasekhar 1950 (METHODS.md sec. 6), tabulated: made at every textured or spectral entry.
    r.albedo[c] = float(sss::surface_albedo_index_matched_tabulated(ss / st));
  }
  return r;
}

}  // namespace dermis
