#include "dermis/sss/walk/random_walk.h"

#include <stdexcept>
#include <string>

namespace dermis::sss {

MixtureWalkStep<3> make_walk_step(const WalkMedium& medium, const WalkSettings& settings) {
  auto fail = [](const std::string& m) { throw std::invalid_argument("random walk: " + m); };
  std::array<double, 3> sigma_t{}, albedo{};
  for (int c = 0; c < 3; ++c) {
    if (!(medium.sigma_t[c] > 0 && std::isfinite(medium.sigma_t[c])))
      fail("sigma_t = sigma_a + sigma_s must be positive and finite in every channel, got " +
           std::to_string(medium.sigma_t[c]));
    if (!(medium.sigma_s[c] >= 0 && medium.sigma_s[c] <= medium.sigma_t[c]))
      fail("need 0 <= sigma_s <= sigma_t in every channel, got sigma_s = " + std::to_string(medium.sigma_s[c]) +
           ", sigma_t = " + std::to_string(medium.sigma_t[c]));
    sigma_t[c] = medium.sigma_t[c];
    albedo[c] = std::min(1.0, double(medium.sigma_s[c]) / double(medium.sigma_t[c]));
  }
  if (settings.max_steps < 0) fail("max_steps must be >= 0, got " + std::to_string(settings.max_steps));
  if (!(settings.roulette_threshold > 0 && settings.roulette_threshold <= 1))
    fail("roulette_threshold must be in (0, 1], got " + std::to_string(settings.roulette_threshold));
  return MixtureWalkStep<3>(sigma_t, albedo, medium.g, guided_choice_probability(settings.sampling, settings.p_guided),
                            settings.channel_preference);
}

}  // namespace dermis::sss
