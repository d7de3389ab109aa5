#include "denoiser/selection.h"

namespace tessera::denoiser {

namespace {

// The estimated squared error (summed over channels) of one candidate, averaged over the box.
Planes estimated_error(const Halves& halves, const Filtered& f, int cand, int radius) {
  const Half& a = halves.h[0];
  const Half& b = halves.h[1];
  const Planes& fa = f.filtered[0][cand];
  const Planes& fb = f.filtered[1][cand];
  const std::size_t n = fa.pixels();
  Planes err(fa.width, fa.height, 1);
  std::vector<float> both(n);
  for (std::size_t i = 0; i < n; ++i) {
    both[i] = a.valid[i] * b.valid[i];
    float e = 0.0f;
    for (int k = 0; k < 3; ++k) {
      const float da = fa.at(k, i) - b.color.at(k, i), db = fb.at(k, i) - a.color.at(k, i);
      e += da * da - b.variance.at(k, i) + db * db - a.variance.at(k, i);
    }
    err.at(0, i) = 0.5f * e;
  }
  return box_mean(err, radius, &both);
}

}  // namespace

Selection select_and_combine(const Halves& halves, const Filtered& filtered, int radius) {
  const Planes e0 = estimated_error(halves, filtered, 0, radius);
  const Planes e1 = estimated_error(halves, filtered, 1, radius);
  const std::size_t n = e0.pixels();
  Selection out{Planes(e0.width, e0.height, 3), std::vector<std::uint8_t>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    const int c = e1.at(0, i) < e0.at(0, i) ? 1 : 0;
    out.chosen[i] = static_cast<std::uint8_t>(c);
    // Each half weighs as its samples; a half without samples here still carries its
    // neighbours' fit, so equal weights when neither has any.
    const float na = halves.h[0].count[i], nb = halves.h[1].count[i];
    const float wa = na + nb > 0.0f ? na / (na + nb) : 0.5f;
    for (int k = 0; k < 3; ++k)
      out.rgb.at(k, i) = wa * filtered.filtered[0][c].at(k, i) + (1.0f - wa) * filtered.filtered[1][c].at(k, i);
  }
  return out;
}

}  // namespace tessera::denoiser
