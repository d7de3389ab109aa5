// Albedo demodulation (as production denoisers do): the regression filters colour / (albedo +
// epsilon), the illumination, which is smooth where a texture is not, and the filtered result is
// multiplied back. A texture then no longer makes neighbouring pixels dissimilar for NL-means
// (so they are averaged) and its detail is restored by the factor: the prefiltered albedo's
// (denoiser/feature_filter.h), which keeps a texture's detail and drops the albedo's own noise
// (the noisy albedo's put that noise back into every filtered candidate: the grid of spheres'
// relMSE 8% higher, docs/performance.md). The dividing factor is the
// same for both halves, so it changes no half's independence; epsilon keeps black albedo (and
// the background, whose albedo is 0) finite: there the colour is only scaled. (Dividing each
// half by its own albedo half instead was measured worse: where one half's samples see the sky
// and the other's a surface, the halves differ 100x; docs/performance.md, Denoiser quality.)
#pragma once

#include "denoiser/prepare.h"

namespace tessera::denoiser {

// 3 channels: max(albedo, 0) + epsilon per pixel (non-finite albedo reads as 0).
Planes demodulation_factor(const DenoiseInput& in, float epsilon);
// The same from features whose first 3 channels are the albedo (the prefiltered features).
Planes demodulation_factor(const Planes& features, float epsilon);

// The colour halves and variances (and sample counts) of `in` divided by the factor (the
// variances by its square), every other field empty.
DenoiseInput demodulated_colour(const DenoiseInput& in, const Planes& factor);

// Halves prepared from demodulated colour, back in colour space: colour times the factor,
// variances times its square (the factor is a constant per pixel). Guides are left as they are.
void remodulate(Halves& halves, const Planes& factor);

// Each channel times the factor, in place.
void remodulate(Planes& colour, const Planes& factor);

}  // namespace tessera::denoiser
