// The sampler regions of a path (Sampler::region(dimension, tag), core/sampler.h): a
// decision that must not shift the dimensions of the vertex it is made at draws from a
// region of its own, named by a tag. Every tag the integrator uses is here, once.
#pragma once

#include <cstdint>

namespace dermis {

enum SamplerRegion : uint32_t {
  // The roulette of the camera's split-off smooth reflection (path_state.h
  // reflection_survival, first_vertex_survives): one number, in the region of the dimension
  // the decision is made at (the reflected path's first vertex: of its first dimension).
  kReflectionRouletteRegion = 0x5e1eu,
  // The reflected path split off at the camera's first smooth hit (camera_reflection.h).
  kReflectedPathRegion = 0x5e1fu,
  // A subsurface exit's sampler (subsurface_vertex.cpp), from the entry vertex's dimension.
  kSubsurfaceExitRegion = 0x55e1u,
  // The camera's first entry's exits drawn as one sequence (Sampler::set_split): this tag
  // plus the exit count, each count its own dimensions.
  kSplitExitsRegion = 0x5e170000u,
  // At an entry with several exits, exit k >= 1 (plus k): its sampler, then at the camera's
  // first entry its lobe and its way on (subsurface_vertex.cpp).
  kExtraExitRegion = 0x5a3e0u,
  kExtraExitLobeRegion = 0x5c0e0u,
  kExtraExitPathRegion = 0x5c0f0u,
  // Path splitting's copy k >= 1 at a subsurface exit (plus k): its lobe and its path.
  kSplitCopyLobeRegion = 0x5b117u,
  kSplitCopyPathRegion = 0x5b127u,
  // The nested path of transmitted_irradiance (integrator.h).
  kTransmittedIrradianceRegion = 0x1aadu,
  // A spectral camera sample's wavelengths (renderer.cpp), one number from the camera's
  // block: the dimensions of the path are those of an RGB render.
  kWavelengthsRegion = 0x1a3bdu,
};

// Not a region: mixed into a vertex's sample hash to seed a layered BSDF's own random
// streams (materials/bsdf.h), fresh at every vertex.
inline constexpr uint64_t kCoatedSeedSalt = 0xc0a7edull;

}  // namespace dermis
