#include "dermis/render/spectral_media.h"

#include "dermis/materials/at_wavelengths.h"
#include "dermis/render/volumetric_texture.h"
#include "dermis/spectral/spectrum_at.h"

namespace dermis {

namespace {

HomogeneousMedium file_medium_at_wavelengths(const RenderScene& sc, int m, const SampledWavelengths& w) {
  const HomogeneousMedium& rgb = sc.media[std::size_t(m)];
  if (std::size_t(m) >= sc.medium_spectra.size()) return medium_at_wavelengths(rgb, w);
  const RenderScene::MediumSpectra& data = sc.medium_spectra[std::size_t(m)];
  if (data.sigma_a < 0 && data.sigma_s < 0) return medium_at_wavelengths(rgb, w);
  auto at = [&](int d, RGB scaled) {
    return d >= 0 ? tabulated_at(sc.spectra[std::size_t(d)], w) * data.scale : unbounded_at(scaled, w);
  };
  return HomogeneousMedium::from_coefficients(at(data.sigma_a, rgb.sigma_a), at(data.sigma_s, rgb.sigma_s), 1, rgb.g);
}

}  // namespace

HomogeneousMedium scene_medium_at_wavelengths(const RenderScene& sc, int medium, const SampledWavelengths& w) {
  const int v = volumetric_of_medium(sc, medium);
  return v >= 0 ? volumetric_medium_at_wavelengths(sc, v, w) : file_medium_at_wavelengths(sc, medium, w);
}

RGB homogeneous_emission(const RenderScene& sc, int medium, const SampledWavelengths* w) {
  if (medium < 0 || std::size_t(medium) >= sc.medium_emission.size()) return RGB(0);
  const RenderScene::MediumEmission& e = sc.medium_emission[std::size_t(medium)];
  if (!w || e.Le.is_black()) return e.Le;
  return e.data >= 0 ? tabulated_at(sc.spectra[std::size_t(e.data)], *w) * e.scale : illuminant_at(e.Le, *w);
}

GridMediumView grid_medium_view(const RenderScene& sc, int medium, const SampledWavelengths* w, bool emission) {
  const GridMedium& grid = sc.grid_media[std::size_t(sc.grid_medium_of(medium))];
  const HomogeneousMedium& rgb = sc.media[std::size_t(medium)];
  GridMediumView v;
  v.grid = &grid;
  v.g = rgb.g;
  v.wavelengths = w;
  if (grid.kind == GridMedium::Kind::RGBGrid) {  // the colours are the grid's, read per sample
    v.sigma_a_unit = v.sigma_s_unit = RGB(sc.medium_spectra[std::size_t(medium)].scale);
  } else {
    const HomogeneousMedium unit = w ? scene_medium_at_wavelengths(sc, medium, *w) : rgb;
    v.sigma_a_unit = unit.sigma_a;
    v.sigma_s_unit = unit.sigma_s;
  }
  v.emissive = emission && grid.emissive();
  if (v.emissive && grid.kind != GridMedium::Kind::RGBGrid)
    v.Le_unit = !w                  ? grid.Le
                : grid.Le_data >= 0 ? tabulated_at(sc.spectra[std::size_t(grid.Le_data)], *w)
                                    : illuminant_at(grid.Le, *w);
  return v;
}

}  // namespace dermis
