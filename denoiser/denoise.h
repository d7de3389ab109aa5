// A feature-guided regression denoiser of the NFOR family (Bitterli et al. 2016, "Nonlinearly
// Weighted First-order Regression for Denoising Monte Carlo Renderings"): in a window around
// each pixel, colour is regressed linearly on the features (constant, screen position, albedo,
// normal, depth) with NL-means weights computed from the noisy colour. The features are first
// prefiltered (NL-means guided by their half-buffer variance); each half buffer is regressed
// with weights computed from the other one (cross-filtering), so the noise of the weights is
// independent of the data. The NL-means distances compare log(1 + colour), with variances
// estimated in that range: a bright, noisy highlight is then far from a dark, quiet pixel
// (compared linearly, its variance made it "similar" to everything, and its energy leaked
// into dark neighbours' fits as halos). The colour is regressed demodulated, divided by the
// albedo plus epsilon (denoiser/demodulate.h), and multiplied back, by the prefiltered albedo,
// before the selection. Two
// candidate bandwidths are run in each of two window sizes (9x9 and 17x17); per pixel, the
// four and the unfiltered colour are blended by the inverse square of the relative error the
// half buffers estimate (denoiser/selection.h).
//
// Before all that, fireflies are taken out of each half buffer (denoiser/outliers.h, after
// Cycles' denoiser): a pixel brighter than twice the 75th percentile of its 5x5 neighbourhood
// that the other half does not confirm, or (given each pixel's variance) whose mean lies
// within 3 standard deviations of that reference, is scaled down to that reference for the
// weights and is data for no window; the light it loses is given back to the valid pixels
// around it, in both halves. The selection may still keep the noisy colour at such a pixel
// (denoiser/selection.cpp, offered()), but not a firefly 25x its reference (the other half
// stands for the noisy colour there: kImplausibleExcess in denoiser/outliers.h).
// Each window's fit is bounded by the range of the colours it was fitted to, so no window
// extrapolates.
//
// A plain image-processing library: Eigen, TBB and the standard library only.
#pragma once

#include <cstdint>
#include <vector>

namespace tessera {

// Every vector is row-major, top row first, 3 floats per pixel (depth and samples: 1).
// Non-finite values are treated as missing: a colour half that is not finite at a pixel is
// left out there (the other half stands in; a pixel with neither is reconstructed from its
// neighbours), and a non-finite feature value is read as 0 (what the renderer writes where
// no sample hit). The output never holds a non-finite value.
struct DenoiseInput {
  int width = 0, height = 0;
  std::vector<float> color_even, color_odd;  // means of the even- and odd-numbered samples
  std::vector<float> albedo, normal;  // first-hit feature means
  // Feature half buffers; empty: the features are used as they are (no prefilter).
  std::vector<float> albedo_even, albedo_odd, normal_even, normal_odd;
  std::vector<float> depth;  // optional
  // Optional per-pixel sample count (adaptive sampling gives pixels different counts): the
  // even half holds ceil(n/2) samples, the odd half floor(n/2). Empty: equal halves.
  std::vector<float> samples;
  // Optional, 3 per pixel: the variance of each pixel's mean, estimated from its samples
  // (the renderer's variance.R/G/B). With it a pixel whose halves agree is still a firefly
  // when its mean lies within 3 standard deviations of its neighbourhood (denoiser/outliers.h).
  std::vector<float> variance;
};

struct DenoiseParams {
  int threads = 0;  // 0: all cores (TBB's default concurrency)
  // Regression window (2 radius + 1)^2 pixels, centres every `stride` pixels (collaborative:
  // each solve reconstructs its whole window); stride must be at most radius + 1. 4 and 3
  // cost the same time as 6 and 4 (each centre's window is 2.1x smaller, there are 1.8x more
  // centres); with demodulation they measured lower relMSE on all three scenes of
  // docs/performance.md (without it, 4 and 3 made DamagedHelmet worse), though the Cornell
  // box's edges got worse.
  int radius = 4;
  int stride = 3;
  // A second regression with larger windows (0: none), whose two bandwidths are two more
  // candidates for the selection: flat, noisy regions (the Cornell box's walls) keep a
  // low-frequency residue through 9x9 windows that 17x17 ones average away, and the
  // selection takes them only where their estimated error is lower. Radius 8, stride 6 costs
  // less than 4 and 3 (fewer centres).
  int wide_radius = 8;
  int wide_stride = 6;
  // The candidate NL-means bandwidths k: a strict one for detail, a wide one for smooth
  // regions (the unfiltered colour covers where both filters err: 0.35 and 2 measured lower
  // relMSE than NFOR's 0.5 and 1 on the Cornell box, DamagedHelmet and the grid of spheres).
  float bandwidths[2] = {0.35f, 2.0f};
  int feature_radius = 3;  // feature prefilter window: (2 r + 1)^2 pixels; 0: no prefilter
  float feature_bandwidth = 1.0f;
  int variance_radius = 2;  // the 1-dof per-pixel variance is averaged over (2 r + 1)^2 pixels
  int selection_radius = 3;  // the estimated error of each candidate is averaged likewise
  int selection_blend_radius = 3;
  // The per-pixel variance of a half from the two, (A - B)^2 / (1/nA + 1/nB), assumes
  // independent halves; tessera's default Sobol sampler stratifies even and odd samples
  // together, so they are anticorrelated and it reads high: 1.27-1.30x each half's true error
  // at 16 spp on the three scenes of docs/performance.md. Divided by this (1.1 to 1.28
  // measured: higher favours DamagedHelmet and the grid, lower the Cornell box), the noisy
  // colour's error is not overstated nor the filters' (which subtract it) understated. 1 for
  // independent halves: the app takes it from the frame's sampler (denoise_params in app/frame/frame_denoise.h).
  float half_variance_bias = 1.15f;  // each pixel blends the candidates' weights over its (2 r + 1)^2 box
  // Albedo demodulation (denoiser/demodulate.h): the regression filters colour / (albedo +
  // epsilon). 0.1 rather than 0.01: at an edge or under depth of field the mean albedo is noisy
  // and a small epsilon lets that noise divide the colour (the grid of spheres 3.1e-3 at 0.1,
  // 4.4e-3 at 0.001); 0.05 to 0.3 measured alike.
  bool demodulate = true;
  float demodulation_epsilon = 0.1f;
  float ridge = 1e-3f;  // Tikhonov term on the feature coefficients, relative to the weight sum
};

struct DenoiseResult {
  std::vector<float> rgb;  // 3 per pixel, finite, non-negative
  std::vector<std::uint8_t> selected;  // 1 per pixel: the candidate of the largest weight, 0 the unfiltered colour, 1 + 2 pass + bandwidth a filter
  std::vector<float> variance;  // 1 per pixel: the estimated variance of the noisy mean colour (channel average), fireflies excluded
  std::vector<std::uint8_t> outliers;  // 1 per pixel: bit 0 the even half was a firefly there, bit 1 the odd half
};

// Throws std::invalid_argument when a size does not match width x height, the colour halves
// or the albedo and normal are missing, or a parameter is out of range.
DenoiseResult denoise(const DenoiseInput& in, const DenoiseParams& params);

}  // namespace tessera
