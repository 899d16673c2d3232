#include "dermis/sss/profiles/profile.h"

namespace dermis::sss {

ProfileRGB make_burley_rgb(RGB albedo, RGB mean_free_path, BurleyParameterisation p) {
  ProfileRGB rgb;
  for (int c = 0; c < 3; ++c) rgb.channel[c] = BurleyProfile(albedo[c], mean_free_path[c], p);
  return rgb;
}

ProfileRGB make_dipole_rgb(RGB albedo, RGB mean_free_path, double eta) {
  ProfileRGB rgb;
  for (int c = 0; c < 3; ++c) rgb.channel[c] = DipoleProfile::from_albedo(albedo[c], mean_free_path[c], eta);
  return rgb;
}

ProfileRGB make_dipole_rgb_from_coefficients(RGB sigma_a, RGB sigma_s, double g, double eta) {
  ProfileRGB rgb;
  for (int c = 0; c < 3; ++c) rgb.channel[c] = DipoleProfile::from_coefficients(sigma_a[c], sigma_s[c], g, eta);
  return rgb;
}

ProfileRGB make_cubic_rgb(RGB albedo, RGB radius) {
  ProfileRGB rgb;
  for (int c = 0; c < 3; ++c) rgb.channel[c] = CubicProfile(radius[c], albedo[c]);
  return rgb;
}

ProfileRGB make_gaussian_rgb(RGB albedo, RGB variance) {
  ProfileRGB rgb;
  for (int c = 0; c < 3; ++c) rgb.channel[c] = GaussianProfile(variance[c], albedo[c]);
  return rgb;
}

ProfileRGB make_skin_rgb(double scene_units_per_mm, RGB albedo) {
  const auto skin = skin_sum_of_gaussians(scene_units_per_mm, albedo);
  ProfileRGB rgb;
  for (int c = 0; c < 3; ++c) rgb.channel[c] = skin[c];
  return rgb;
}

ProfileRGB make_tabulated_rgb(const std::shared_ptr<const ProfileTable>& table, RGB albedo, RGB mean_free_path) {
  ProfileRGB rgb;
  for (int c = 0; c < 3; ++c) rgb.channel[c] = TabulatedProfile(table, albedo[c], mean_free_path[c]);
  return rgb;
}

ProfileFamily dipole_family(double eta) {
  dipole_boundary_a(eta);  // validates eta now rather than per node
  return [eta](double albedo) {
    const DipoleProfile p = DipoleProfile::from_albedo(albedo, 1.0, eta);
    return RadialFunction([p](double r) { return p.eval(r); });
  };
}

ProfileFamily burley_family(BurleyParameterisation param) {
  return [param](double albedo) {
    const BurleyProfile p(albedo, 1.0, param);
    return RadialFunction([p](double r) { return p.eval(r); });
  };
}

}  // namespace dermis::sss
