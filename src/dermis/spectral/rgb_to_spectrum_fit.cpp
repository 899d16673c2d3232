#include "dermis/spectral/rgb_to_spectrum_fit.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "dermis/spectral/cie_observer.h"

namespace dermis {

namespace {

// A reflectance's linear sRGB per unit of spectrum at each node: the rows of
// M_XYZ->sRGB [x y z](lambda) D65(lambda) / sum(D65 y) (CIE 015:2004, eqs. 7.1-7.3).
struct ColourWeights {
  std::vector<double> t;                      // the node's wavelength in [0, 1]
  std::vector<std::array<double, 3>> weight;  // its weight per channel
};

// At every nanometre (reflectance_rgb's sums).
const ColourWeights& weights_1nm() {
  static const ColourWeights w = [] {
    const CieTables& c = cie_tables();
    ColourWeights w;
    for (int i = 0; i < CieTables::kSamples; ++i) {
      const double d = c.d65[i] / c.d65_y;
      const auto rgb = xyz_to_linear_srgb(c.x[i] * d, c.y[i] * d, c.z[i] * d);
      w.t.push_back(double(i) / (CieTables::kSamples - 1));
      w.weight.push_back(rgb);
    }
    return w;
  }();
  return w;
}

// At every 5 nm for the fits, each node's weight the 1 nm weights under its hat function
// (exact for a spectrum linear between nodes; the sigmoids are smooth at that scale).
const ColourWeights& weights_5nm() {
  static const ColourWeights w = [] {
    const ColourWeights& fine = weights_1nm();
    constexpr int kStep = 5, kNodes = (CieTables::kSamples - 1) / kStep + 1;
    ColourWeights w;
    w.t.resize(kNodes);
    w.weight.assign(kNodes, {0, 0, 0});
    for (int j = 0; j < kNodes; ++j) w.t[j] = fine.t[std::size_t(j * kStep)];
    for (int i = 0; i < CieTables::kSamples; ++i) {
      const int j = std::min(i / kStep, kNodes - 2);
      const double f = double(i - j * kStep) / kStep;  // hat functions of nodes j and j + 1
      for (int k = 0; k < 3; ++k) {
        w.weight[std::size_t(j)][k] += (1 - f) * fine.weight[std::size_t(i)][k];
        w.weight[std::size_t(j) + 1][k] += f * fine.weight[std::size_t(i)][k];
      }
    }
    return w;
  }();
  return w;
}

// The colour of the sigmoid of c0 t^2 + c1 t + c2 and, if wanted, its derivatives in c.
std::array<double, 3> colour_of(const ColourWeights& w, const double c[3], double jacobian[3][3] = nullptr) {
  std::array<double, 3> rgb{0, 0, 0};
  if (jacobian)
    for (int k = 0; k < 3; ++k) jacobian[k][0] = jacobian[k][1] = jacobian[k][2] = 0;
  for (std::size_t j = 0; j < w.t.size(); ++j) {
    const double t = w.t[j], x = (c[0] * t + c[1]) * t + c[2];
    const double q = std::sqrt(1 + x * x);
    const double s = std::isinf(x) ? (x > 0 ? 1 : 0) : 0.5 + x / (2 * q);  // eq. (3)
    for (int k = 0; k < 3; ++k) rgb[k] += s * w.weight[j][k];
    if (jacobian) {
      const double d = 1 / (2 * q * q * q);  // S'(x)
      const double dx[3] = {t * t, t, 1};
      for (int k = 0; k < 3; ++k)
        for (int m = 0; m < 3; ++m) jacobian[k][m] += d * dx[m] * w.weight[j][k];
    }
  }
  return rgb;
}

// Solves a x = b (3 x 3) by Gaussian elimination with partial pivoting; false if singular.
bool solve3(double a[3][3], double b[3], double x[3]) {
  for (int col = 0; col < 3; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 3; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    if (!(std::abs(a[pivot][col]) > 1e-300)) return false;
    std::swap(a[col], a[pivot]);
    std::swap(b[col], b[pivot]);
    for (int r = col + 1; r < 3; ++r) {
      const double f = a[r][col] / a[col][col];
      for (int m = col; m < 3; ++m) a[r][m] -= f * a[col][m];
      b[r] -= f * b[col];
    }
  }
  for (int r = 2; r >= 0; --r) {
    double s = b[r];
    for (int m = r + 1; m < 3; ++m) s -= a[r][m] * x[m];
    x[r] = s / a[r][r];
  }
  return true;
}

double largest(const std::array<double, 3>& r) { return std::max({std::abs(r[0]), std::abs(r[1]), std::abs(r[2])}); }

}  // namespace

RGB reflectance_rgb(const SigmoidPolynomial& s) {
  const double c[3] = {s.c0, s.c1, s.c2};
  const auto rgb = colour_of(weights_1nm(), c);
  return RGB(float(rgb[0]), float(rgb[1]), float(rgb[2]));
}

namespace {

// Damped Newton iterations on the colour's three equations, with the colours summed at
// `w`'s nodes: each step halved until the colour comes closer.
int newton(const ColourWeights& w, RGB target, double c[3], int max_iterations) {
  constexpr double kTolerance = 1e-7;
  double jacobian[3][3];
  auto residual = [&](const double* coefficients, double(*jac)[3]) {
    auto rgb = colour_of(w, coefficients, jac);
    for (int k = 0; k < 3; ++k) rgb[k] -= target[k];
    return rgb;
  };
  auto r = residual(c, jacobian);
  int iterations = 0;
  for (; iterations < max_iterations && largest(r) > kTolerance; ++iterations) {
    double b[3] = {-r[0], -r[1], -r[2]}, step[3];
    if (!solve3(jacobian, b, step)) break;
    bool improved = false;
    for (double scale = 1; scale > 1e-4 && !improved; scale /= 2) {
      const double next[3] = {c[0] + scale * step[0], c[1] + scale * step[1], c[2] + scale * step[2]};
      if (largest(residual(next, nullptr)) < largest(r)) std::copy(next, next + 3, c), improved = true;
    }
    if (!improved) break;
    r = residual(c, jacobian);
  }
  return iterations;
}

}  // namespace

SigmoidFit fit_sigmoid(RGB target, SigmoidPolynomial start) {
  double c[3] = {start.c0, start.c1, start.c2};
  SigmoidFit fit;
  // At 5 nm to come close, then at every nanometre (reflectance_rgb's sums) to finish.
  fit.iterations = newton(weights_5nm(), target, c, 100);
  fit.iterations += newton(weights_1nm(), target, c, 20);
  fit.polynomial = {float(c[0]), float(c[1]), float(c[2])};
  auto rgb = colour_of(weights_1nm(), c);
  for (int k = 0; k < 3; ++k) rgb[k] -= target[k];
  fit.residual = largest(rgb);
  return fit;
}

double RgbToSpectrumGrid::z_node(int i) {
  auto smoothstep = [](double x) { return x * x * (3 - 2 * x); };
  return smoothstep(smoothstep(double(i) / (kResolution - 1)));
}

std::vector<SigmoidPolynomial> fit_rgb_to_spectrum_grid() {
  constexpr int n = RgbToSpectrumGrid::kResolution;
  std::vector<SigmoidPolynomial> grid(RgbToSpectrumGrid::kCells);
  // Each (channel, y, x) column is marched along z from a fifth of the way up, each fit
  // starting from its neighbour's coefficients (continuation, the paper's sec. 4).
  tbb::parallel_for(0, 3 * n * n, [&](int column) {
    const int channel = column / (n * n), y = column / n % n, x = column % n;
    auto fit_cell = [&](int z, SigmoidPolynomial start) {
      const float zv = float(RgbToSpectrumGrid::z_node(z));
      RGB rgb;
      rgb[channel] = zv;
      rgb[(channel + 1) % 3] = float(x) / (n - 1) * zv;
      rgb[(channel + 2) % 3] = float(y) / (n - 1) * zv;
      const SigmoidPolynomial p = fit_sigmoid(rgb, start).polynomial;
      grid[RgbToSpectrumGrid::index(channel, z, y, x)] = p;
      return p;
    };
    const int start = n / 5;
    SigmoidPolynomial p;
    for (int z = start; z < n; ++z) p = fit_cell(z, p);
    p = grid[RgbToSpectrumGrid::index(channel, start, y, x)];
    for (int z = start - 1; z >= 0; --z) p = fit_cell(z, p);
  });
  return grid;
}

}  // namespace dermis
