// Denoising a rendered frame: its half buffers and features go to the denoiser, and the
// result becomes the frame's beauty, with the noisy beauty kept beside it (noisy.R/G/B).
// Shared by `tessera render --denoise` and `tessera denoise`.
#pragma once

#include <string>
#include <vector>

#include "denoiser/denoise.h"
#include "renderer/film/film.h"

namespace tessera {

// The EXR channels denoising needs: the beauty, the even and odd halves, albedo and normal.
const std::vector<std::string>& denoise_channels();

DenoiseInput denoise_input(const FrameImage& frame);

// The denoiser's parameters for a frame rendered with `sampler` (its name, as the EXR header
// gives it; empty: unknown, taken as the default sampler): the halves' variance correction
// is the Sobol sampler's, none for independent halves.
DenoiseParams denoise_params(int threads, const std::string& sampler);

// Replaces frame.rgb by the denoised beauty and keeps the noisy one in frame.noisy_rgb.
// Returns the seconds it took. `frame` must have every channel missing_denoise_channels asks.
double denoise_frame(FrameImage& frame, const DenoiseParams& params);

}  // namespace tessera
