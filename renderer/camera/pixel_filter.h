// The pixel reconstruction filter, by filter importance sampling (Ernst et al. 2006, as Cycles
// and pbrt-v4 do it): each camera sample lands at an offset from the pixel centre drawn in
// proportion to the filter, and counts in that pixel alone with weight 1. A pixel's value is
// then the filter-weighted average of the image around it, each sample still belongs to one
// pixel (tiles, resume and adaptive sampling are untouched), and the filter's tails cost no
// extra variance. Non-negative separable filters only: f(x, y) = f(x) f(y).
//   box:             width 1 by default: the pixel's own square, the offset the raw jitter.
//   gaussian:        exp(-2 (6x/width)^2), Cycles' form (sigma = width / 12).
//   blackman-harris: Cycles' default (width 1.5): a bell with nearly no tails, less aliasing
//                    and less edge noise than the box at the same sharpness.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/util/math.h"

namespace tessera {

enum class PixelFilterKind : std::uint8_t { box, gaussian, blackman_harris };

const std::vector<std::string>& pixel_filter_names();
const char* pixel_filter_name(PixelFilterKind kind);
PixelFilterKind parse_pixel_filter(const std::string& name);  // throws std::invalid_argument

struct PixelFilterParams {
  PixelFilterKind kind = PixelFilterKind::blackman_harris;
  float width = 0.0f;  // pixels, the filter's whole support; 0 = its default (box 1, others 1.5)
};

float default_filter_width(PixelFilterKind kind);
float filter_width(const PixelFilterParams& p);  // the width in effect
// How far from its pixel's centre a sample can land, in pixels (half the width; the box of
// width 1 reaches its square's edges).
inline float filter_reach(const PixelFilterParams& p) { return std::max(0.5f, 0.5f * filter_width(p)); }
std::string describe(const PixelFilterParams& p);  // "blackman-harris 1.5": headers and resume

// The filter's 1D profile at x (pixels from the centre, |x| <= width / 2); not normalised.
float pixel_filter_value(PixelFilterKind kind, float width, float x);

class PixelFilter {
 public:
  explicit PixelFilter(const PixelFilterParams& p);
  // Where in pixel (x, y) the sample with the 2D draw u falls: (x, y) + the result, the
  // pixel's square being [0,1)^2 (so the box of width 1 returns u unchanged).
  vec2 sample(const vec2& u) const { return box_ ? u : vec2(sample_1d(u.x), sample_1d(u.y)); }

 private:
  // The filters are symmetric: the sign from which half u is in, the distance from the
  // centre from v = |2u - 1| through the table, read at s = 1 - sqrt(1 - v) so that its
  // points crowd into the tails, where the profile's mass thins out.
  float sample_1d(float u) const {
    const float v = std::fabs(2.0f * u - 1.0f);
    const float t = (1.0f - std::sqrt(1.0f - v)) * static_cast<float>(kTableSize);
    const int i = std::min(static_cast<int>(t), kTableSize - 1);
    const float r = distance_[i] + (t - static_cast<float>(i)) * (distance_[i + 1] - distance_[i]);
    return u < 0.5f ? 0.5f - r : 0.5f + r;
  }
  // 4097 floats (16 KiB) stay in cache beside the BVH; a uniform 64K-point table of the
  // whole CDF, as accurate, cost 4% of a simple scene's render in cache misses.
  static constexpr int kTableSize = 4096;
  bool box_;
  std::vector<float> distance_;  // from the centre, at s = k / kTableSize
};

}  // namespace tessera
