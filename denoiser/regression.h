// The NFOR regression: in the window of every centre (on a strided grid), colour is fitted as
// a linear function of the features by weighted least squares, and the fit is evaluated at
// every pixel of the window (collaborative regression); each pixel averages the fits of the
// windows that cover it, weighted by its weight in each.
#pragma once

#include "denoiser/prepare.h"

namespace tessera::denoiser {

// The filtered colour of each half for each candidate bandwidth: filtered[half][candidate],
// 3 channels. Half h is regressed with weights computed from the other half (cross-filtering).
struct Filtered {
  Planes filtered[2][2];
};

// Windows of (2 radius + 1)^2 pixels centred every `stride` pixels (the rest of the
// parameters from p). Runs in the caller's arena; the result does not depend on the number
// of threads.
Filtered regress(const Halves& halves, const Planes& features, int radius, int stride, const DenoiseParams& p);

}  // namespace tessera::denoiser
