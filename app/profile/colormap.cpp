#include "app/profile/colormap.h"

#include <algorithm>

#include "imageio/image_codec.h"

namespace tessera {

std::vector<Colour> viridis(const std::vector<double>& t) {
  std::vector<float> clamped(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) clamped[i] = static_cast<float>(std::clamp(t[i], 0.0, 1.0));
  const std::vector<float> srgb = image_codec().color_map_srgb("viridis", clamped);
  std::vector<Colour> out(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) out[i] = {srgb[3 * i], srgb[3 * i + 1], srgb[3 * i + 2]};
  return out;
}

std::vector<Colour> viridis_ramp(int n) {
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i) t[i] = n > 1 ? double(i) / (n - 1) : 0.0;
  return viridis(t);
}

Colour category_colour(std::size_t index) {
  constexpr unsigned kColours[kCategoryColours] = {0x0072B2, 0xD55E00, 0x009E73, 0xCC79A7, 0xE69F00, 0x56B4E9};
  return hex_colour(kColours[index % kCategoryColours]);
}

}  // namespace tessera
