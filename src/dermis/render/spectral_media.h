// The scene's media at a spectral path's wavelengths, as the path tracer's free flights and
// its shadow rays both read them: a `volumetric` material's medium from its parameters read
// at the wavelengths and inverted per wavelength (volumetric_texture.h), a medium of the file
// from its coefficients' spectra where they are given as data (RenderScene::medium_spectra),
// else from the spectra of their colours (materials/at_wavelengths.h).
#pragma once

#include "dermis/materials/medium.h"
#include "dermis/render/render_scene.h"
#include "dermis/spectral/sampled_wavelengths.h"

namespace dermis {

HomogeneousMedium scene_medium_at_wavelengths(const RenderScene& sc, int medium, const SampledWavelengths& w);

}  // namespace dermis
