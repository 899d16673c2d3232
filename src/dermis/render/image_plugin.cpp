#include "dermis/render/image_plugin.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>

namespace dermis {

namespace {

constexpr const char* kPluginName = "libdermis_oiio.so";

ImagePlugin load() {
  std::vector<std::string> tried;
  void* handle = nullptr;
  auto attempt = [&](const std::string& path) {
    if (handle) return;
    handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) tried.push_back(fmt::format("{} ({})", path, ::dlerror()));
  };
  if (const char* env = std::getenv("DERMIS_OIIO_PLUGIN"); env && *env) {
    attempt(env);
  } else {
    // The folder of the executable or shared object this function was linked into.
    Dl_info info{};
    if (::dladdr(reinterpret_cast<void*>(&image_plugin), &info) && info.dli_fname) {
      std::error_code ec;
      std::filesystem::path dir = std::filesystem::canonical(info.dli_fname, ec).parent_path();
      for (int up = 0; up < 4 && !handle && !dir.empty(); ++up, dir = dir.parent_path()) {
        const std::filesystem::path candidate = dir / kPluginName;
        if (std::filesystem::exists(candidate, ec)) attempt(candidate.string());
      }
    }
    if (!handle) attempt(kPluginName);  // the loader's own search path (LD_LIBRARY_PATH, ...)
  }
  if (!handle) {
    std::string where;
    for (const std::string& t : tried) where += (where.empty() ? "" : "; ") + t;
    throw std::runtime_error(
        fmt::format("the image plugin {} (OpenImageIO) could not be loaded: {}", kPluginName, where));
  }
  ImagePlugin p;
  p.read = reinterpret_cast<decltype(p.read)>(::dlsym(handle, "dermis_plugin_read_image"));
  p.write = reinterpret_cast<decltype(p.write)>(::dlsym(handle, "dermis_plugin_write_image"));
  if (!p.read || !p.write) throw std::runtime_error(fmt::format("{} lacks its entry points", kPluginName));
  return p;
}

}  // namespace

const ImagePlugin& image_plugin() {
  static std::once_flag once;
  static ImagePlugin plugin;
  // A failed load throws out of call_once and is tried again by the next caller.
  std::call_once(once, [] { plugin = load(); });
  return plugin;
}

}  // namespace dermis
