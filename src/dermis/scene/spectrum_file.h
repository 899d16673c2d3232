// pbrt-v4's spectrum files ("spectrum name" "file.spd"): numbers separated by white space,
// read as (wavelength in nm, value) pairs; '#' starts a comment that runs to the end of the
// line. Wavelengths must increase.
#pragma once

#include <string>
#include <vector>

#include "dermis/scene/diagnostics.h"

namespace dermis {

struct SampledSpectrum {
  std::vector<double> lambda;  // nm, increasing
  std::vector<double> value;
};

// The pairs of the file at `path` (an absolute path). Throws SceneError: at `named_at` (the
// scene value that names the file) when it cannot be read; at path:line:col for a bad
// number, a wavelength that does not increase, an odd count of numbers or no numbers.
SampledSpectrum read_spectrum_file(const std::string& path, const SourceLoc& named_at);

}  // namespace dermis
