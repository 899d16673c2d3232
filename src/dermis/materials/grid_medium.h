// pbrt-v4's heterogeneous media (pbrt-v4 sec. 11.4): a box [p0, p1] in the medium's own
// space, placed in the world by the transform current where the medium was made, whose
// coefficients vary inside it and are zero outside:
// - Density ("uniformgrid"): sigma_a and sigma_s per unit density times a density grid;
// - RGBGrid ("rgbgrid"): sigma_a and sigma_s each a grid of colours (absent: 1), times a scale;
// - Cloud ("cloud"): sigma_a and sigma_s per unit density times pbrt-v4's procedural cloud
//   density (sums of Perlin noise, falling off with height).
// A coarse grid of majorants (16^3 cells, the largest coefficient reachable in each) bounds
// the coefficients for delta and ratio tracking (null_scattering.h); GridMediumView is the
// medium as one path reads it (its colours or its wavelengths) and MajorantTraversal walks a
// ray's cells (Amanatides & Woo 1987).
#pragma once

#include <memory>
#include <vector>

#include "dermis/core/rgb.h"
#include "dermis/core/transform.h"
#include "dermis/geometry/ray.h"
#include "dermis/materials/nanovdb_grid.h"
#include "dermis/materials/voxel_grid.h"
#include "dermis/spectral/sampled_wavelengths.h"

namespace dermis {

struct GridMedium {
  enum class Kind { Density, RGBGrid, Cloud, NanoVDB };
  Kind kind = Kind::Density;
  Transform medium_from_world;
  Vec3 p0{0, 0, 0}, p1{1, 1, 1};  // the box, in the medium's space (p0 < p1 on every axis)

  VoxelGrid<float> density;                               // Density: the density grid
  VoxelGrid<RGB> sigma_a_grid, sigma_s_grid;              // RGBGrid: the colours (empty: 1 everywhere)
  float cloud_density = 1, wispiness = 1, frequency = 5;  // Cloud: pbrt-v4's parameters
  // NanoVDB: the density grid and the optional temperature grid of an .nvdb file, in the
  // medium's space (the box is the union of their world boxes), and the emission's scale.
  std::shared_ptr<const NanoVdbGrid> vdb_density, vdb_temperature;
  float vdb_le_scale = 1;

  // Emission (pbrt-v4's Le). Density: the colour `Le` (luminance 1 where given as a spectrum,
  // whose samples are RenderScene::spectra[Le_data]) times the grid `le_scale` (absent in the
  // file: one sample of 1, which pbrt-v4's interpolation makes a tent, 1 at the centre, 1/8 at
  // the corners). RGBGrid: the grid of colours `le_grid` times `le_grid_scale`.
  RGB Le;
  int Le_data = -1;
  // Density: or a blackbody at the temperature (temperature - offset) x scale, normalised to 1
  // at its peak (pbrt-v4's BlackbodySpectrum), times le_scale; none at 100 K or below.
  VoxelGrid<float> temperature;
  float temperature_offset = 0, temperature_scale = 1;
  float blackbody_scale = 1;  // the blackbody's radiance per unit of its normalised spectrum
  VoxelGrid<float> le_scale;
  VoxelGrid<RGB> le_grid;
  float le_grid_scale = 1;
  bool emissive() const {
    if (kind == Kind::RGBGrid) return !le_grid.empty() && le_grid_scale > 0;
    if (kind == Kind::NanoVDB) return vdb_temperature && vdb_le_scale > 0;
    return !temperature.empty() || Le.max() > 0;
  }

  // The coarse majorant grid, filled by build_majorants(): per cell, the largest density
  // (Density, Cloud: the same in all three slots) or, for RGBGrid, the largest sigma_a +
  // sigma_s per channel (`rgb`, before the scale) and a bound on it at any wavelength
  // (`any_wavelength`: an unbounded colour's spectrum never exceeds twice its largest
  // component, spectrum_at.h).
  // Density: `uniform`, the density all over the cell where the grid holds one value there
  // (a uniform region: no look-up of eight samples needed), else -1.
  struct MajorantCell {
    RGB rgb;
    float any_wavelength = 0;
    float uniform = -1;
  };
  int majorant_res[3] = {1, 1, 1};
  std::vector<MajorantCell> majorants;

