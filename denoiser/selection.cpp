#include "denoiser/selection.h"

#include <algorithm>
#include <cmath>

namespace tessera::denoiser {

namespace {

constexpr float kRelativeEpsilon = 1e-2f;  // relMSE's: (x - ref)^2 / (ref^2 + 0.01)
// Each candidate's error is floored at this share of the unfiltered one's before weighing:
// it caps a filter's weight at 100x the unfiltered colour's. 0.05 to 0.2 measured alike.
constexpr float kErrorFloor = 0.1f;
constexpr float kTinyError = 1e-10f;  // the unfiltered error where the colour is noise-free

// The weight of half A in a combination: each half weighs as its samples; a half without
// samples here still carries its neighbours' fit, so equal weights when neither has any.
float weight_a(const Halves& halves, std::size_t i) {
  const float na = halves.h[0].count[i], nb = halves.h[1].count[i];
  return na + nb > 0.0f ? na / (na + nb) : 0.5f;
}

// A filtered candidate's colour, halves combined.
Planes combined(const Halves& halves, const Filtered& f, int cand) {
  Planes out(f.filtered[0][cand].width, f.filtered[0][cand].height, 3);
  for (std::size_t i = 0; i < out.pixels(); ++i) {
    const float wa = weight_a(halves, i);
    for (int k = 0; k < 3; ++k)
      out.at(k, i) = wa * f.filtered[0][cand].at(k, i) + (1.0f - wa) * f.filtered[1][cand].at(k, i);
  }
  return out;
}

// Per pixel and candidate: the estimated relative squared error, summed over channels.
Planes pixel_errors(const Halves& halves, const Filtered& filtered, const Planes (&colour)[kCandidates]) {
  const Half& a = halves.h[0];
  const Half& b = halves.h[1];
  Planes err(a.color.width, a.color.height, kCandidates);
  for (std::size_t i = 0; i < err.pixels(); ++i) {
    const float wa = weight_a(halves, i), wb = 1.0f - wa;
    float e[kCandidates] = {0.0f, 0.0f, 0.0f};
    for (int k = 0; k < 3; ++k) {
      float s = colour[0].at(k, i);
      for (int c = 1; c < kCandidates; ++c) s = std::min(s, colour[c].at(k, i));
      s = std::max(s, 0.0f);
      const float inv = 1.0f / (s * s + kRelativeEpsilon);
      const float va = a.pixel_variance.at(k, i), vb = b.pixel_variance.at(k, i);
      for (int c = 0; c < kUnfiltered; ++c) {
        const float da = filtered.filtered[0][c].at(k, i) - b.color.at(k, i);
        const float db = filtered.filtered[1][c].at(k, i) - a.color.at(k, i);
        e[c] += 0.5f * (da * da - vb + db * db - va) * inv;
      }
      e[kUnfiltered] += (wa * wa * va + wb * wb * vb) * inv;
    }
    for (int c = 0; c < kCandidates; ++c) err.at(c, i) = e[c];
  }
  return err;
}

// Whether the noisy colour is a candidate at pixel i: where it exists and its box holds an
// estimate; and where a half was taken out as a firefly (or is missing), only if that
// estimate is the least: a legitimate glint keeps its value where the neighbourhood says the
// filters are worse, and a firefly on a surface the filters explain gets no weight at all.
bool offered(const Unfiltered& noisy, const Planes& estimated, const std::vector<float>& both, const Planes& error,
             std::size_t i) {
  if (noisy.present[i] == 0.0f || estimated.at(0, i) == 0.0f) return false;
  if (both[i] != 0.0f) return true;
  const float e = error.at(kUnfiltered, i);
  return e < error.at(0, i) && e < error.at(1, i);
}

}  // namespace

Selection select_and_combine(const Halves& halves, const Filtered& filtered, const Unfiltered& noisy, int radius,
                             int blend_radius) {
  const Half& a = halves.h[0];
  const Half& b = halves.h[1];
  const Planes colour[kCandidates] = {combined(halves, filtered, 0), combined(halves, filtered, 1), noisy.rgb};
  const std::size_t n = a.valid.size();
  const int w = a.color.width, h = a.color.height;

  // The estimates hold where both halves hold data; a pixel without (a firefly, a missing
  // half) takes its box's.
  std::vector<float> both(n);
  for (std::size_t i = 0; i < n; ++i) both[i] = a.valid[i] * b.valid[i];
  Planes both_plane(w, h, 1);
  both_plane.data = both;
  const Planes estimated = box_mean(both_plane, radius);
  Selection out{Planes(w, h, 3), std::vector<std::uint8_t>(n),
                box_mean(pixel_errors(halves, filtered, colour), radius, &both)};

  // Weights relative to the unfiltered colour's, so they lie in [0, 1 / kErrorFloor^2] and
  // the box sums stay exact (1 / error^2 spans too many decades for a running sum).
  Planes weight(w, h, kCandidates);
  for (std::size_t i = 0; i < n; ++i) {
    const float unfiltered = std::max(out.error.at(kUnfiltered, i), kTinyError);
    for (int c = 0; c < kCandidates; ++c) {
      const float ratio = unfiltered / std::max(out.error.at(c, i), kErrorFloor * unfiltered);
      weight.at(c, i) = std::isfinite(ratio) ? ratio * ratio : 0.0f;  // NaN, inf: no weight
    }
  }
  const Planes blended = box_mean(weight, blend_radius);
  for (std::size_t i = 0; i < n; ++i) {
    float wt[kCandidates];
    for (int c = 0; c < kCandidates; ++c) wt[c] = blended.at(c, i);
    if (!offered(noisy, estimated, both, out.error, i)) wt[kUnfiltered] = 0.0f;
    if (!(wt[0] + wt[1] + wt[2] > 0.0f)) wt[0] = wt[1] = 1.0f;  // no usable estimate: the filters alike
    int best = 0;
    for (int c = 1; c < kCandidates; ++c)
      if (wt[c] > wt[best]) best = c;
    out.chosen[i] = static_cast<std::uint8_t>(best);
    const float total = wt[0] + wt[1] + wt[2];
    for (int k = 0; k < 3; ++k) {
      float v = 0.0f;
      for (int c = 0; c < kCandidates; ++c) v += wt[c] * colour[c].at(k, i);
      out.rgb.at(k, i) = v / total;
    }
  }
  return out;
}

}  // namespace tessera::denoiser
