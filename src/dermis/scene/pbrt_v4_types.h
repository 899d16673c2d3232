// The type names pbrt-v4 accepts after each typed directive (Material "diffuse", Shape
// "sphere", ...), and the check that refuses any other name, as pbrt-v4 does ("%s: material
// type unknown."). A type pbrt-v4 knows but Dermis does not render is not refused here: the
// directive warns about it where it is handled (docs/scene-format.md lists them).
#pragma once

#include <span>
#include <string>

#include "dermis/scene/diagnostics.h"

namespace dermis {

// What a typed directive creates, for the message and the list of names pbrt-v4 accepts.
enum class TypedDirective { Material, LightSource, AreaLightSource, Camera, Shape, Texture, Medium, Film, PixelFilter };

// The type names pbrt-v4 accepts for `kind` (Dermis' own additions, such as Shape "objmesh",
// included).
std::span<const char* const> known_types(TypedDirective kind);

// Throws SceneError at `at` when `type` is none of known_types(kind): "unknown Material type
// 'difuse' (did you mean 'diffuse'?)", or the list of known names when nothing is near.
void require_known_type(TypedDirective kind, const std::string& type, const SourceLoc& at);

}  // namespace dermis
