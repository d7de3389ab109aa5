#include "app/colormap.h"

#include <algorithm>

#include <OpenImageIO/imagebufalgo.h>

namespace tessera {

std::vector<Colour> viridis(const std::vector<double>& t) {
  if (t.empty()) return {};
  const int n = static_cast<int>(t.size());
  OIIO::ImageBuf values(OIIO::ImageSpec(n, 1, 1, OIIO::TypeDesc::FLOAT));
  for (int i = 0; i < n; ++i) {
    const float v = static_cast<float>(std::clamp(t[i], 0.0, 1.0));
    values.setpixel(i, 0, &v, 1);
  }
  // OpenImageIO's maps are linear light, like its images; the chart wants sRGB.
  const OIIO::ImageBuf linear = OIIO::ImageBufAlgo::color_map(values, 0, "viridis");
  const OIIO::ImageBuf srgb = OIIO::ImageBufAlgo::colorconvert(linear, "linear", "sRGB");
  std::vector<Colour> out(n);
  for (int i = 0; i < n; ++i) {
    float c[3];
    srgb.getpixel(i, 0, c, 3);
    out[i] = {c[0], c[1], c[2]};
  }
  return out;
}

std::vector<Colour> viridis_ramp(int n) {
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i) t[i] = n > 1 ? double(i) / (n - 1) : 0.0;
  return viridis(t);
}

}  // namespace tessera
