// Tabulated spectral data (measurements, transcribed in named_spectra_data.cpp): the CIE 1931
// standard observer and the spectra pbrt-v4 scenes use by name.
#pragma once

#include <span>

namespace dermis {

// One row of a colour matching function table: wavelength (nm) and x-bar, y-bar, z-bar.
struct CieObserverSample {
  double lambda, x, y, z;
};
// The CIE 1931 2-degree standard observer, 360-830 nm at 5 nm.
std::span<const CieObserverSample> cie_1931_observer();

// What a named spectrum measures, which decides how it becomes RGB.
enum class NamedSpectrumKind {
  Illuminant,       // relative spectral power of a light ("stdillum-*", "illum-*")
  OpticalConstant,  // a metal's eta or k ("metal-*-eta", "metal-*-k")
  GlassIndex,       // a glass's index of refraction ("glass-*")
};

struct NamedSpectrumTable {
  const char* name;  // as pbrt-v4 spells it
  NamedSpectrumKind kind;
  std::span<const double> pairs;  // wavelength (nm, increasing), value, wavelength, value, ...
};
// pbrt-v4's named spectra that carry data here (37 tables).
std::span<const NamedSpectrumTable> named_spectrum_tables();

// pbrt-v4's camera sensor names ("canon_eos_5d", ...; the spectra are NAME_r/_g/_b): names only.
std::span<const char* const> camera_sensor_names();

}  // namespace dermis
