#include "dermis/materials/grid_medium.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dermis/materials/medium.h"
#include "dermis/materials/noise.h"
#include "dermis/spectral/blackbody.h"
#include "dermis/spectral/spectrum_at.h"

namespace dermis {

namespace {

constexpr int kMajorantCells = 16;         // per axis, as pbrt-v4's grid media
constexpr int kNanoVdbMajorantCells = 64;  // per axis, as pbrt-v4's NanoVDBMedium

// pbrt-v4's DNoise (util/noise.cpp): the noise's gradient by forward differences of 0.01.
Vec3 noise_gradient(Vec3 p) {
  constexpr float delta = 0.01f;
  const float n = perlin_noise_pbrt_v4(p);
  return Vec3(perlin_noise_pbrt_v4(p + Vec3(delta, 0, 0)) - n, perlin_noise_pbrt_v4(p + Vec3(0, delta, 0)) - n,
              perlin_noise_pbrt_v4(p + Vec3(0, 0, delta)) - n) /
         delta;
}

}  // namespace

float pbrt_v4_cloud_density(Vec3 p, float density, float wispiness, float frequency) {
  // pbrt-v4 sec. 11.4.2 (CloudMedium::Density): the lookup point perturbed by two octaves of
  // the noise's gradient, five octaves of noise, scaled down with height.
  Vec3 pp = p * frequency;
  if (wispiness > 0) {
    float vomega = 0.05f * wispiness, vlambda = 10.0f;
    for (int i = 0; i < 2; ++i) {
      pp = pp + noise_gradient(pp * vlambda) * vomega;
      vomega *= 0.5f;
      vlambda *= 1.99f;
    }
  }
  float d = 0, omega = 0.5f, lambda = 1.0f;
  for (int i = 0; i < 5; ++i) {
    d += omega * perlin_noise_pbrt_v4(pp * lambda);
    omega *= 0.5f;
    lambda *= 1.99f;
  }
  d = std::clamp((1 - p.y) * 4.5f * density * d, 0.0f, 1.0f);
  d += 2 * std::max(0.0f, 0.5f - p.y);
  return std::clamp(d, 0.0f, 1.0f);
}

Vec3 GridMedium::unit_point(Vec3 p_world) const {
  const Vec3 p = medium_from_world.point(p_world);
  return Vec3((p.x - p0.x) / (p1.x - p0.x), (p.y - p0.y) / (p1.y - p0.y), (p.z - p0.z) / (p1.z - p0.z));
}

Vec3 GridMedium::unit_vector(Vec3 v_world) const {
  const Vec3 v = medium_from_world.vector(v_world);
  return Vec3(v.x / (p1.x - p0.x), v.y / (p1.y - p0.y), v.z / (p1.z - p0.z));
}

Vec3 GridMedium::medium_point(Vec3 unit) const {
  return p0 + Vec3(unit.x * (p1.x - p0.x), unit.y * (p1.y - p0.y), unit.z * (p1.z - p0.z));
}

float GridMedium::density_at(Vec3 unit) const {
  switch (kind) {
    case Kind::Cloud:
      return pbrt_v4_cloud_density(medium_point(unit), cloud_density, wispiness, frequency);
    case Kind::NanoVDB:
      return vdb_density->value(medium_point(unit));
    default: {
      const float uniform = majorants.empty() ? -1 : majorants[std::size_t(majorant_cell(unit))].uniform;
      return uniform >= 0 ? uniform : density.lookup(unit);
    }
  }
}

int GridMedium::majorant_cell(Vec3 unit) const {
  int c[3];
  for (int a = 0; a < 3; ++a) c[a] = std::clamp(int(unit[a] * float(majorant_res[a])), 0, majorant_res[a] - 1);
  return (c[2] * majorant_res[1] + c[1]) * majorant_res[0] + c[0];
}

void GridMedium::build_majorants() {
  if (kind == Kind::Cloud) {  // the density never exceeds 1: one cell (pbrt-v4's homogeneous majorant)
    majorant_res[0] = majorant_res[1] = majorant_res[2] = 1;
    majorants.assign(1, {RGB(1), 1});
    return;
  }
  if (kind == Kind::NanoVDB) {
    const int n = kNanoVdbMajorantCells;
    for (int& r : majorant_res) r = n;
    majorants.assign(std::size_t(n) * n * n, {});
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const Vec3 lo = medium_point(Vec3(float(x), float(y), float(z)) / float(n));
          const Vec3 hi = medium_point(Vec3(float(x + 1), float(y + 1), float(z + 1)) / float(n));
          const float d = vdb_density->max_over(lo, hi);
          majorants[(std::size_t(z) * n + std::size_t(y)) * n + std::size_t(x)] = {RGB(d), d};
        }
    return;
  }
  for (int& r : majorant_res) r = kMajorantCells;
  majorants.assign(std::size_t(kMajorantCells) * kMajorantCells * kMajorantCells, {});
  auto biggest = [](const RGB& c) { return c.max(); };
  auto channel_max = [](const VoxelGrid<RGB>& grid, Vec3 lo, Vec3 hi) {
    if (grid.empty()) return RGB(1);
    RGB m;
    for (int c = 0; c < 3; ++c) m[c] = grid.max_over(lo, hi, [c](const RGB& v) { return v[c]; });
    return m;
  };
  for (int z = 0; z < kMajorantCells; ++z)
    for (int y = 0; y < kMajorantCells; ++y)
      for (int x = 0; x < kMajorantCells; ++x) {
        const Vec3 lo = Vec3(float(x), float(y), float(z)) / float(kMajorantCells);
        const Vec3 hi = Vec3(float(x + 1), float(y + 1), float(z + 1)) / float(kMajorantCells);
        MajorantCell& cell =
            majorants[(std::size_t(z) * kMajorantCells + std::size_t(y)) * kMajorantCells + std::size_t(x)];
        if (kind == Kind::Density) {
          const float d = density.max_over(lo, hi, [](float v) { return v; });
          cell = {RGB(d), d};
          // Widened by a little more than a float's rounding of a point into its cell.
          const Vec3 margin(1e-5f, 1e-5f, 1e-5f);
          float v;
          if (density.uniform_over(lo - margin, hi + margin, v)) cell.uniform = v;
        } else {
          cell.rgb = channel_max(sigma_a_grid, lo, hi) + channel_max(sigma_s_grid, lo, hi);
          const float a = sigma_a_grid.empty() ? 1 : 2 * sigma_a_grid.max_over(lo, hi, biggest);
          const float s = sigma_s_grid.empty() ? 1 : 2 * sigma_s_grid.max_over(lo, hi, biggest);
          cell.any_wavelength = a + s;
        }
      }
}

