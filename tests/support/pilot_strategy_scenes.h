// The scenes of SubsurfaceRandomWalk.ThePilotsStrategiesEqualAMediumInsideADielectric
// (render/subsurface_walk_test.cpp), shared with the calibration of its false-failure rate
// (bench/statistics/region_means_calibration.cpp): the walk with the dielectric boundary and
// one of the strategies the render's pilot may choose, and the same medium inside a
// dielectric rendered by the volumetric path tracer.
#pragma once

#include <array>
#include <string>

#include "support/lit_sphere_scene.h"

namespace dermis::testing {

inline const char* kPilotTestCoefficients = R"("rgb sigma_a" [0.05 0.15 0.3] "rgb sigma_s" [2 3 4] "float g" 0.3)";

// No guided flights and the channels drawn by throughput alone (channel preference 0), half
// the flights guided, and the larger guided share of 0.8 with channel preference 0.5.
inline const std::array<const char*, 3> kPilotStrategies = {
    "\"float guidedshare\" 0 \"float channelpreference\" 0", "\"float guidedshare\" 0.5 \"float channelpreference\" 0",
    "\"float guidedshare\" 0.8 \"float channelpreference\" 0.5"};

inline std::string pilot_strategy_walk_scene(const std::string& strategy) {
  return lit_sphere_header(16) + "Material \"subsurface\" " + kPilotTestCoefficients +
         " \"float eta\" 1.4 \"string method\" \"randomwalk\" \"string boundary\" \"dielectric\" " + strategy +
         "\nShape \"sphere\"\n";
}

inline std::string pilot_strategy_volume_scene() {
  return lit_sphere_header(16) + "MakeNamedMedium \"m\" \"string type\" \"homogeneous\" " + kPilotTestCoefficients +
         "\nMediumInterface \"m\" \"\"\nMaterial \"dielectric\" \"float eta\" 1.4\nShape \"sphere\"\n";
}

}  // namespace dermis::testing
