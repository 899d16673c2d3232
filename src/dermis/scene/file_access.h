// Which files a scene may name. By default any file the process can read, as in pbrt-v4
// (production scenes use `../` and absolute paths). Confined (`dermis render --confine`,
// `--allow-path DIR`), for farms that render scenes from strangers: every file the scene
// names -- Include and Import, meshes, image textures and environment maps, spectrum files,
// and the output it names in Film "filename" -- must resolve, after `..` and symbolic links,
// inside the main scene file's directory or one of the allowed directories.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "dermis/scene/diagnostics.h"

namespace dermis {

struct FileAccessOptions {
  bool confined = false;
  std::vector<std::string> allowed_dirs;  // besides the scene's directory; implies confined
  // Where set, every file the scene names to be read (resolved) is appended to it, before it
  // is read and whether or not reading it succeeds: what `dermis render --watch` watches.
  std::vector<std::string>* named_files = nullptr;
};

class FileAccess {
 public:
  // Any file (pbrt-v4's behaviour).
  FileAccess() = default;
  // Confined to `scene_dir` and options.allowed_dirs (each made canonical now), when
  // options.confined or any directory is allowed; else any file.
  FileAccess(const FileAccessOptions& options, const std::string& scene_dir);

  bool confined() const { return confined_; }
  // Throws SceneError at `at` when confined and `path` (absolute) resolves outside every
  // allowed directory: "<what> '<as written>' is outside the directories this scene may read ...".
  void check_read(const std::string& path, const std::string& as_written, const SourceLoc& at,
                  const std::string& what) const;
  // The same for a file the scene asks to be written (Film "filename"); the working directory
  // is allowed too.
  void check_write(const std::string& path, const std::string& as_written, const SourceLoc& at,
                   const std::string& what) const;

 private:
  bool inside(const std::string& path, const std::vector<std::string>& roots) const;
  std::string roots_text(const std::vector<std::string>& roots) const;
  bool confined_ = false;
  std::vector<std::string> roots_;  // canonical
  std::vector<std::string>* named_files_ = nullptr;
};

}  // namespace dermis