MediumCoefficients GridMediumView::at(Vec3 p_world) const {
  const Vec3 u = grid->unit_point(p_world);
  if (!(u.x >= 0 && u.x <= 1 && u.y >= 0 && u.y <= 1 && u.z >= 0 && u.z <= 1)) return {};
  if (grid->kind != GridMedium::Kind::RGBGrid) {
    const float d = grid->density_at(u);
    return {sigma_a_unit * d, sigma_s_unit * d, emissive ? density_emission(u) : RGB(0)};
  }
  auto read = [&](const VoxelGrid<RGB>& g) {
    if (g.empty()) return RGB(1);
    if (!wavelengths) return g.lookup(u);
    return g.lookup(u, [&](const RGB& c) { return unbounded_at(c, *wavelengths); });
  };
  RGB Le;
  if (emissive) {
    Le = (wavelengths ? grid->le_grid.lookup(u, [&](const RGB& c) { return illuminant_at(c, *wavelengths); })
                      : grid->le_grid.lookup(u)) *
         grid->le_grid_scale;
  }
  return {read(grid->sigma_a_grid) * sigma_a_unit, read(grid->sigma_s_grid) * sigma_s_unit, Le};
}

RGB GridMediumView::density_emission(Vec3 u) const {
  const bool vdb = grid->kind == GridMedium::Kind::NanoVDB;
  const float scale = vdb ? grid->vdb_le_scale : grid->le_scale.lookup(u);
  if (!(scale > 0)) return RGB(0);
  if (!vdb && grid->temperature.empty()) return Le_unit * scale;
  // pbrt-v4's GridMedium::SamplePoint and NanoVDBMedium::SamplePoint: the temperature offset
  // and scaled, no emission at 100 K or below.
  const float t = vdb ? grid->vdb_temperature->value(grid->medium_point(u)) : grid->temperature.lookup(u);
  const float kelvin = (t - grid->temperature_offset) * grid->temperature_scale;
  if (!(kelvin > 100)) return RGB(0);
  const float s = scale * grid->blackbody_scale;
  if (!wavelengths) return normalized_blackbody_rgb(kelvin) * s;
  RGB Le;
  for (int i = 0; i < 3; ++i) Le[i] = normalized_blackbody(wavelengths->lambda[std::size_t(i)], kelvin) * s;
  return Le;
}

