#include "dermis/sss/walk/walk_step.h"

namespace dermis::sss {

WalkSampling parse_walk_sampling(const std::string& text) {
  if (text == "classical") return WalkSampling::Classical;
  if (text == "dwivedi") return WalkSampling::Dwivedi;
  if (text == "mis") return WalkSampling::Mis;
  throw std::invalid_argument("walk sampling must be 'classical', 'dwivedi' or 'mis', got '" + text + "'");
}

const char* walk_sampling_name(WalkSampling sampling) {
  switch (sampling) {
    case WalkSampling::Classical:
      return "classical";
    case WalkSampling::Dwivedi:
      return "dwivedi";
    case WalkSampling::Mis:
      return "mis";
  }
  return "?";
}

double guided_choice_probability(WalkSampling sampling, double p_guided) {
  switch (sampling) {
    case WalkSampling::Classical:
      return 0.0;
    case WalkSampling::Dwivedi:
      return 1.0;
    case WalkSampling::Mis:
      if (!(p_guided >= 0 && p_guided <= 1))
        throw std::invalid_argument("guided sampling probability must be in [0, 1], got " + std::to_string(p_guided));
      return p_guided;
  }
  return 0.0;
}

}  // namespace dermis::sss
