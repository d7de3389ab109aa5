// Adaptive sampling as Cycles does it: between sample waves, a pixel whose estimated
// relative error is below the threshold stops taking samples, unless a neighbour is still
// noisy. The decision reads only the film, at fixed points (after each whole wave), so it
// is the same for any thread count, tile size, scheduler, and after --resume.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/film/film.h"
#include "renderer/parallel/tile_scheduler.h"

namespace tessera {

struct AdaptiveSampling {
  float threshold = 0.0f;  // --noise-threshold; 0: off, every pixel gets spp
  int min_spp = 0;  // --min-spp; 0: automatic, as Cycles
  bool on() const { return threshold > 0.0f; }
};

// The fewest samples before a pixel may stop: --min-spp, or Cycles' automatic
// max(4, ceil(16 / threshold^0.3)) (threshold 0.1 -> 32, 0.01 -> 64, 0.001 -> 128); at least
// 4, as in Cycles (the odd half needs samples), at most spp.
int adaptive_min_spp(const AdaptiveSampling& adaptive, int spp);

// The sample waves of an adaptive render: make_sample_waves(spp) with one more boundary at
// the minimum, so that a pixel can stop exactly there.
std::vector<SampleWave> make_adaptive_waves(int spp, int min_spp);

// Cycles' per-pixel error (film_adaptive_sampling_convergence_check): with I the mean of all
// samples and A the mean of the odd-numbered ones,
//   error = (|I.r - A.r| + |I.g - A.g| + |I.b - A.b|) / (0.0001 + d),  s = I.r + I.g + I.b,
//   d = sqrt(s) when s < 1 (noise matters most in the darks), else s.
// Cycles' A is 2 x (odd sum) / n, the odd mean when n is even; tessera's waves end at odd
// counts too, so it takes the odd mean itself. Infinite below 2 samples (no odd half yet).
double pixel_error(const glm::dvec3& mean, const glm::dvec3& odd_mean, std::uint32_t samples);

struct ConvergenceCheck {
  float threshold = 0.0f;  // the user's; Cycles compares the error with 5 x threshold
  std::uint32_t min_spp = 4;
  std::uint32_t wave_end = 0;  // the sample count the wave just finished reached: stored as checked_at
};

// Sets film.converged from the film alone: a pixel converges when it has min_spp samples
// and its error is below 5 x threshold, and so does every pixel of its 3x3 neighbourhood
// (Cycles' filter_x/filter_y: a pixel beside a noisy one keeps going). A converged pixel
// took no samples since, so it stays converged unless a neighbour turned noisy; then it
// catches up with its neighbours. Returns how many pixels converged.
std::uint64_t check_convergence(FilmState& film, const ConvergenceCheck& check);

}  // namespace tessera
