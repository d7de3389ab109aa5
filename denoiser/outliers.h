// Firefly (outlier) detection before the regression, after Cycles' denoiser
// (filter_detect_outliers): a pixel of a half buffer whose luminance exceeds twice the 75th
// percentile of the luminances in its 5x5 neighbourhood (in the same half) is a candidate.
// Cycles then keeps a candidate as a legitimate highlight when its own sample variance says
// the reference is more than 3 sigma below it; here the per-pixel evidence is the other half,
// an independent estimate of the same pixel: the candidate is a legitimate highlight (an
// emissive detail, a specular glint every sample sees) when the other half is also above the
// reference and no less than 1/kHighlightRatio of it. A firefly is one rare, huge sample, so
// it lands in one half only and fails that test. Where fireflies are dense (rough metal walls
// lit by a small lamp: caustics), both halves of a pixel often hold one, of different sizes:
// the two halves then disagree by more than kHighlightRatio and the larger is an outlier; the
// smaller, confirmed only by that outlier, is one too (remove_outliers). Where they are
// denser still, both halves of a pixel catch one of about the same size (a caustic path's
// weight varies little): at 640x480 and 16 spp the shared CornellBox had 173 pixels over three
// times their denoised neighbourhood, each with both halves 5-15x their own references and
// within 1.5x of each other. There the pixel's own variance decides, as in Cycles: with the
// renderer's variance of each pixel's mean (DenoiseInput::variance), a confirmed candidate is
// a highlight only when the pixel's mean lies more than kHighlightSigmas standard deviations
// above the reference. A glint every sample sees has little variance; a pixel of 16 samples of
// which two are fireflies has a standard deviation about as large as its mean.
//
// What an outlier becomes (prepare_halves): its colour in that half is scaled down to the
// reference luminance (so that its NL-means guide does not make it dissimilar from everything)
// and it is marked not valid in that half, so it is data for no window, takes no part in the
// variance estimate or the selection's error estimate, and its pixel is reconstructed from its
// neighbours' fits. Each half is detected on its own colour and neighbourhood; the other half
// only vetoes at the same pixel, and the scaled value is the half's own reference, so the
// weights of one half's regression still come from the other half's colours alone.
//
// Energy: what an outlier loses is not dropped but given back to the valid pixels within
// kOutlierSpreadRadius, half to each half, in proportion to their luminance (prepare.cpp,
// spread_excess): a firefly's mean contribution stays in the frame as the brighter surroundings
// a converged render shows, not as one pixel, and both halves agree about it, so the regression
// takes it for light rather than noise. A noise-free image (equal halves) has no outliers: the
// other half always confirms.
//
// Measured at 16 spp against a 1,024 spp reference, four seeds (docs/performance.md, "Denoiser
// quality"): on the shared CornellBox (rough metal walls lit by a small lamp, 320x240) the
// denoised relMSE fell from 3.2-3.5e-2 (a looser confirmation, factor 4, and the outliers'
// light dropped) to 1.3-1.6e-2, below the undenoised 256 spp frame's 1.8e-2; on DamagedHelmet
// under the sunrise (320x180) the median stayed (3.04e-3 against 3.08e-3), single seeds moving
// by -7% to +23%.
//
// The selection's unfiltered candidate (denoiser/selection.h) keeps an outlier's colour as
// given, a glint that only one half happened to catch, unless the outlier exceeds its
// reference kImplausibleExcess-fold: then it takes the other half alone. Under relative
// error a pixel whose halves say 2.7 and 237 is far better served by the 2.7 unless the pixel
// is nearly certainly bright, and nothing in a 5x5 neighbourhood 25x darker says so; real
// glints that one half misses sit among bright neighbours and exceed their reference a few
// times (DamagedHelmet, docs/performance.md: the other half at every flagged pixel took
// 320x180 frames' relMSE 4-20% up; kept as given, a single 640x360 firefly 450x its
// reference took its frame's 5.7x up).
#pragma once

#include <algorithm>

#include "denoiser/planes.h"

namespace tessera::denoiser {

constexpr int kOutlierRadius = 2;  // the 5x5 neighbourhood of the reference
constexpr float kOutlierPercentile = 0.75f;
constexpr float kOutlierFactor = 2.0f;  // the reference is twice the percentile
constexpr float kHighlightRatio = 1.5f;  // the other half confirms when > the reference and > 1/1.5 of it
constexpr float kHighlightSigmas = 3.0f;  // the pixel's mean must exceed the reference by this many sigma
constexpr float kImplausibleExcess = 25.0f;  // see above: the unfiltered candidate takes the other half
constexpr int kOutlierSpreadRadius = 11;  // an outlier's lost colour goes to the 23x23 box about it

// Cycles' luminance for outliers: the channel mean of pixel i's colour clamped to non-negative.
inline float outlier_luminance(const Planes& c, std::size_t i) {
  return (std::max(c.at(0, i), 0.0f) + std::max(c.at(1, i), 0.0f) + std::max(c.at(2, i), 0.0f)) / 3.0f;
}

// Per pixel: 1 where `self` (3 channels) is an outlier given the other half `other`; `ref`
// receives the reference luminance (luminance: the mean over channels of max(0, c)) of every
// candidate, valid pixel above its reference, and 0 elsewhere.
// `valid` (1 per pixel, 0/1) are the pixels of `self` that hold data: others never are.
// Rows in parallel in the caller's arena; deterministic.
// `sigma` (1 per pixel, or empty: none known) is the standard deviation of the pixel's mean
// luminance (outlier_sigma).
std::vector<std::uint8_t> detect_outliers(const Planes& self, const Planes& other, const std::vector<float>& valid,
                                          const std::vector<float>& sigma, std::vector<float>& ref);

// Per pixel, from the variance of each channel's mean (3 per pixel; empty gives empty): the
// square root of their average, as Cycles takes it; 0 where not finite (nothing known).
std::vector<float> outlier_sigma(const std::vector<float>& variance);

}  // namespace tessera::denoiser
