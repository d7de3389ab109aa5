#include "denoiser/denoise.h"

#include <cmath>

#include <tbb/task_arena.h>

#include "denoiser/demodulate.h"
#include "denoiser/feature_filter.h"
#include "denoiser/prepare.h"
#include "denoiser/regression.h"
#include "denoiser/selection.h"

namespace tessera {

namespace {

using namespace denoiser;

DenoiseResult run(const DenoiseInput& in, const DenoiseParams& p) {
  Planes factor;
  if (p.demodulate) factor = demodulation_factor(in, p.demodulation_epsilon);
  Halves halves = p.demodulate ? prepare_halves(demodulated_colour(in, factor), p) : prepare_halves(in, p);
  const Features features = prepare_features(in, p, halves);
  const Planes filtered_features = prefilter_features(features, p.feature_radius, p.feature_bandwidth);
  std::vector<Filtered> passes{regress(halves, filtered_features, p.radius, p.stride, p)};
  if (p.wide_radius > 0) passes.push_back(regress(halves, filtered_features, p.wide_radius, p.wide_stride, p));
  if (p.demodulate) {  // the selection judges colour, as relMSE does
    remodulate(halves, factor);  // back to the colour as given
    // The filtered illumination times the prefiltered albedo: times the noisy one, every
    // candidate carried the albedo's noise (under depth of field and at edges, which surface
    // a pixel's samples saw) back in whole.
    const Planes filtered_factor = demodulation_factor(filtered_features, p.demodulation_epsilon);
    for (Filtered& filtered : passes)
      for (auto& half : filtered.filtered)
        for (Planes& candidate : half) remodulate(candidate, filtered_factor);
  }
  const Selection selection = select_and_combine(halves, passes, unfiltered_colour(in), p.selection_radius, p.selection_blend_radius,
                                                 p.half_variance_bias);

  const std::size_t n = selection.rgb.pixels();
  DenoiseResult out;
  out.rgb.resize(3 * n);
  out.variance.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      // Radiance is non-negative; a fit can undershoot next to an edge. Nothing non-finite
      // can reach here (inputs are sanitised), the test is a last guard.
      const float v = selection.rgb.at(k, i);
      out.rgb[3 * i + k] = std::isfinite(v) && v > 0.0f ? v : 0.0f;
    }
    // The variance of the noisy mean: var(A) nA^2 + var(B) nB^2 over (nA + nB)^2.
    const float na = halves.h[0].count[i], nb = halves.h[1].count[i];
    float var = 0.0f;
    for (int k = 0; k < 3; ++k)
      var += halves.h[0].variance.at(k, i) * na * na + halves.h[1].variance.at(k, i) * nb * nb;
    out.variance[i] = na + nb > 0.0f ? var / (3.0f * (na + nb) * (na + nb)) : 0.0f;
  }
  out.selected = selection.chosen;
  out.outliers.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    out.outliers[i] = static_cast<std::uint8_t>(halves.h[0].outlier[i] | (halves.h[1].outlier[i] << 1));
  return out;
}

}  // namespace

DenoiseResult denoise(const DenoiseInput& in, const DenoiseParams& p) {
  validate(in, p);
  if (p.threads == 0) return run(in, p);
  tbb::task_arena arena(p.threads);
  DenoiseResult out;
  arena.execute([&] { out = run(in, p); });
  return out;
}

}  // namespace tessera
