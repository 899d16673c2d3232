// Tests of the disk-projection probe sampler (King et al. 2013; METHODS 2.1):
// the combined area pdf integrates to the hit probability over planes (two independent
// quadratures), chi-square of hit positions on planes and on a sphere (every hit
// counts), and the flat-plane estimator recovers the kept energy.
#include "dermis/sss/probe/disk_probe.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "dermis/core/rng.h"
#include "dermis/sss/probe/probe_test_support.h"
#include "support/chi_square.h"

namespace dermis::sss {
namespace {

using testing::integrate_pieces;
using testing::integrate_plane_polar;
using testing::MeanAndError;
using testing::TestPlane;

struct NamedProfile {
  std::string name;
  ProfileRGB profile;
  RGB weights;
};

std::vector<NamedProfile> test_profiles() {
  return {
      {"gaussian", make_gaussian_rgb(RGB(0.8f, 0.6f, 0.4f), RGB(0.04f, 0.09f, 0.25f)), RGB(0.8f, 0.6f, 0.4f)},
      {"skin", make_skin_rgb(1.0), RGB(1.0f, 0.7f, 0.5f)},
      {"burley", make_burley_rgb(RGB(0.8f, 0.5f, 0.3f), RGB(0.5f, 0.3f, 0.2f)), RGB(1.0f)},
      {"dipole", make_dipole_rgb(RGB(0.8f, 0.5f, 0.3f), RGB(0.3f, 0.2f, 0.1f), 1.3), RGB(0.8f, 0.5f, 0.3f)},
  };
}

// A frame at the origin whose tangents are rotated about N (so that no axis is special).
ProbeFrame test_frame() {
  const Vec3d n = normalize(Vec3d(0.1, -0.2, 1.0));
  ProbeFrame f = ProbeFrame::around(Vec3d(0.3, -0.1, 0.2), n);
  const double c = std::cos(0.7), s = std::sin(0.7);
  const Vec3d t = f.t * c + f.b * s, b = f.b * c - f.t * s;
  f.t = t;
  f.b = b;
  return f;
}

// Unit normal tilted from N by `tilt` towards a direction between T and B.
Vec3d tilted_normal(const ProbeFrame& f, double tilt) {
  const Vec3d side = normalize(f.t * 0.8 + f.b * 0.6);
  return normalize(f.n * std::cos(tilt) + side * std::sin(tilt));
}

// Strategy radii of the sampler: where the pdf jumps (at |x - P| = R_i).
std::vector<double> radii(const DiskProbeSampler& s) {
  std::vector<double> r;
  for (int i = 0; i < s.strategy_count(); ++i) r.push_back(s.strategy_radius(i));
  return r;
}

// Reference strategies rebuilt from the profile (independently of the sampler): the
// probability q_i, the sphere radius R_i and the radial CDF F_i in closed form.
struct ReferenceStrategy {
  double probability, radius;
  std::function<double(double)> cdf;
};
std::vector<ReferenceStrategy> reference_strategies(const ProfileRGB& profile, RGB weights) {
  const double total = double(weights[0]) + weights[1] + weights[2];
  std::vector<ReferenceStrategy> out;
  for (int c = 0; c < 3; ++c) {
    const double qc = weights[c] / total;
    if (qc == 0) continue;
    const RadialProfile& p = profile[c];
    auto gaussian_cdf = [](const GaussianProfile& g) {
      return [g](double r) { return -std::expm1(-r * r / (2 * g.variance())) / GaussianProfile::kept_fraction(); };
    };
    if (const auto* sum = p.get_if<SumOfGaussiansProfile>()) {
      for (int j = 0; j < sum->lobe_count(); ++j)
        if (qc * sum->lobe_probability(j) > 0)
          out.push_back({qc * sum->lobe_probability(j), sum->lobe(j).r_max(), gaussian_cdf(sum->lobe(j))});
    } else if (const auto* g = p.get_if<GaussianProfile>()) {
      out.push_back({qc, g->r_max(), gaussian_cdf(*g)});
    } else if (const auto* b = p.get_if<BurleyProfile>()) {
      out.push_back({qc, b->r_max(), [b](double r) { return b->cdf(r) / b->kept_fraction(); }});
    } else if (const auto* d = p.get_if<DipoleProfile>()) {
      out.push_back(
          {qc, d->r_max(), [d](double r) { return d->energy_within(r) / (d->albedo() * d->kept_fraction()); }});
    }
  }
  return out;
}

// Expected number of hits per probe on the plane through P with normal n, from the disk
// side: the disk point at (r, phi) on axis a gives a line that meets the plane at height
// t = -r g_a(phi) with g_a = (cos phi U.n + sin phi W.n) / (V.n); the hit is on the segment
// iff r^2 (1 + g^2) <= R_i^2. So E = sum_a P_a sum_i q_i (1/2pi) int F_i(R_i / sqrt(1 + g_a^2)) dphi.
double hits_per_probe_from_disks(const ProbeFrame& f, const std::vector<ReferenceStrategy>& strategies,
                                 ProbeAxisProbabilities axes, Vec3d n) {
  const double pa[3] = {axes.normal, axes.tangent, axes.bitangent};
  const double axis_total = pa[0] + pa[1] + pa[2];
  double e = 0;
  for (int a = 0; a < 3; ++a) {
    const Vec3d v = f.axis(a), u = f.axis((a + 1) % 3), w = f.axis((a + 2) % 3);
    const double vn = dot(v, n);
    if (pa[a] == 0 || std::abs(vn) < 1e-15) continue;
    for (const auto& s : strategies) {
      auto integrand = [&](double phi) {
        const double g = (std::cos(phi) * dot(u, n) + std::sin(phi) * dot(w, n)) / vn;
        return s.cdf(s.radius / std::sqrt(1 + g * g));
      };
      e += pa[a] / axis_total * s.probability * testing::integrate_capped(integrand, 0, 2 * kPiD, 1e-11) / (2 * kPiD);
    }
  }
  return e;
}

TEST(DiskProbe, SingleAxisOnThePlanePerpendicularToNIsTheDiskPdf) {
  const ProbeFrame f = test_frame();
  for (const auto& [name, profile, weights] : test_profiles()) {
    const DiskProbeSampler sampler(profile, weights, ProbeAxisProbabilities::single_axis());
    const TestPlane plane(f.p, f.n);
    const double total = double(weights[0]) + weights[1] + weights[2];
    for (double s : {1e-3, 0.01, 0.1, 0.5, 1.0, 2.5}) {
      const double r = s * sampler.max_radius() * 0.999;
      double disk = 0;  // sum_c q_c pdf_c(r) / (2 pi r), from the channel profiles directly
      for (int c = 0; c < 3; ++c) disk += weights[c] / total * profile[c].pdf_radius(r) / (2 * kPiD * r);
      const double pdf = sampler.pdf_area(f, plane.point(r, 1.3), f.n);
      EXPECT_NEAR(pdf, disk, 1e-12 * disk + 1e-300) << name << " r " << r;
    }
    // ... and it integrates to one over the plane (adaptive quadrature, 1e-6).
    const double integral = integrate_plane_polar(
        plane, [&](Vec3d x) { return sampler.pdf_area(f, x, f.n); }, 0, sampler.max_radius(), 0, 2 * kPiD,
        radii(sampler), 1e-9);
    EXPECT_NEAR(integral, 1.0, 1e-6) << name;
  }
}

TEST(DiskProbe, AreaPdfIntegratesToTheHitProbabilityOnTiltedPlanes) {
  const ProbeFrame f = test_frame();
  const auto profiles = test_profiles();
  for (int k : {0, 1, 2}) {  // gaussian, skin, burley
    const auto& [name, profile, weights] = profiles[k];
    const auto reference = reference_strategies(profile, weights);
    for (auto axes : {ProbeAxisProbabilities{}, ProbeAxisProbabilities::single_axis()}) {
      const DiskProbeSampler sampler(profile, weights, axes);
      // The sampler's strategies are the reference's, those of one shape (a lobe that the
      // channels share) merged into one with the sum of their probabilities.
      std::vector<double> distinct_radii;
      for (const auto& r : reference)
        if (std::find(distinct_radii.begin(), distinct_radii.end(), r.radius) == distinct_radii.end())
          distinct_radii.push_back(r.radius);
      ASSERT_EQ(sampler.strategy_count(), int(distinct_radii.size())) << name;
      for (int i = 0; i < sampler.strategy_count(); ++i) {
        double probability = 0;
        for (const auto& r : reference)
          if (r.radius == sampler.strategy_radius(i)) probability += r.probability;
        EXPECT_NEAR(sampler.strategy_probability(i), probability, 1e-12) << name << " strategy " << i;
      }
      for (double tilt_deg : {0.0, 30.0, 60.0, 85.0}) {
        const Vec3d n = tilted_normal(f, tilt_deg * kPiD / 180);
        const TestPlane plane(f.p, n);
        const double integral = integrate_plane_polar(
            plane, [&](Vec3d x) { return sampler.pdf_area(f, x, n); }, 0, sampler.max_radius(), 0, 2 * kPiD,
            radii(sampler), 1e-9);
        const double expected = hits_per_probe_from_disks(f, reference, axes, n);
        EXPECT_NEAR(integral, expected, 2e-6)
            << name << (axes.normal == 1 ? " single axis" : " three axes") << " tilt " << tilt_deg;
        // The probability lost beyond the spheres is what keeps it below one.
        EXPECT_LE(integral, 1 + 1e-6);
        if (tilt_deg == 0 && axes.normal == 1) {
          EXPECT_NEAR(integral, 1.0, 1e-6);
        }
        if (tilt_deg == 0 && axes.normal != 1) {
          EXPECT_NEAR(integral, 0.5, 1e-6);  // T and B never hit
        }
      }
    }
  }
}

// Chi-square of the hit positions on a plane, bins in polar coordinates about the foot of
// P, plus one bin for probes that miss.
// folded: the two-number form (one number cut into the axis, the strategy and the radius).
void expect_plane_hits_match_pdf(const DiskProbeSampler& sampler, const ProbeFrame& f, const TestPlane& plane,
                                 const std::string& what, uint64_t seed, bool folded) {
  const double h = std::abs(dot(f.p - plane.origin, plane.normal));
  const double s_max = std::sqrt(std::max(0.0, sampler.max_radius() * sampler.max_radius() - h * h));
  constexpr int kRadial = 10, kAngular = 8, kProbes = 100000;
  std::vector<double> s_edges(kRadial + 1);
  for (int i = 0; i <= kRadial; ++i)
    s_edges[i] = s_max * std::sqrt(double(i) / kRadial) * std::sqrt(double(i) / kRadial);
  std::vector<double> breaks;
  for (double r : radii(sampler))
    if (r > h) breaks.push_back(std::sqrt(r * r - h * h));
  std::vector<double> expected(kRadial * kAngular + 1), observed(kRadial * kAngular + 1, 0.0);
  double hit_total = 0;
  for (int i = 0; i < kRadial; ++i)
    for (int j = 0; j < kAngular; ++j) {
      const double e = integrate_plane_polar(
          plane, [&](Vec3d x) { return sampler.pdf_area(f, x, plane.normal); }, s_edges[i], s_edges[i + 1],
          2 * kPiD * j / kAngular, 2 * kPiD * (j + 1) / kAngular, breaks, 1e-9);
      expected[i * kAngular + j] = e * kProbes;
      hit_total += e;
    }
  expected.back() = (1 - hit_total) * kProbes;
  Rng rng(seed, 1);
  for (int n = 0; n < kProbes; ++n) {
    const double u0 = rng.uniform_double(), u1 = rng.uniform_double();
    const auto smp =
        folded ? sampler.sample(f, u0, u1) : sampler.sample(f, u0, u1, rng.uniform_double(), rng.uniform_double());
    Vec3d x;
    if (!testing::intersect(smp.segment, plane, &x)) {
      observed.back() += 1;
      continue;
    }
    double s, psi;
    plane.polar(x, &s, &psi);
    const int i = std::min(int(std::upper_bound(s_edges.begin(), s_edges.end(), s) - s_edges.begin()) - 1, kRadial - 1);
    const int j = std::min(int(psi / (2 * kPiD) * kAngular), kAngular - 1);
    observed[i * kAngular + j] += 1;
  }
  const auto result = dermis::testing::chi_square(observed, expected);
  EXPECT_GT(result.p_value, dermis::testing::kChiSquareAlpha)
      << what << ": chi-square " << result.statistic << " dof " << result.dof;
}

TEST(DiskProbe, HitsOnPlanesMatchTheAreaPdf) {
  const ProbeFrame f = test_frame();
  const auto profiles = test_profiles();
  uint64_t seed = 100;
  for (int k : {0, 1}) {  // gaussian (3 channels), skin (lobes)
    const auto& [name, profile, weights] = profiles[k];
    for (auto axes : {ProbeAxisProbabilities{}, ProbeAxisProbabilities::single_axis()}) {
      const DiskProbeSampler sampler(profile, weights, axes);
      for (bool folded : {false, true}) {
        const std::string what = name + (axes.normal == 1 ? " single axis" : " three axes") + (folded ? " folded" : "");
        expect_plane_hits_match_pdf(sampler, f, TestPlane(f.p, tilted_normal(f, 0.9)), what + " tilted plane", ++seed,
                                    folded);
        const Vec3d n = tilted_normal(f, 0.5);
        expect_plane_hits_match_pdf(sampler, f, TestPlane(f.p - n * (0.25 * sampler.max_radius()), n),
                                    what + " offset plane", ++seed, folded);
      }
    }
  }
}

// The two-number form cuts one number into the axis, the strategy and the radius: from
// 4096 evenly spaced numbers each (axis, strategy) takes its share (within one) and its
// radii grow with the number, one contiguous run of it each, so a stratified number gives
// every strategy stratified radii. The angle is the second number's, untouched.
TEST(DiskProbe, OneNumberCutIntoTheChoicesStratifiesEachStrategysRadii) {
  const ProbeFrame f = test_frame();
  for (const auto& [name, profile, weights] : test_profiles()) {
    const DiskProbeSampler sampler(profile, weights, ProbeAxisProbabilities{0.75, 0.125, 0.125});
    constexpr int kNumbers = 4096;
    std::map<std::pair<int, int>, std::vector<double>> radii;  // in the order of the number
    int last_cell = -1;
    std::set<int> cells_seen;
    for (int j = 0; j < kNumbers; ++j) {
      const auto smp = sampler.sample(f, (j + 0.5) / kNumbers, 0.3);
      const int cell = smp.axis * DiskProbeSampler::kMaxStrategies + smp.strategy;
      if (cell != last_cell) {
        EXPECT_TRUE(cells_seen.insert(cell).second) << name << ": one run per choice";
        last_cell = cell;
      }
      radii[{smp.axis, smp.strategy}].push_back(smp.disk_radius);
    }
    for (const auto& [choice, r] : radii) {
      const double share = sampler.axis_probability(choice.first) * sampler.strategy_probability(choice.second);
      EXPECT_NEAR(double(r.size()), share * kNumbers, 1.0)
          << name << " axis " << choice.first << " strategy " << choice.second;
      EXPECT_TRUE(std::is_sorted(r.begin(), r.end()))
          << name << " axis " << choice.first << " strategy " << choice.second;
    }
  }
}

// A sphere whose surface passes 0.02 R below P: segments often cross it twice, and
// every crossing counts. Bins in solid angle about the sphere's centre.
TEST(DiskProbe, EveryHitOnASphereCountsAndMatchesTheAreaPdf) {
  const ProbeFrame f = test_frame();
  const auto profiles = test_profiles();
  uint64_t seed = 200;
  for (int k : {0, 1}) {
    const auto& [name, profile, weights] = profiles[k];
    const DiskProbeSampler sampler(profile, weights);
    const double big = sampler.max_radius();
    const double radius = 0.6 * big;
    const Vec3d centre = f.p - f.n * (radius + 0.02 * big);
    const double dist = length(f.p - centre);
    const Framed about(f.n);  // polar axis from the centre towards P
    // Points of the sphere within `big` of P: cos theta >= c_min.
    const double c_min = std::max(-1.0, (radius * radius + dist * dist - big * big) / (2 * radius * dist));
    constexpr int kPolar = 12, kAzimuth = 8, kProbes = 100000;
    std::vector<double> cos_breaks;  // where |x - P| = R_i
    for (double r : radii(sampler)) cos_breaks.push_back((radius * radius + dist * dist - r * r) / (2 * radius * dist));
    auto point = [&](double cos_t, double phi) {
      const double sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
      return Vec3d(about.to_world(Vec3d(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t)));
    };
    std::vector<double> expected(kPolar * kAzimuth), observed(kPolar * kAzimuth, 0.0);
    double expected_hits = 0;
    for (int i = 0; i < kPolar; ++i)
      for (int j = 0; j < kAzimuth; ++j) {
        const double c0 = c_min + (1 - c_min) * i / kPolar, c1 = c_min + (1 - c_min) * (i + 1) / kPolar;
        const double p0 = 2 * kPiD * j / kAzimuth, p1 = 2 * kPiD * (j + 1) / kAzimuth;
        const double e = testing::integrate_capped(
            [&](double phi) {
              return integrate_pieces(
                  [&](double c) {
                    const Vec3d dir = point(c, phi);
                    return sampler.pdf_area(f, centre + dir * radius, dir) * radius * radius;
                  },
                  c0, c1, cos_breaks, 1e-10);
            },
            p0, p1, 1e-9);
        expected[i * kAzimuth + j] = e * kProbes;
        expected_hits += e;
      }
    Rng rng(++seed, 2);
    MeanAndError hits_per_probe;
    int double_hits = 0;
    for (int n = 0; n < kProbes; ++n) {
      const auto smp =
          sampler.sample(f, rng.uniform_double(), rng.uniform_double(), rng.uniform_double(), rng.uniform_double());
      Vec3d x[2];
      const int hits = testing::intersect_sphere(smp.segment, centre, radius, x);
      hits_per_probe.add(hits);
      double_hits += hits == 2;
      for (int h = 0; h < hits; ++h) {
        const Vec3d local = about.to_local(normalize(x[h] - centre));
        double phi = std::atan2(local.y, local.x);
        if (phi < 0) phi += 2 * kPiD;
        const int i = std::clamp(int((local.z - c_min) / (1 - c_min) * kPolar), 0, kPolar - 1);
        const int j = std::min(int(phi / (2 * kPiD) * kAzimuth), kAzimuth - 1);
        observed[i * kAzimuth + j] += 1;
      }
    }
    EXPECT_GT(double_hits, kProbes / 20) << name << ": the test needs segments with two crossings";
    EXPECT_NEAR(hits_per_probe.mean(), expected_hits, 4 * hits_per_probe.error()) << name;
    // Counts per bin are sums over crossings (Poisson-like); the total is checked above.
    const auto result = dermis::testing::chi_square(observed, expected);
    EXPECT_GT(result.p_value, dermis::testing::kChiSquareAlpha)
        << name << ": chi-square " << result.statistic << " dof " << result.dof;
  }
}

// sum_hits R(|x - P|) / pdf_area(x) on a plane through P averages to the energy of R
// within the largest sphere, int_0^R R(r) 2 pi r dr (adaptive quadrature), within 4 sigma.
TEST(DiskProbe, FlatPlaneEstimatorRecoversTheKeptEnergy) {
  const ProbeFrame f = test_frame();
  uint64_t seed = 300;
  for (const auto& [name, profile, weights] : test_profiles()) {
    for (auto axes : {ProbeAxisProbabilities{}, ProbeAxisProbabilities::single_axis()}) {
      const DiskProbeSampler sampler(profile, weights, axes);
      for (double tilt : {0.0, 0.7}) {
        const Vec3d n = tilted_normal(f, tilt);
        const TestPlane plane(f.p, n);
        MeanAndError estimate[3];
        Rng rng(++seed, 3);
        for (int k = 0; k < 20000; ++k) {
          const auto smp =
              sampler.sample(f, rng.uniform_double(), rng.uniform_double(), rng.uniform_double(), rng.uniform_double());
          Vec3d x;
          const bool hit = testing::intersect(smp.segment, plane, &x);
          for (int c = 0; c < 3; ++c)
            estimate[c].add(hit ? profile[c].eval(length(x - f.p)) / sampler.pdf_area(f, x, n) : 0.0);
        }
        for (int c = 0; c < 3; ++c) {
          const double kept = integrate_pieces([&](double r) { return 2 * kPiD * r * profile[c].eval(r); }, 0,
                                               sampler.max_radius(), {1e-6, 1e-4, 1e-2, 0.1, 1.0}, 1e-12);
          EXPECT_NEAR(estimate[c].mean(), kept, 4 * estimate[c].error())
              << name << (axes.normal == 1 ? " single axis" : " three axes") << " tilt " << tilt << " channel " << c
              << " kept/A " << kept / profile[c].albedo();
        }
      }
    }
  }
}

TEST(DiskProbe, RejectsBadWeights) {
  const ProfileRGB p = make_gaussian_rgb(RGB(0.5f), RGB(1.0f));
  EXPECT_THROW(DiskProbeSampler(p, RGB(0.0f)), std::invalid_argument);
  EXPECT_THROW(DiskProbeSampler(p, RGB(1.0f, -1.0f, 1.0f)), std::invalid_argument);
  EXPECT_THROW(DiskProbeSampler(p, RGB(1.0f), ProbeAxisProbabilities{0, 0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace dermis::sss
