#include "dermis/scene/diagnostics.h"

#include <fmt/format.h>

namespace dermis {

std::string SourceLoc::str() const { return fmt::format("{}:{}:{}", file, line, column); }

SceneError::SceneError(const SourceLoc& loc, const std::string& message)
    : std::runtime_error(fmt::format("{}: error: {}", loc.str(), message)), loc_(loc), message_(message) {}

void Diagnostics::warn(const SourceLoc& loc, const std::string& message) {
  warnings.push_back(fmt::format("{}: warning: {}", loc.str(), message));
}

}  // namespace dermis
