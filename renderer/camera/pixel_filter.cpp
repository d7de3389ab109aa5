#include "renderer/camera/pixel_filter.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "renderer/util/named_enum.h"

namespace tessera {
namespace {

// The profile from the centre out in bins of width/32768 pixel: its integral is exact to
// far below what the table's interpolation resolves.
constexpr int kProfileBins = 16384;

}  // namespace

const std::vector<std::string>& pixel_filter_names() {
  static const std::vector<std::string> names = {"box", "gaussian", "blackman-harris"};
  return names;
}

const char* pixel_filter_name(PixelFilterKind kind) { return enum_name(pixel_filter_names(), kind); }

PixelFilterKind parse_pixel_filter(const std::string& name) {
  return parse_enum<PixelFilterKind>(pixel_filter_names(), name, "pixel filter");
}

float default_filter_width(PixelFilterKind kind) { return kind == PixelFilterKind::box ? 1.0f : 1.5f; }

float filter_width(const PixelFilterParams& p) { return p.width > 0.0f ? p.width : default_filter_width(p.kind); }

std::string describe(const PixelFilterParams& p) {
  return fmt::format("{} {}", pixel_filter_name(p.kind), filter_width(p));
}

float pixel_filter_value(PixelFilterKind kind, float width, float x) {
  if (std::fabs(x) > 0.5f * width) return 0.0f;
  switch (kind) {
    case PixelFilterKind::box: return 1.0f;
    case PixelFilterKind::gaussian: {
      const float t = x * 6.0f / width;
      return std::exp(-2.0f * t * t);
    }
    case PixelFilterKind::blackman_harris: {
      const float t = 2.0f * kPi * (x / width + 0.5f);
      return 0.35875f - 0.48829f * std::cos(t) + 0.14128f * std::cos(2.0f * t) - 0.01168f * std::cos(3.0f * t);
    }
  }
  return 0.0f;
}

PixelFilter::PixelFilter(const PixelFilterParams& p) : box_(describe(p) == "box 1") {
  if (box_) return;
  const float half = 0.5f * filter_width(p);
  std::vector<double> cdf(kProfileBins + 1, 0.0);  // of the distance from the centre, at the bins' edges
  for (int i = 0; i < kProfileBins; ++i)
    cdf[i + 1] = cdf[i] + pixel_filter_value(p.kind, 2.0f * half, half * (i + 0.5f) / kProfileBins);
  // Invert the piecewise-linear CDF at v = 1 - (1 - s)^2, walking both in step.
  distance_.resize(kTableSize + 1);
  int bin = 0;
  for (int k = 0; k <= kTableSize; ++k) {
    const double s = static_cast<double>(k) / kTableSize;
    const double target = cdf.back() * (1.0 - (1.0 - s) * (1.0 - s));
    while (bin + 1 < kProfileBins && cdf[bin + 1] < target) ++bin;
    const double in_bin = cdf[bin + 1] > cdf[bin] ? (target - cdf[bin]) / (cdf[bin + 1] - cdf[bin]) : 0.0;
    distance_[k] = static_cast<float>(half * (bin + std::clamp(in_bin, 0.0, 1.0)) / kProfileBins);
  }
}

}  // namespace tessera
