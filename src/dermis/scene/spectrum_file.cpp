#include "dermis/scene/spectrum_file.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <filesystem>

#include "dermis/scene/gzip_file.h"

namespace dermis {

namespace {

// Spectrum files are a few kilobytes; a larger one is not a spectrum.
constexpr uint64_t kMaxSpectrumFileBytes = uint64_t(64) << 20;

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

}  // namespace

SampledSpectrum read_spectrum_file(const std::string& path, const SourceLoc& named_at) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw SceneError(named_at, fmt::format("spectrum file '{}' is a directory", path));
  if (!std::filesystem::is_regular_file(path, ec))
    throw SceneError(named_at, fmt::format("spectrum file '{}' is not a regular file", path));
  if (std::filesystem::file_size(path, ec) > kMaxSpectrumFileBytes)
    throw SceneError(named_at, fmt::format("spectrum file '{}' is larger than {} MiB: not a spectrum", path,
                                           kMaxSpectrumFileBytes >> 20));
  std::string text;
  try {
    text = read_file_contents(path, kMaxSpectrumFileBytes);
  } catch (const FileReadError& e) {
    throw SceneError(named_at, fmt::format("spectrum file '{}': {}", path, e.reason()));
  }
  SampledSpectrum s;
  SourceLoc last{path, 1, 1};  // where the last number starts
  int line = 1, column = 1;
  size_t count = 0;
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '\n') {
      ++line, column = 1, ++i;
    } else if (is_space(c)) {
      ++column, ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else {
      size_t end = i;
      while (end < text.size() && !is_space(text[end]) && text[end] != '#') ++end;
      const std::string_view word(text.data() + i, end - i);
      const SourceLoc at{path, line, column};
      double v = 0;
      const char* first = word.data() + (word.front() == '+' ? 1 : 0);
      auto [ptr, ec] = std::from_chars(first, word.data() + word.size(), v);
      if (ec != std::errc() || ptr != word.data() + word.size() || !std::isfinite(v))
        throw SceneError(at, fmt::format("spectrum file: '{}' is not a number (expected wavelength (nm) and value "
                                         "pairs)",
                                         excerpt(word)));
      if (count % 2 == 0) {
        if (v <= 0) throw SceneError(at, fmt::format("spectrum file: wavelength {} nm is not positive", v));
        if (!s.lambda.empty() && v <= s.lambda.back())
          throw SceneError(
              at, fmt::format("spectrum file: wavelengths must increase ({} nm after {} nm)", v, s.lambda.back()));
        s.lambda.push_back(v);
      } else {
        s.value.push_back(v);
      }
      ++count;
      last = at;
      column += int(end - i);
      i = end;
    }
  }
  if (count == 0)
    throw SceneError({path, 1, 1}, "spectrum file holds no numbers (expected wavelength (nm) and value pairs)");
  if (count % 2 != 0)
    throw SceneError(last, fmt::format("spectrum file: {} numbers, not pairs: wavelength {} nm has no value", count,
                                       s.lambda.back()));
  return s;
}

}  // namespace dermis
