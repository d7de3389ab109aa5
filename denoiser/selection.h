// Weighing the candidates per pixel (NFOR section 5, plus the unfiltered colour).
// The error of filtered half A is estimated against the independent noisy half B,
// E[(F_A - B)^2] = MSE(F_A) + Var(B), so MSE(F_A) ~ (F_A - B)^2 - Var(B); symmetrically for
// F_B. Candidate 0 is the noisy colour as given (not demodulated, and at a pixel the outlier
// test flagged, with its firefly: see offered() in selection.cpp; but an implausible firefly,
// denoiser/outliers.h, gives way to the other half alone), whose error is the
// variance of the halves' mean, wa^2 Var(A) + wb^2 Var(B): half a single half's for equal
// halves (it was compared as a single half's, which undervalued it 2x). A filtered half's
// error is kept as it is, an upper bound of the combined filter's (the halves share its bias).
// Var(A) and Var(B) are the halves' 1-dof estimates corrected for the sampler's
// anticorrelated halves (DenoiseParams::half_variance_bias).
// Errors are relative, (error) / (s^2 + 0.01) per channel with s the smallest candidate value
// (the denoiser's target, relMSE), so that a highlight's large absolute errors do not decide
// for the dark pixels in its box; they are averaged over a box because a single pixel's
// estimate is as noisy as the pixel (a per-pixel veto measured worse).
//
// The candidates are then blended, not chosen: each weighs 1 / error^2 (errors floored at a
// tenth of the unfiltered one's, as the box-mean estimates of good filters scatter around 0),
// and the weights are averaged over a small box so that no seam follows a change of choice.
// A hard choice threw away the unfiltered colour wherever a filter's noisy estimate came out
// lower; weighted, the glossy reflections no feature explains keep most of their noisy value.
#pragma once

#include "denoiser/regression.h"

namespace tessera::denoiser {

constexpr int kUnfiltered = 0;  // candidate 0; filter pass p, bandwidth b is 1 + 2 p + b
constexpr int kMaxCandidates = 5;  // two passes

struct Selection {
  Planes rgb;  // 3 channels: the blended candidates, halves combined by their sample counts
  std::vector<std::uint8_t> chosen;  // per pixel: the candidate of the largest blended weight
  Planes error;  // one channel per candidate: its estimated relative error (box mean)
};

// `passes`: the regressions' results (each two bandwidths), at least one; the halves' variance
// estimates are divided by half_variance_bias (DenoiseParams).
Selection select_and_combine(const Halves& halves, const std::vector<Filtered>& passes, const Unfiltered& noisy,
                             int radius, int blend_radius, float half_variance_bias);

}  // namespace tessera::denoiser
