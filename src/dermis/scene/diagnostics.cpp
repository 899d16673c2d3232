#include "dermis/scene/diagnostics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <vector>

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
    : std::runtime_error(fmt::format("{}: error: {}", loc.str(), bounded(message))),
      loc_(loc),
      message_(bounded(message)) {}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const bool same =
          std::tolower(static_cast<unsigned char>(a[i - 1])) == std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

void Diagnostics::warn(const SourceLoc& loc, const std::string& message) {
  warnings.push_back(fmt::format("{}: warning: {}", loc.str(), bounded(message)));
}

}  // namespace dermis