RGB GridMediumView::channel_preference() const {
  if (grid->kind == GridMedium::Kind::RGBGrid) return RGB(1);
  return HomogeneousMedium::from_coefficients(sigma_a_unit, sigma_s_unit, 1, g).channel_preference;
}

MajorantTraversal::MajorantTraversal(const GridMediumView& m, const Ray& ray, float t_max) : m_(&m) {
  const GridMedium& g = *m.grid;
  // The ray in the unit cube of the box (t unchanged: the direction is not renormalised).
  const Vec3 o = g.unit_point(ray.o);
  const Vec3 d = g.unit_vector(ray.d);
  float t0 = 0, t1 = t_max;
  for (int a = 0; a < 3; ++a) {  // the slabs 0 <= o + t d <= 1
    if (d[a] == 0) {
      if (o[a] < 0 || o[a] > 1) return;
      continue;
    }
    float ta = (0 - o[a]) / d[a], tb = (1 - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 < t1)) return;
  t_ = t0;
  t_end_ = t1;
  done_ = false;
  const Vec3 start = o + d * t0;
  for (int a = 0; a < 3; ++a) {
    const int res = g.majorant_res[a];
    const float c = start[a] * float(res);
    cell_[a] = std::clamp(int(std::floor(c)), 0, res - 1);
    if (d[a] == 0) {
      step_[a] = 0;
      next_t_[a] = delta_t_[a] = std::numeric_limits<float>::infinity();
      continue;
    }
    const float inv = 1 / (d[a] * float(res));  // t per cell along axis a
    step_[a] = d[a] > 0 ? 1 : -1;
    const int boundary = d[a] > 0 ? cell_[a] + 1 : cell_[a];
    next_t_[a] = t0 + (float(boundary) - c) * inv;
    delta_t_[a] = std::abs(inv);
  }
}

bool MajorantTraversal::next(MajorantSegment& s) {
  if (done_) return false;
  const GridMedium& g = *m_->grid;
  const int axis = next_t_[0] < next_t_[1] ? (next_t_[0] < next_t_[2] ? 0 : 2) : (next_t_[1] < next_t_[2] ? 1 : 2);
  const float t1 = std::min(next_t_[axis], t_end_);
  s.t0 = t_;
  s.t1 = t1;
  const int cell = (cell_[2] * g.majorant_res[1] + cell_[1]) * g.majorant_res[0] + cell_[0];
  s.sigma_maj = m_->majorant(cell);
  s.density = g.majorants[std::size_t(cell)].uniform;
  s.exact = g.kind == GridMedium::Kind::Density && s.density >= 0;
  t_ = t1;
  if (t1 >= t_end_) {
    done_ = true;
  } else {
    cell_[axis] += step_[axis];
    next_t_[axis] += delta_t_[axis];
    if (cell_[axis] < 0 || cell_[axis] >= g.majorant_res[axis]) done_ = true;
  }
  return true;
}

}  // namespace dermis
