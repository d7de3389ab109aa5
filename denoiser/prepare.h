// From the caller's interleaved buffers to the denoiser's planar working set: the colour
// halves with their validity, sample counts and smoothed variances, the NL-means guides,
// and the features.
#pragma once

#include "denoiser/denoise.h"
#include "denoiser/planes.h"

namespace tessera::denoiser {

struct Half {
  Planes color;  // 3 channels; where this half is missing, the other half (or 0)
  std::vector<float> valid;  // 1 where this half has finite values, at least one sample and no outlier
  std::vector<std::uint8_t> outlier;  // 1 where this half's colour was a firefly (denoiser/outliers.h)
  std::vector<float> excess;  // where an outlier: its luminance over its reference (> 1); 0 elsewhere
  std::vector<float> count;  // its number of samples (1 each when the input gives none)
  Planes variance;  // 3: the variance of this half's mean, estimated from both halves, smoothed
  // 3: the same, one pixel's own estimate (1 degree of freedom, unbiased, 0 where a half is
  // missing): the selection averages it over its box together with the errors it corrects,
  // so a highlight's variance weighs there only in proportion (the relative error).
  Planes pixel_variance;
  // 3 + 3: the 3x3 mean of the range-compressed colour log(1 + c), and its variance
  Planes guide, guide_variance;
};

struct Halves {
  Half h[2];  // even, odd
};

// Throws std::invalid_argument on a size mismatch or a parameter out of range.
void validate(const DenoiseInput& in, const DenoiseParams& p);

Halves prepare_halves(const DenoiseInput& in, const DenoiseParams& p);

// The noisy colour as the caller gave it (fireflies included, not demodulated): the finite
// halves' mean weighted by their sample counts, the selection's unfiltered candidate.
struct Unfiltered {
  Planes rgb;  // 3 channels; 0 where `present` is 0
  std::vector<float> present;  // 1 where either half is finite and has samples
};

Unfiltered unfiltered_colour(const DenoiseInput& in);

struct Features {
  Planes values;  // albedo (3), normal (3), then depth (1) when given
  Planes variance;  // of the albedo and normal means (6); empty when the input has no feature halves
};

// The feature means, and their variance estimated from the feature halves when given.
Features prepare_features(const DenoiseInput& in, const DenoiseParams& p, const Halves& halves);

}  // namespace tessera::denoiser
