#include "dermis/scene/diagnostics.h"

#include <fmt/format.h>

namespace dermis {

std::string SourceLoc::str() const { return fmt::format("{}:{}:{}", file, line, column); }

std::string excerpt(std::string_view text, std::size_t max) {
  if (text.size() <= max) return std::string(text);
  return fmt::format("{}... ({} bytes in all)", text.substr(0, max), text.size());
}

namespace {

// Every message stays readable: whatever a message quotes, it is cut at 2000 bytes.
std::string bounded(const std::string& message) {
  constexpr std::size_t kMaxMessage = 2000;
  return message.size() <= kMaxMessage ? message : excerpt(message, kMaxMessage);
}

}  // namespace

SceneError::SceneError(const SourceLoc& loc, const std::string& message)
    : std::runtime_error(fmt::format("{}: error: {}", loc.str(), bounded(message))), loc_(loc), message_(bounded(message)) {}

void Diagnostics::warn(const SourceLoc& loc, const std::string& message) {
  warnings.push_back(fmt::format("{}: warning: {}", loc.str(), bounded(message)));
}

}  // namespace dermis