  void build_majorants();
  // The majorant cell a point of the unit cube is in.
  int majorant_cell(Vec3 unit) const;
  // A point of the world in the box's unit cube (outside [0, 1]^3: outside the medium).
  Vec3 unit_point(Vec3 p_world) const;
  // A vector of the world in the unit cube's measure (a ray's direction there).
  Vec3 unit_vector(Vec3 v_world) const;
  // The density at a point of the unit cube (Density, Cloud, NanoVDB), and the point of the
  // medium's space it stands for.
  float density_at(Vec3 unit) const;
  Vec3 medium_point(Vec3 unit) const;
};

// pbrt-v4's CloudMedium::Density at a point of the medium's space.
float pbrt_v4_cloud_density(Vec3 p, float density, float wispiness, float frequency);

// The coefficients at a point, at a path's colours or wavelengths.
struct MediumCoefficients {
  RGB sigma_a, sigma_s;
  RGB Le;  // emitted radiance (zero unless the view reads emission)
};

// A grid medium as one path reads it.
struct GridMediumView {
  const GridMedium* grid = nullptr;
  // Density, Cloud: sigma_a and sigma_s per unit density, scale applied, at the path's
  // colours or wavelengths. RGBGrid: the scale in every slot.
  RGB sigma_a_unit, sigma_s_unit;
  float g = 0;
  const SampledWavelengths* wavelengths = nullptr;  // RGBGrid: each colour read at these; null: RGB
  // Emission: read at all (false: Le stays zero); Density: the colour of Le at the path's
  // colours or wavelengths (the le_scale grid multiplies it).
  bool emissive = false;
  RGB Le_unit;

  MediumCoefficients at(Vec3 p_world) const;
  // Density, Cloud: the emission at a point of the unit cube (Le or the temperature's blackbody, times le_scale).
  RGB density_emission(Vec3 unit) const;
  // The majorant of cell i, per slot (inline: the DDA reads it at every cell).
  RGB majorant(int cell) const {
    const GridMedium::MajorantCell& c = grid->majorants[std::size_t(cell)];
    if (grid->kind != GridMedium::Kind::RGBGrid) return (sigma_a_unit + sigma_s_unit) * c.rgb[0];
    return (wavelengths ? RGB(c.any_wavelength) : c.rgb) * sigma_a_unit[0];
  }
  // The preference of delta tracking's channel choice (null_scattering.h) for channels of
  // little absorption (HomogeneousMedium::channel_preference), which a density scales alike
  // everywhere; an rgbgrid's albedo varies from sample to sample: none (1).
  RGB channel_preference() const;
};

// One stretch [t0, t1) of a ray inside one majorant cell.
struct MajorantSegment {
  float t0 = 0, t1 = 0;
  RGB sigma_maj;
  // The majorant is the medium's own extinction all along the stretch (a uniform cell of a
  // density grid, of density `density`): its transmittance is exp(-sigma_maj (t1 - t0)).
  bool exact = false;
  float density = 0;
};

// The majorant cells a ray crosses within [0, t_max), in order (3D DDA).
class MajorantTraversal {
 public:
  MajorantTraversal(const GridMediumView& m, const Ray& ray, float t_max);
  // The next stretch; false when the ray has left the box or reached t_max.
  bool next(MajorantSegment& s);

 private:
  const GridMediumView* m_;
  float t_ = 0, t_end_ = 0;
  int cell_[3] = {0, 0, 0}, step_[3] = {0, 0, 0};
  float next_t_[3] = {0, 0, 0}, delta_t_[3] = {0, 0, 0};
  bool done_ = true;
};

}  // namespace dermis
