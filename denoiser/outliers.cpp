#include "denoiser/outliers.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace tessera::denoiser {

namespace {

std::vector<float> luminance(const Planes& c) {
  const std::size_t n = c.pixels();
  std::vector<float> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = outlier_luminance(c, i);
  return out;
}

}  // namespace

std::vector<float> outlier_sigma(const std::vector<float>& variance) {
  std::vector<float> sigma(variance.size() / 3);
  for (std::size_t i = 0; i < sigma.size(); ++i) {
    const float v = (variance[3 * i] + variance[3 * i + 1] + variance[3 * i + 2]) / 3.0f;
    sigma[i] = std::isfinite(v) && v > 0.0f ? std::sqrt(v) : 0.0f;
  }
  return sigma;
}

std::vector<std::uint8_t> detect_outliers(const Planes& self, const Planes& other, const std::vector<float>& valid,
                                          const std::vector<float>& sigma, std::vector<float>& ref) {
  const int w = self.width, h = self.height, r = kOutlierRadius;
  const std::vector<float> ls = luminance(self), lo = luminance(other);
  std::vector<std::uint8_t> out(self.pixels(), 0);
  ref.assign(self.pixels(), 0.0f);
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    float values[(2 * r + 1) * (2 * r + 1)];
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        const float l = ls[i], half_l = 0.5f * l;
        // l > 2 values[k] (k-th smallest) exactly when more than k values are below l / 2: a
        // count first (branch-free, cheap), the percentile itself only for the few candidates.
        int n = 0, below = 0;  // the window clipped to the image, centre included (as Cycles)
        for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy) {
          const float* row = ls.data() + static_cast<std::size_t>(yy) * w;
          for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx, ++n) below += row[xx] < half_l;
        }
        const int k = static_cast<int>(n * kOutlierPercentile);  // Cycles' index: 18 of 25
        if (!(valid[i] != 0.0f && below > k)) continue;
        n = 0;
        for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy)
          for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx)
            values[n++] = ls[static_cast<std::size_t>(yy) * w + xx];
        std::nth_element(values, values + k, values + n);
        const float reference = kOutlierFactor * values[k];
        ref[i] = reference;
        const float confirm = lo[i];
        const bool candidate = l > reference;  // true by the count; kept for clarity
        bool highlight = confirm > reference && kHighlightRatio * confirm >= l;
        // The halves' mean stands for the pixel's (equal halves up to one sample).
        if (highlight && !sigma.empty()) highlight = 0.5f * (l + confirm) - kHighlightSigmas * sigma[i] > reference;
        out[i] = candidate && !highlight ? 1 : 0;
      }
  });
  return out;
}

}  // namespace tessera::denoiser
