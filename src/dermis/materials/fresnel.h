// Forwarding header: Fresnel reflectance, reflect and refract live in core/fresnel.h
// (one implementation for the renderer, the random walk and the half-space simulator).
// Kept so that includes of this path keep compiling; include core/fresnel.h instead.
#pragma once

#include "dermis/core/fresnel.h"
