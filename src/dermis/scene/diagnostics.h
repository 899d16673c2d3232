// Where a piece of scene input came from, and the errors and warnings about it.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace dermis {

struct SourceLoc {
  std::string file;
  int line = 0;
  int column = 0;
  // "file:line:col"
  std::string str() const;
};

// Malformed input. what() is "file:line:col: message" ready for the user.
// Input text quoted in a message: as is up to `max` bytes, else its start and its size
// (a 10 MB token is not echoed into a log).
std::string excerpt(std::string_view text, std::size_t max = 64);

// Levenshtein distance, case-insensitive (short strings only), for "did you mean" hints.
std::size_t edit_distance(std::string_view a, std::string_view b);

class SceneError : public std::runtime_error {
 public:
  SceneError(const SourceLoc& loc, const std::string& message);
  const SourceLoc& loc() const { return loc_; }
  const std::string& message() const { return message_; }

 private:
  SourceLoc loc_;
  std::string message_;
};

// Non-fatal remarks (unsupported directive, unused parameter): "file:line:col: warning: ...".
struct Diagnostics {
  std::vector<std::string> warnings;
  void warn(const SourceLoc& loc, const std::string& message);
};

}  // namespace dermis
