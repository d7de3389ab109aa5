// Choosing between the candidates per pixel (NFOR section 5, plus the unfiltered colour).
// The error of filtered half A is estimated against the independent noisy half B,
// E[(F_A - B)^2] = MSE(F_A) + Var(B), so MSE(F_A) ~ (F_A - B)^2 - Var(B); symmetrically for
// F_B. The third candidate is the noisy colour itself, whose error is its variance: where
// every filter's estimated error exceeds it (beside a highlight, on a detail no feature
// explains) the pixel keeps its noisy value. Errors are relative, (error) / (s^2 + 0.01) per
// channel with s the smallest candidate value (the denoiser's target, relMSE), so that a
// highlight's large absolute errors do not decide for the dark pixels in its box; they are
// averaged over a box because a single pixel's estimate is as noisy as the pixel. The choice
// is then smoothed: each pixel blends the candidates in the proportions they were chosen in
// its (2 blend + 1)^2 neighbourhood, so no seam follows the boundary of a choice.
#pragma once

#include "denoiser/regression.h"

namespace tessera::denoiser {

constexpr int kCandidates = 3;  // the two bandwidths, then the unfiltered colour
constexpr int kUnfiltered = 2;

struct Selection {
  Planes rgb;  // 3 channels: the blended candidates, halves combined by their sample counts
  std::vector<std::uint8_t> chosen;  // per pixel: the candidate of least estimated error
  Planes error;  // kCandidates channels: each candidate's estimated relative error (box mean)
};

Selection select_and_combine(const Halves& halves, const Filtered& filtered, int radius, int blend_radius);

}  // namespace tessera::denoiser
