#include "dermis/render/spectral_media.h"

#include "dermis/materials/at_wavelengths.h"
#include "dermis/render/volumetric_texture.h"

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

}  // namespace dermis
