// The pbrt-v4 scene parser: reads the documented subset of the format (docs/scene-format.md)
// into a SceneDesc. Malformed input throws SceneError ("file:line:col: error: message");
// things Dermis ignores or approximates become warnings in SceneDesc::diagnostics.
#pragma once

#include <string>

#include "dermis/scene/scene_desc.h"

namespace dermis {

// Parses a pbrt-v4 file (and its Includes/Imports).
SceneDesc parse_scene_file(const std::string& path);

// Same for a string; `name` is used in messages; relative paths resolve against base_dir.
SceneDesc parse_scene_string(const std::string& text, const std::string& name = "<string>",
                             const std::string& base_dir = ".");

}  // namespace dermis
