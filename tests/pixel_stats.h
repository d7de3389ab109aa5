// The mean and spread over a rendered image's pixels of one channel: the closed-form render
// tests compare the mean with the closed form, within the noise the spread shows.
#pragma once

#include <cmath>
#include <cstddef>

#include "renderer/render/render.h"

namespace tessera::test {

struct PixelStats {
  double mean = 0.0, variance = 0.0;  // over pixels, of one channel
};

inline PixelStats stats_of(const FrameImage& img, int channel = 0) {
  const std::size_t n = img.rgb.size() / 3;
  PixelStats st;
  for (std::size_t i = 0; i < n; ++i) st.mean += img.rgb[3 * i + channel];
  st.mean /= n;
  for (std::size_t i = 0; i < n; ++i) st.variance += std::pow(img.rgb[3 * i + channel] - st.mean, 2);
  st.variance /= (n - 1);
  return st;
}

}  // namespace tessera::test
