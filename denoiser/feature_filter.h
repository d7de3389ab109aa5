// Feature prefiltering (NFOR section 4.2): the features are Monte Carlo estimates too (depth of
// field, anti-aliased edges, rough first hits), and regressing on noisy features biases the
// fit, so they are first smoothed by NL-means guided by their own half-buffer variance.
#pragma once

#include "denoiser/prepare.h"

namespace tessera::denoiser {

// NL-means over a (2 radius + 1)^2 window with 3x3 patch means. One weight per pixel pair:
// the larger of the normalised albedo and normal distances, so an edge in either keeps the
// pixels apart. Depth (no halves, so no variance) passes through unfiltered. Rows run in parallel in the caller's arena;
// every output pixel is a gather in a fixed order, so the result does not depend on threads.
Planes prefilter_features(const Features& f, int radius, float bandwidth);

}  // namespace tessera::denoiser
