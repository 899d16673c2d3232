// Command-line checks with messages a user can act on. CLI11's PositiveNumber and
// NonNegativeNumber answer `--spp 0` with "Value 0 not in range 0.000000 to <a 309-digit
// number>"; these say "--spp: must be a positive number, got '0'" (exit status 2).
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <string>

namespace dermis::app {

// A finite number (the option's own type still decides integer or not) that is > 0, or
// >= 0 when `allow_zero`.
inline CLI::Validator number_check(bool allow_zero) {
  const char* what = allow_zero ? "a non-negative number" : "a positive number";
  return CLI::Validator(
      [allow_zero, what](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        const bool ok = end != s.c_str() && *end == '\0' && std::isfinite(v) && (allow_zero ? v >= 0 : v > 0);
        return ok ? std::string() : "must be " + std::string(what) + ", got '" + s.substr(0, 64) + "'";
      },
      allow_zero ? "NONNEGATIVE" : "POSITIVE");
}

inline const CLI::Validator kPositive = number_check(false);
inline const CLI::Validator kNonNegative = number_check(true);

}  // namespace dermis::app
