#include "dermis/scene/file_access.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

namespace dermis {

namespace fs = std::filesystem;

namespace {

// `p` with every symbolic link and `..` resolved, as far as it exists (the rest lexically).
fs::path resolved(const std::string& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p), ec);
  return ec ? fs::absolute(p).lexically_normal() : r;
}

}  // namespace

FileAccess::FileAccess(const FileAccessOptions& options, const std::string& scene_dir)
    : confined_(options.confined || !options.allowed_dirs.empty()), named_files_(options.named_files) {
  if (!confined_) return;
  roots_.push_back(resolved(scene_dir).string());
  for (const std::string& d : options.allowed_dirs) roots_.push_back(resolved(d).string());
}

bool FileAccess::inside(const std::string& path, const std::vector<std::string>& roots) const {
  const fs::path p = resolved(path);
  return std::any_of(roots.begin(), roots.end(), [&](const std::string& root) {
    // Component by component: "/scene" contains "/scene/a.ply", not "/scene2/a.ply".
    const fs::path r(root);
    const auto ri = std::mismatch(r.begin(), r.end(), p.begin(), p.end()).first;
    return ri == r.end() || (std::next(ri) == r.end() && ri->empty());  // a trailing '/' in root
  });
}

std::string FileAccess::roots_text(const std::vector<std::string>& roots) const {
  std::string text;
  for (const std::string& r : roots) text += (text.empty() ? "'" : ", '") + r + "'";
  return text;
}

void FileAccess::check_read(const std::string& path, const std::string& as_written, const SourceLoc& at,
                            const std::string& what) const {
  if (named_files_) named_files_->push_back(path);
  if (!confined_ || inside(path, roots_)) return;
  throw SceneError(at,
                   fmt::format("{} '{}' is outside the directories this scene may read ({}; --confine), at '{}' "
                               "once resolved: move it inside, or allow its directory with --allow-path",
                               what, excerpt(as_written), roots_text(roots_), excerpt(resolved(path).string(), 200)));
}

void FileAccess::check_write(const std::string& path, const std::string& as_written, const SourceLoc& at,
                             const std::string& what) const {
  if (!confined_) return;
  std::vector<std::string> roots = roots_;
  if (const std::string cwd = resolved(".").string(); std::find(roots.begin(), roots.end(), cwd) == roots.end())
    roots.push_back(cwd);
  if (inside(path, roots)) return;
  throw SceneError(at,
                   fmt::format("{} '{}' is outside the directories this scene may write ({}; --confine), at '{}' "
                               "once resolved: give the output with -o",
                               what, excerpt(as_written), roots_text(roots), excerpt(resolved(path).string(), 200)));
}

}  // namespace dermis
