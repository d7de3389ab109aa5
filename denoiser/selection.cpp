#include "denoiser/selection.h"

#include <algorithm>
#include <cmath>

namespace tessera::denoiser {

namespace {

constexpr float kRelativeEpsilon = 1e-2f;  // relMSE's: (x - ref)^2 / (ref^2 + 0.01)

// The weight of half A in a combination: each half weighs as its samples; a half without
// samples here still carries its neighbours' fit, so equal weights when neither has any.
float weight_a(const Halves& halves, std::size_t i) {
  const float na = halves.h[0].count[i], nb = halves.h[1].count[i];
  return na + nb > 0.0f ? na / (na + nb) : 0.5f;
}

// The candidates' colours, halves combined: the filtered ones, and the noisy colour where
// both halves hold data (elsewhere the unfiltered candidate is not offered).
Planes candidate(const Halves& halves, const Filtered& f, int cand) {
  const Planes& ref = halves.h[0].color;
  Planes out(ref.width, ref.height, 3);
  for (std::size_t i = 0; i < out.pixels(); ++i) {
    const float wa = weight_a(halves, i);
    for (int k = 0; k < 3; ++k)
      out.at(k, i) = cand == kUnfiltered ? wa * halves.h[0].color.at(k, i) + (1.0f - wa) * halves.h[1].color.at(k, i)
                                         : wa * f.filtered[0][cand].at(k, i) + (1.0f - wa) * f.filtered[1][cand].at(k, i);
  }
  return out;
}

}  // namespace

Selection select_and_combine(const Halves& halves, const Filtered& filtered, int radius, int blend_radius) {
  const Half& a = halves.h[0];
  const Half& b = halves.h[1];
  Planes colour[kCandidates];
  for (int c = 0; c < kCandidates; ++c) colour[c] = candidate(halves, filtered, c);
  const std::size_t n = a.valid.size();
  const int w = a.color.width, h = a.color.height;

  // Per pixel and candidate: the estimated squared error of one half's estimate, relative,
  // summed over channels, where both halves hold data (the box mean's mask).
  Planes err(w, h, kCandidates);
  std::vector<float> both(n);
  for (std::size_t i = 0; i < n; ++i) {
    both[i] = a.valid[i] * b.valid[i];
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
      e[kUnfiltered] += 0.5f * (va + vb) * inv;
    }
    for (int c = 0; c < kCandidates; ++c) err.at(c, i) = e[c];
  }
  Selection out{Planes(w, h, 3), std::vector<std::uint8_t>(n), box_mean(err, radius, &both)};

  // The choice: the least estimated error; the unfiltered colour only where both halves
  // hold data (a pixel with a firefly or a missing half is reconstructed by the filters).
  Planes chosen(w, h, kCandidates);
  for (std::size_t i = 0; i < n; ++i) {
    int best = 0;
    const int last = both[i] != 0.0f ? kUnfiltered : kUnfiltered - 1;
    for (int c = 1; c <= last; ++c)
      if (out.error.at(c, i) < out.error.at(best, i)) best = c;
    out.chosen[i] = static_cast<std::uint8_t>(best);
    chosen.at(best, i) = 1.0f;
  }
  // Blended in the proportions of the neighbourhood's choices; the unfiltered share of a
  // pixel that cannot take it goes to the filter it chose.
  const Planes share = box_mean(chosen, blend_radius);
  for (std::size_t i = 0; i < n; ++i) {
    float wt[kCandidates];
    for (int c = 0; c < kCandidates; ++c) wt[c] = share.at(c, i);
    if (both[i] == 0.0f) wt[out.chosen[i]] += wt[kUnfiltered], wt[kUnfiltered] = 0.0f;
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
