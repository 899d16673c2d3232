// The pbrt-v4 scene parser: reads the documented subset of the format (docs/scene-format.md)
// into a SceneDesc. Malformed input throws SceneError ("file:line:col: error: message");
// things Dermis ignores or approximates become warnings in SceneDesc::diagnostics.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "dermis/core/load_monitor.h"
#include "dermis/scene/file_access.h"
#include "dermis/scene/scene_desc.h"

namespace dermis {

// Parses a pbrt-v4 file (and its Includes/Imports). `access`: which files the scene may
// name (scene/file_access.h; by default any, as in pbrt-v4). With a monitor, the files and
// meshes read report their progress (core/load_monitor.h), and the parse stops with
// Interrupted once the monitor's cancel flag is set.
SceneDesc parse_scene_file(const std::string& path, const FileAccessOptions& access = {},
                           const LoadMonitor* monitor = nullptr);

// Same for a string; `name` is used in messages; relative paths resolve against base_dir
// (which is also the scene's directory for `access`).
SceneDesc parse_scene_string(const std::string& text, const std::string& name = "<string>",
                             const std::string& base_dir = ".", const FileAccessOptions& access = {},
                             const LoadMonitor* monitor = nullptr);

// Re-reads material `index` of a parsed scene with the parameters in `params_text`
// (pbrt parameter text, e.g. "\"string method\" \"disk\" \"rgb mfp\" [1 2 3]") replacing
// those of the same name, as if the scene had been written that way; meshes and
// textures are not read again. Messages about the new text name `source_name`.
// Throws SceneError (file:line:col) or std::out_of_range for a bad index; returns the
// warnings the new parameters caused.
std::vector<std::string> set_material_parameters(SceneDesc& scene, std::size_t index, const std::string& params_text,
                                                 const std::string& source_name = "<parameters>");

}  // namespace dermis
