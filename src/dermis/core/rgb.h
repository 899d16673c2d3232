// RGB radiometric quantities: three linear channels (Rec.709 primaries).
#pragma once

#include <algorithm>
#include <cmath>

namespace dermis {

struct RGB {
  float c[3] = {0, 0, 0};
  constexpr RGB() = default;
  constexpr explicit RGB(float v) : c{v, v, v} {}
  constexpr RGB(float r, float g, float b) : c{r, g, b} {}
  constexpr float operator[](int i) const { return c[i]; }
  constexpr float& operator[](int i) { return c[i]; }
  constexpr float r() const { return c[0]; }
  constexpr float g() const { return c[1]; }
  constexpr float b() const { return c[2]; }
  constexpr RGB operator+(RGB o) const { return {c[0] + o.c[0], c[1] + o.c[1], c[2] + o.c[2]}; }
  constexpr RGB operator-(RGB o) const { return {c[0] - o.c[0], c[1] - o.c[1], c[2] - o.c[2]}; }
  constexpr RGB operator*(RGB o) const { return {c[0] * o.c[0], c[1] * o.c[1], c[2] * o.c[2]}; }
  constexpr RGB operator/(RGB o) const { return {c[0] / o.c[0], c[1] / o.c[1], c[2] / o.c[2]}; }
  constexpr RGB operator*(float s) const { return {c[0] * s, c[1] * s, c[2] * s}; }
  constexpr RGB operator/(float s) const { return {c[0] / s, c[1] / s, c[2] / s}; }
  constexpr RGB& operator+=(RGB o) {
    for (int i = 0; i < 3; ++i) c[i] += o.c[i];
    return *this;
  }
  constexpr RGB& operator*=(RGB o) {
    for (int i = 0; i < 3; ++i) c[i] *= o.c[i];
    return *this;
  }
  constexpr RGB& operator*=(float s) {
    for (int i = 0; i < 3; ++i) c[i] *= s;
    return *this;
  }
  constexpr RGB& operator/=(float s) {
    for (int i = 0; i < 3; ++i) c[i] /= s;
    return *this;
  }
  constexpr bool operator==(const RGB&) const = default;
  constexpr bool is_black() const { return c[0] == 0 && c[1] == 0 && c[2] == 0; }
  constexpr float max() const { return std::max(c[0], std::max(c[1], c[2])); }
  constexpr float average() const { return (c[0] + c[1] + c[2]) / 3.0f; }
  // Relative luminance of linear Rec.709 RGB.
  constexpr float luminance() const { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }
  bool is_finite() const { return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]); }
};

constexpr RGB operator*(float s, RGB v) { return v * s; }
inline RGB exp(RGB v) { return {std::exp(v[0]), std::exp(v[1]), std::exp(v[2])}; }
inline RGB sqrt(RGB v) { return {std::sqrt(v[0]), std::sqrt(v[1]), std::sqrt(v[2])}; }

}  // namespace dermis
