// The scene's media at a spectral path's wavelengths, as the path tracer's free flights and
// its shadow rays both read them: a `volumetric` material's medium from its parameters read
// at the wavelengths and inverted per wavelength (volumetric_texture.h), a medium of the file
// from its coefficients' spectra where they are given as data (RenderScene::medium_spectra),
// else from the spectra of their colours (materials/at_wavelengths.h).
#pragma once

#include "dermis/materials/grid_medium.h"
#include "dermis/materials/medium.h"
#include "dermis/render/render_scene.h"
#include "dermis/spectral/sampled_wavelengths.h"

namespace dermis {

HomogeneousMedium scene_medium_at_wavelengths(const RenderScene& sc, int medium, const SampledWavelengths& w);

// A grid medium (sc.grid_medium_of(medium) >= 0) as a path reads it: at its wavelengths when it
// has them (w non-null), else in RGB.
// The emission of a homogeneous medium of the file (zero for any other): at the path's
// wavelengths when it has them (w non-null).
RGB homogeneous_emission(const RenderScene& sc, int medium, const SampledWavelengths* w);

// With `emission`, the view reads the medium's emission too (Le).
GridMediumView grid_medium_view(const RenderScene& sc, int medium, const SampledWavelengths* w, bool emission = false);

}  // namespace dermis
