#include "dermis/spectral/spectrum_at.h"

#include <algorithm>

#include "dermis/spectral/cie_observer.h"
#include "dermis/spectral/rgb_to_spectrum.h"

namespace dermis {

namespace {

enum class Kind { Reflectance, Unbounded, Illuminant };

template <class Spectrum>
RGB values_at(const Spectrum& s, const SampledWavelengths& w) {
  RGB out;
  for (int i = 0; i < kPathWavelengths; ++i) out[i] = s(w.lambda[std::size_t(i)]);
  return out;
}

// The spectra of the last few colours of this thread, whatever the wavelengths (the
// table's lookup skipped for a colour seen again).
struct RecentSpectrum {
  RGB rgb{-1, -1, -1};
  RgbSpectrum spectrum;
};
constexpr int kRecentSpectra = 8;
thread_local RecentSpectrum recent_spectra[kRecentSpectra];
thread_local int recent_spectra_next = 0;

const RgbSpectrum& spectrum_of(RGB rgb) {
  for (const RecentSpectrum& r : recent_spectra)
    if (r.rgb == rgb) return r.spectrum;
  RecentSpectrum& r = recent_spectra[recent_spectra_next];
  recent_spectra_next = (recent_spectra_next + 1) % kRecentSpectra;
  r.rgb = rgb;
  r.spectrum = RgbToSpectrumTable::srgb()(rgb);
  return r.spectrum;
}

RGB compute(RGB rgb, Kind kind, const SampledWavelengths& w) {
  if (kind == Kind::Reflectance) {
    for (int c = 0; c < 3; ++c) rgb[c] = std::clamp(rgb[c], 0.0f, 1.0f);
    return values_at(spectrum_of(rgb), w);
  }
  // pbrt-v4's unbounded spectrum: scale x the reflectance spectrum of rgb / scale, the scale
  // twice the largest component (rgb_to_spectrum.h unbounded_spectrum).
  for (int c = 0; c < 3; ++c) rgb[c] = std::max(rgb[c], 0.0f);
  const float scale = 2 * std::max({rgb[0], rgb[1], rgb[2]});
  if (scale == 0) return RGB(0);
  RGB out = values_at(spectrum_of(rgb / scale), w) * scale;
  if (kind == Kind::Illuminant)
    for (int i = 0; i < kPathWavelengths; ++i) out[i] *= d65_at(w.lambda[std::size_t(i)]);
  return out;
}

// The last few conversions of this thread: a path reads the same few colours (its lights',
// its materials') at the same wavelengths again and again. The hero wavelength names the set.
struct Recent {
  RGB rgb;
  Kind kind;
  float hero;
  RGB values;
};
constexpr int kRecent = 8;
thread_local Recent recent[kRecent] = {};
thread_local int recent_next = 0;

RGB at_wavelengths(RGB rgb, Kind kind, const SampledWavelengths& w) {
  const float hero = w.lambda[0];
  for (const Recent& r : recent)
    if (r.hero == hero && r.kind == kind && r.rgb == rgb) return r.values;
  const RGB values = compute(rgb, kind, w);
  recent[recent_next] = {rgb, kind, hero, values};
  recent_next = (recent_next + 1) % kRecent;
  return values;
}

}  // namespace

RGB reflectance_at(RGB rgb, const SampledWavelengths& w) { return at_wavelengths(rgb, Kind::Reflectance, w); }
RGB unbounded_at(RGB rgb, const SampledWavelengths& w) { return at_wavelengths(rgb, Kind::Unbounded, w); }
RGB illuminant_at(RGB rgb, const SampledWavelengths& w) { return at_wavelengths(rgb, Kind::Illuminant, w); }

RGB tabulated_at(std::span<const float> every_nanometre, const SampledWavelengths& w) {
  RGB out;
  const int n = int(every_nanometre.size());
  for (int i = 0; i < kPathWavelengths; ++i) {
    const float x = w.lambda[std::size_t(i)] - CieTables::kLambdaMin;
    const int k = std::clamp(int(x), 0, std::max(n - 2, 0));
    const float f = std::clamp(x - float(k), 0.0f, 1.0f);
    out[i] = n == 0   ? 0
             : n == 1 ? every_nanometre[0]
                      : (1 - f) * every_nanometre[std::size_t(k)] + f * every_nanometre[std::size_t(k) + 1];
  }
  return out;
}

float d65_at(float lambda_nm) {
  const CieTables& cie = cie_tables();
  static const double to_luminance_one = cie.y_sum / cie.d65_y;  // sum d65 y / sum y = 1
  return float(cie_table_at(cie.d65, lambda_nm) * to_luminance_one);
}

}  // namespace dermis
