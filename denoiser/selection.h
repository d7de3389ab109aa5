// Choosing between the candidate filters per pixel (NFOR section 5): the error of filtered
// half A is estimated against the independent noisy half B, E[(F_A - B)^2] = MSE(F_A) + Var(B),
// so MSE(F_A) ~ (F_A - B)^2 - Var(B); symmetrically for F_B, averaged over a box because a
// single pixel's estimate is as noisy as the pixel.
#pragma once

#include "denoiser/regression.h"

namespace tessera::denoiser {

struct Selection {
  Planes rgb;  // 3 channels: the chosen candidate, halves combined by their sample counts
  std::vector<std::uint8_t> chosen;  // per pixel
};

Selection select_and_combine(const Halves& halves, const Filtered& filtered, int radius);

}  // namespace tessera::denoiser
