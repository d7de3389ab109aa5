#include "renderer/sampling/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera {

int adaptive_min_spp(const AdaptiveSampling& adaptive, int spp) {
  const int automatic = static_cast<int>(std::ceil(16.0f / std::pow(adaptive.threshold, 0.3f)));
  const int wanted = adaptive.min_spp > 0 ? adaptive.min_spp : automatic;
  return std::min(spp, std::max(4, wanted));
}

std::vector<SampleWave> make_adaptive_waves(int spp, int min_spp) {
  std::vector<SampleWave> waves;
  for (const SampleWave& w : make_sample_waves(spp)) {
    if (w.begin < min_spp && min_spp < w.end) {
      waves.push_back({w.begin, min_spp});
      waves.push_back({min_spp, w.end});
    } else {
      waves.push_back(w);
    }
  }
  return waves;
}

double pixel_error(const glm::dvec3& mean, const glm::dvec3& odd_mean, std::uint32_t samples) {
  if (samples < 2) return std::numeric_limits<double>::infinity();
  const glm::dvec3 d = glm::abs(mean - odd_mean);
  const double s = mean.r + mean.g + mean.b;
  const double normalise = s < 1.0 ? std::sqrt(std::max(s, 0.0)) : s;
  return (d.r + d.g + d.b) / (0.0001 + normalise);
}

namespace {

// The pixel's own test, before the neighbourhood is considered.
bool quiet_enough(const FilmState& film, std::size_t i, const ConvergenceCheck& check) {
  const std::uint32_t n = film.samples[i];
  if (n < check.min_spp) return false;
  const glm::dvec3 mean = film.radiance[i] / static_cast<double>(n);
  const glm::dvec3 odd = film.radiance_odd[i] / static_cast<double>(n / 2);
  return pixel_error(mean, odd, n) < 5.0 * static_cast<double>(check.threshold);
}

}  // namespace

std::uint64_t check_convergence(FilmState& film, const ConvergenceCheck& check) {
  const int w = film.width, h = film.height;
  std::vector<std::uint8_t> quiet(film.pixel_count());
  for (std::size_t i = 0; i < quiet.size(); ++i) quiet[i] = quiet_enough(film, i, check);
  std::uint64_t converged = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      bool all = true;
      for (int yy = std::max(0, y - 1); yy <= std::min(h - 1, y + 1) && all; ++yy)
        for (int xx = std::max(0, x - 1); xx <= std::min(w - 1, x + 1) && all; ++xx)
          all = quiet[static_cast<std::size_t>(yy) * w + xx];
      film.converged[static_cast<std::size_t>(y) * w + x] = all;
      converged += all;
    }
  }
  film.checked_at = check.wave_end;
  return converged;
}

}  // namespace tessera
