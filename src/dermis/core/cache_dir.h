// Where Dermis keeps what it can rebuild but would rather not (tables that take seconds):
// $XDG_CACHE_HOME/dermis, else $HOME/.cache/dermis; empty when neither is set (no cache).
#pragma once

#include <cstdlib>
#include <string>

namespace dermis {

inline std::string default_cache_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/dermis";
  if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/dermis";
  return {};
}

}  // namespace dermis
